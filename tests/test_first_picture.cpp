// A shadow in the first picture (scene/first_picture.h): the view's cast shadow counted exactly
// on scenes laid out on the probe's grid under every light type; the default light moved only
// when its shadow is out of view; a ground added where nothing receives a shadow and nowhere
// else; levels lit by their own bulbs seen from near them. The hierarchy it casts with:
// test_ray_cast.cpp.
#include "generated_scenes.h"
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "scene/first_picture.h"
#include "scene/gltf_loader.h"
#include "scene/interior.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A ground of 80 x 60 and a square plate of 8 x 8 at height `height`, its edges on whole units:
// from straight above, an orthographic view 64 x 36 units wide sees each unit square as one of
// the probe's 64 x 36 pixels, sampled at its centre, so that shadows with whole-unit edges are
// counted exactly.
Scene plateOverGround(float height) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("m", glm::vec3(0.6f));
    mb.quad({-40, 0, 30}, {40, 0, 30}, {40, 0, -30}, {-40, 0, -30}, m);
    mb.quad({-10, height, 4}, {-2, height, 4}, {-2, height, -4}, {-10, height, -4}, m);
    scene.cameras.push_back({.name = "above",
                             .position = {0, 50, 0},
                             .target = {0, 0, 0},
                             .up = {0, 0, -1},
                             .orthographic = true,
                             .ymag = 18.0f,
                             .znear = 1.0f,
                             .zfar = 100.0f});
    return scene;
}

ViewShadow measured(const Scene& scene, const Light& light) {
    const TriangleBvh bvh(scene);
    return ViewProbe(scene, bvh, scene.cameras.front()).measure(light);
}

// A warehouse: a closed shell facing out (an exterior by the measure, a level by its shape),
// crates on its floor, two bulbs under its roof.
Scene warehouse() {
    Scene s;
    s.name = "warehouse";
    MeshBuilder mb(s);
    const uint32_t m = mb.material("m", glm::vec3(0.6f));
    mb.box(boxAt({0, 3, 0}, {40, 6, 30}), m);
    mb.quad({-19.9f, 0.01f, 14.9f}, {19.9f, 0.01f, 14.9f}, {19.9f, 0.01f, -14.9f},
            {-19.9f, 0.01f, -14.9f}, m);
    for (int i = 0; i < 6; ++i)
        mb.box(boxAt({-12.0f + 5.0f * static_cast<float>(i), 0.75f, i % 2 ? 4.0f : -4.0f},
                     glm::vec3(1.5f)),
               m);
    s.lights = {{.name = "a", .type = LightType::Point, .position = {-8, 5, 0}, .intensity = 50},
                {.name = "b", .type = LightType::Point, .position = {8, 5, 0}, .intensity = 50}};
    return s;
}

// The scene's triangles as one glTF mesh, its point lights as KHR_lights_punctual nodes; no
// camera.
std::filesystem::path asGltf(const Scene& s, const std::string& name) {
    GltfBuilder b;
    std::vector<float> xyz;
    for (const Vertex& v : s.vertices)
        xyz.insert(xyz.end(), {v.position.x, v.position.y, v.position.z});
    const int p = b.positions(xyz);
    b.node({{"mesh", b.mesh(p, b.accessor(b.view(s.indices), 5125, s.indices.size(), "SCALAR"))}});
    nlohmann::json lights = nlohmann::json::array();
    for (const Light& l : s.lights) {
        b.node({{"extensions", {{"KHR_lights_punctual", {{"light", lights.size()}}}}},
                {"translation", {l.position.x, l.position.y, l.position.z}}});
        lights.push_back({{"type", "point"}, {"intensity", l.intensity}});
    }
    if (!lights.empty()) {
        b.j["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
        b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    }
    return b.writeGltf(scratchDir("gltf", "first-picture") / (name + ".gltf"));
}

// A room whose most open point stands over a low table in its middle, a cabinet against its
// back wall and a box in a corner.
Scene furnishedRoom() {
    Scene scene = room(true);
    scene.indices.resize(scene.indices.size() - 36); // the room without its table
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("furniture", glm::vec3(0.5f));
    mb.box(boxAt({0, 0.4f, 0}, {3, 0.8f, 2}), m);
    mb.box(boxAt({-2, 1, -5}, {3, 2, 1.5f}), m);
    mb.box(boxAt({-8.5f, 0.5f, 4}, glm::vec3(1)), m);
    return scene;
}

constexpr float kPixels = 64.0f * 36.0f;

} // namespace

TEST(FirstPicture, TheProbeCountsCastShadowPixelByPixelUnderEveryLightType) {
    // A sun travelling at 45 degrees towards +x: the plate at height 12 casts its 8 x 8 shadow 12
    // units along, x from 2 to 10, clear of the plate itself (x -10 to -2).
    const Scene high = plateOverGround(12.0f);
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(1, -1, 0))};
    ViewShadow v = measured(high, sun);
    EXPECT_EQ(v.covered, 1.0f);
    EXPECT_EQ(v.castShadow * kPixels, 64.0f);
    EXPECT_EQ(v.lit * kPixels, kPixels - 64.0f) << "the plate's top is lit, its shadow not";
    // Straight down, the shadow lies under the plate, out of view.
    EXPECT_EQ(measured(high, {.direction = {0, -1, 0}}).castShadow, 0.0f);
    // From below the ground: every surface in view is turned away.
    v = measured(high, {.direction = {0, 1, 0}});
    EXPECT_EQ(v.lit + v.castShadow, 0.0f);

    // A bulb at (-18, 8, 0) over the plate at height 4: the shadow is the plate scaled by
    // 8 / (8 - 4) = 2 from the light's foot, x from -2 to 14 and z from -8 to 8: 16 x 16 pixels.
    const Scene low = plateOverGround(4.0f);
    const Light bulb{.type = LightType::Point, .position = {-18, 8, 0}};
    const ViewShadow b = measured(low, bulb);
    EXPECT_EQ(b.castShadow * kPixels, 256.0f);
    EXPECT_EQ((b.lit + b.castShadow) * kPixels, kPixels) << "everything in view faces it";
    // A spot there aimed at (6, 0, 0) with a 30-degree cone holds the whole shadow and less of
    // the ground.
    Light spot = bulb;
    spot.type = LightType::Spot;
    spot.direction = glm::normalize(glm::vec3(6, 0, 0) - spot.position);
    spot.outerConeAngle = glm::radians(30.0f);
    const ViewShadow s = measured(low, spot);
    EXPECT_EQ(s.castShadow * kPixels, 256.0f);
    EXPECT_LT(s.lit, 0.5f * b.lit) << "outside the cone is neither lit nor in shadow";
    EXPECT_GT(s.lit, 0.05f);
    // A bulb under the plate's height lights the plate's top not at all, and casts nothing.
    EXPECT_EQ(measured(low, {.type = LightType::Point, .position = {-6, 2, 0}}).castShadow, 0.0f);
    // A light that casts no shadow does not count.
    const TriangleBvh bvh(low);
    const ViewProbe probe(low, bvh, low.cameras.front());
    Light quiet = bulb;
    quiet.castsShadow = false;
    EXPECT_EQ(probe.castShadow(std::vector{spot}), 256.0f / kPixels);
    EXPECT_EQ(probe.castShadow(std::vector{quiet}), 0.0f);
    EXPECT_EQ(probe.subject(), v.subject);
    // A surface facing a sun at a cosine of 0.04 is grazed: neither lit nor in shadow; at 0.06
    // it is lit.
    for (const float cosine : {0.04f, 0.06f}) {
        const Light grazing{.direction = {-std::sqrt(1.0f - cosine * cosine), -cosine, 0.0f}};
        const ViewShadow g = measured(high, grazing);
        EXPECT_EQ(g.lit + g.castShadow > 0.0f, cosine > 0.05f) << cosine;
    }
}

// Under several lights a pixel shows a shadow where they bring it under half their light: the
// plate at height 4 under a sun towards +x at 45 degrees (its shadow x -6 to 2, the visible part
// x -2 to 2: 32 pixels) and a bulb above (256 pixels, x -2 to 14 and z -8 to 8, over the
// sun's). The brighter one's shadow shows; two equal suns from either side wash out each other's.
TEST(FirstPicture, SeveralLightsShowTheShadowsThatDarkenThePicture) {
    const Scene low = plateOverGround(4.0f);
    const TriangleBvh bvh(low);
    const ViewProbe probe(low, bvh, low.cameras.front());
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(1, -1, 0))};
    Light bulb{.type = LightType::Point, .position = {-18, 8, 0}};
    EXPECT_EQ(probe.castShadow(std::vector{bulb, sun}) * kPixels, 32.0f) << "the sun outshines it";
    bulb.intensity = 1e4f;
    EXPECT_EQ(probe.castShadow(std::vector{bulb, sun}) * kPixels, 256.0f) << "it outshines the sun";
    bulb.color = {0.0f, 0.0f, 1e-3f}; // blue, a thousandth: its colour counts
    EXPECT_EQ(probe.castShadow(std::vector{bulb, sun}) * kPixels, 32.0f);
    bulb.color = glm::vec3(1.0f), bulb.range = 10.0f; // the ground is out of its reach
    EXPECT_EQ(probe.castShadow(std::vector{bulb, sun}) * kPixels, 32.0f);
    // A spot's cone: its edge brings nothing (glTF's smooth falloff from the inner cone).
    Light spot{.type = LightType::Spot,
               .position = {-18, 8, 0},
               .direction = glm::normalize(glm::vec3(24, -8, 0)),
               .intensity = 1e4f,
               .innerConeAngle = glm::radians(60.0f),
               .outerConeAngle = glm::radians(70.0f)};
    EXPECT_EQ(probe.castShadow(std::vector{spot, sun}) * kPixels, 256.0f);
    // The other sun's shadow: x -14 to -6, its visible part x -14 to -10 (32 pixels).
    const Light other{.type = LightType::Directional,
                      .direction = glm::normalize(glm::vec3(-1, -1, 0))};
    EXPECT_EQ(probe.castShadow(std::vector{sun, other}), 0.0f) << "each lit by the other";
    Light brighter = other;
    brighter.intensity = 1.01f;
    EXPECT_EQ(probe.castShadow(std::vector{sun, brighter}) * kPixels, 32.0f);
}

// A box standing on the ground shadows the ground from its foot: 4 x 4 x 4 at x 4 to 8 under a
// sun towards +x at 45 degrees, its shadow x 8 to 12 (32 pixels). Shadow rays start a hair off
// the receiver: a start a hundredth of the scene up would lose the shadow's far unit.
TEST(FirstPicture, AShadowIsCountedFromTheCastersFoot) {
    Scene s = plateOverGround(4.0f);
    s.indices.resize(6); // the ground only
    MeshBuilder mb(s);
    mb.box(boxAt({6, 2, 0}, {4, 4, 8}), 0);
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(1, -1, 0))};
    EXPECT_EQ(measured(s, sun).castShadow * kPixels, 32.0f);
}

// A ball on a ground framed with the ball at the right edge: the standard sun (from the front
// left) throws its shadow to the right, out of the frame; a sun from the right throws it into
// view.
TEST(FirstPicture, TheDefaultSunMovesOnlyWhenItsShadowIsOutOfView) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("m", glm::vec3(0.6f));
    mb.quad({-30, 0, 30}, {30, 0, 30}, {30, 0, -30}, {-30, 0, -30}, m);
    mb.sphere({0, 1.5f, 0}, 1.5f, m, 32, 16); // enough triangles that the subject is the ball
    const Camera edge{.name = "edge", .position = {-8, 4, 10}, .target = {-5, 1, 0}};
    const Light standard = defaultSun(edge);
    const ViewCensus before = viewCensus(scene, edge, standard, scene.bounds());
    ASSERT_LT(before.castShadow, kEnoughShadow) << "the set-up: the shadow leaves the frame";
    const Light chosen = defaultLightFor(scene, edge, false);
    EXPECT_EQ(chosen.type, LightType::Directional);
    EXPECT_EQ(chosen.intensity, standard.intensity);
    const ViewCensus after = viewCensus(scene, edge, chosen, scene.bounds());
    EXPECT_GE(after.castShadow, kEnoughShadow);
    // Framed as the automatic camera frames it, the standard sun's shadow is in view: kept.
    const Camera framed = automaticCamera(scene, ViewChoice::Auto);
    const Light kept = defaultLightFor(scene, framed, false);
    EXPECT_EQ(kept.direction, defaultSun(framed).direction);
    EXPECT_GE(viewCensus(scene, framed, kept, scene.bounds()).castShadow, kEnoughShadow);
}

// A room with crates in front of its camera and the standard bulb right above the camera: each
// crate's shadow falls behind it, where the camera cannot see. A bulb to the side shows them.
TEST(FirstPicture, AnInteriorBulbIsPlacedWhereItsShadowsShow) {
    Scene scene = room(true);
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("crates", glm::vec3(0.5f));
    for (float x : {-7.0f, -4.0f, 4.0f, 7.0f})
        mb.box(boxAt({x, 0.5f, -0.5f}, glm::vec3(1.0f)), m);
    const Camera camera = interiorCamera(scene);
    const Light standard = standardLightFor(scene, camera, true);
    ASSERT_EQ(standard.type, LightType::Point);
    const Bounds subject = subjectBounds(scene);
    ASSERT_LT(viewCensus(scene, camera, standard, subject).castShadow, kEnoughShadow);
    const Light chosen = defaultLightFor(scene, camera, true);
    ASSERT_EQ(chosen.type, LightType::Point);
    EXPECT_GE(viewCensus(scene, camera, chosen, subject).castShadow, kEnoughShadow);
    EXPECT_TRUE(glm::all(glm::lessThan(glm::vec3(-10, 0, -6), chosen.position)) &&
                glm::all(glm::lessThan(chosen.position, glm::vec3(10, 4, 6))))
        << "inside the room";
    // As bright on the floor under it as the default sun.
    EXPECT_NEAR(chosen.intensity / (chosen.position.y * chosen.position.y), defaultSun().intensity,
                1e-3f);
}

// A corridor 40 long and 2.4 wide, seen along its length: the bulbs to the sides of the view
// stop short of its walls, all 18 inside it, at the two documented heights under its ceiling.
TEST(FirstPicture, TheCandidateBulbsStayInsideTheWalls) {
    Scene corridor = room(true);
    for (Vertex& v : corridor.vertices)
        v.position *= glm::vec3(2.0f, 1.0f, 0.2f);
    const Camera camera{
        .name = "auto (interior)", .position = {-18, 1.6f, 0}, .target = {0, 1.6f, 0}};
    const TriangleBvh bvh(corridor);
    const auto bulbs =
        defaultLightCandidates(corridor, bvh, camera, standardLightFor(corridor, camera, true));
    ASSERT_EQ(bulbs.size(), 18u);
    int left = 0, right = 0;
    for (const Light& l : bulbs) {
        EXPECT_EQ(l.type, LightType::Point);
        EXPECT_TRUE(glm::all(glm::lessThan(glm::vec3(-20, 0, -1.2f), l.position)) &&
                    glm::all(glm::lessThan(l.position, glm::vec3(20, 4, 1.2f))))
            << l.position.x << " " << l.position.y << " " << l.position.z;
        left += l.position.z<-0.5f, right += l.position.z> 0.5f;
        // Half way and 0.8 of the way from the camera's height (1.6) to the ceiling (4).
        EXPECT_TRUE(std::abs(l.position.y - 2.8f) < 1e-3f || std::abs(l.position.y - 3.52f) < 1e-3f)
            << l.position.y;
    }
    EXPECT_EQ(left, 6) << "a column of bulbs to either side";
    EXPECT_EQ(right, 6);
    EXPECT_EQ(defaultLightCandidates(corridor, bvh, camera, defaultSun(camera)).size(), 28u);
}

// A room whose most open point stands over a table in its middle, looking along its longest
// free line at an empty wall: no bulb shows a shadow there. Turned towards the cabinet and
// looking down, the camera shows one.
TEST(FirstPicture, AnInteriorCameraTurnsToWhereItsShadowsShow) {
    const Scene scene = furnishedRoom();
    ASSERT_TRUE(isInterior(scene));
    const Camera standard = interiorCamera(scene);
    const Bounds subject = subjectBounds(scene);
    const auto shown = [&](const Camera& c) {
        return viewCensus(scene, c, defaultLightFor(scene, c, true), subject).castShadow;
    };
    if (shown(standard) >= kEnoughShadow) {
        EXPECT_FALSE(betterInteriorView(scene, standard).has_value());
        GTEST_SKIP() << "the set-up: the standard view shows enough already";
    }
    const auto turned = betterInteriorView(scene, standard);
    ASSERT_TRUE(turned.has_value());
    EXPECT_EQ(turned->position, standard.position);
    EXPECT_EQ(turned->yfov, standard.yfov);
    // One of the documented directions: a multiple of 45 degrees round, level or 20 down, the
    // target as far away as before.
    const glm::vec3 look = turned->target - turned->position;
    EXPECT_NEAR(glm::length(look), glm::length(standard.target - standard.position), 1e-3f);
    const glm::vec3 d = glm::normalize(look);
    const float pitch = glm::degrees(std::asin(-d.y));
    EXPECT_TRUE(std::abs(pitch) < 0.01f || std::abs(pitch - 20.0f) < 0.01f) << pitch;
    EXPECT_NEAR(std::remainder(glm::degrees(std::atan2(d.z, d.x)), 45.0f), 0.0f, 0.01f);
    // Towards the cabinet at the back wall, whose shadow shows.
    const glm::vec3 toCabinet = glm::vec3(-2, 1, -5) - turned->position;
    EXPECT_GT(d.x * toCabinet.x + d.z * toCabinet.z, 0.0f);
    EXPECT_GE(shown(*turned), kEnoughShadow);
    EXPECT_GT(shown(*turned), shown(standard));
    // The loader turns it so, for a file without camera or lights.
    const Scene loaded = loadGltf(asGltf(scene, "furnished"));
    ASSERT_EQ(loaded.cameras.size(), 1u);
    EXPECT_EQ(loaded.cameras.front().target, turned->target);
}

TEST(FirstPicture, ALoneObjectGetsAGroundAndAGroundedOneNone) {
    const auto staged = [](Scene s) {
        s.cameras = {automaticCamera(s, ViewChoice::Auto)};
        s.lights = {defaultLightFor(s, s.cameras.front(), false)};
        s.defaultLight = true;
        return s;
    };
    Scene lone = staged(loneObject());
    const size_t triangles = lone.triangleCount();
    const Bounds subject = subjectBounds(lone);
    Scene floating = lone;
    applySceneEdits(floating, {.noGround = true});
    EXPECT_FALSE(floating.automaticGround);
    EXPECT_EQ(floating.triangleCount(), triangles);
    applySceneEdits(lone, {});
    ASSERT_TRUE(lone.automaticGround);
    EXPECT_EQ(lone.triangleCount(), triangles + 2);
    EXPECT_EQ(lone.materials.back().name, "ground (automatic)");
    EXPECT_EQ(lone.vertices.back().position.y, subject.min.y) << "under the subject";
    const ViewCensus v = viewCensus(lone, lone.cameras.front(), lone.lights.front(), subject);
    EXPECT_GE(v.castShadow, 0.01f);
    EXPECT_GE(v.subject, 0.15f);
    EXPECT_NE(automaticGroundNote(lone).find("--no-ground"), std::string::npos);
    // The default light is the rule's for the scene as it now stands, ground and all.
    EXPECT_EQ(lone.lights.front().direction,
              defaultLightFor(lone, lone.cameras.front(), false).direction);
    // Once is enough; --ground on a grounded scene adds no second quad.
    applySceneEdits(lone, {.ground = true});
    EXPECT_EQ(lone.triangleCount(), triangles + 2);
    EXPECT_THROW(applySceneEdits(lone, {.ground = true, .noGround = true}), InputError);

    // A camera that looks away from the model would not see the ground: none, and the scene as
    // it was (the quad tried in place is taken back, the default light as it was).
    Scene away = staged(loneObject());
    away.cameras.front() = {.name = "away", .position = {0, 2, 10}, .target = {0, 2, 20}};
    away.lights.front().direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)); // not the rule's
    const Scene original = away;
    applySceneEdits(away, {});
    EXPECT_FALSE(away.automaticGround);
    EXPECT_EQ(away.vertices.size(), original.vertices.size());
    EXPECT_EQ(away.indices, original.indices);
    EXPECT_EQ(away.materials.size(), original.materials.size());
    EXPECT_EQ(away.lights.front().direction, original.lights.front().direction);

    // Scenes with floors of their own gain nothing from another.
    for (Scene s : {staged(levelUnderSky()), staged(courtyard()), staged(room(true))}) {
        const size_t before = s.triangleCount();
        applySceneEdits(s, {});
        EXPECT_FALSE(s.automaticGround) << s.name;
        EXPECT_EQ(s.triangleCount(), before) << s.name;
    }
    // A model on a thick base of its own (the rays from just above the bottom start inside the
    // base and pass through its underside; from a quarter of the height they meet its top) and
    // a terrain of hills (from its bottom the rays start under the slopes): none.
    Scene based = loneObject();
    for (Vertex& vertex : based.vertices)
        vertex.position.y += 0.6f;
    MeshBuilder(based).box(boxAt({0.5f, 0.3f, 0}, {5, 0.6f, 4}), 0);
    Scene hills;
    hills.name = "hills";
    MeshBuilder hb(hills);
    const uint32_t grass = hb.material("grass", glm::vec3(0.4f));
    const auto height = [](float x, float z) { return 2.0f + std::sin(x) * std::cos(0.7f * z); };
    for (int i = -10; i < 10; ++i)
        for (int k = -10; k < 10; ++k) {
            const float x = static_cast<float>(i), z = static_cast<float>(k);
            hb.quad({x, height(x, z + 1), z + 1}, {x + 1, height(x + 1, z + 1), z + 1},
                    {x + 1, height(x + 1, z), z}, {x, height(x, z), z}, grass);
        }
    for (Scene s : {staged(based), staged(hills)}) {
        const size_t before = s.triangleCount();
        applySceneEdits(s, {});
        EXPECT_FALSE(s.automaticGround) << s.name;
        EXPECT_EQ(s.triangleCount(), before) << s.name;
    }
    // A tall pole's ground reaches three times its height, where a low sun throws its shadow.
    Scene pole;
    MeshBuilder(pole).box(boxAt({0, 5, 0}, {0.4f, 10, 0.4f}), MeshBuilder(pole).material("m", {}));
    addGround(pole);
    Bounds quad;
    for (size_t corner = pole.vertices.size() - 4; corner < pole.vertices.size(); ++corner)
        quad.grow(pole.vertices[corner].position);
    EXPECT_NEAR(quad.extent().x, 30.0f, 1e-3f);
    EXPECT_NEAR(quad.extent().z, 30.0f, 1e-3f);

    for (std::string_view name : builtinSceneNames()) {
        Scene s = loadScene("builtin:" + std::string(name));
        const size_t before = s.triangleCount();
        applySceneEdits(s, {});
        EXPECT_FALSE(s.automaticGround) << name;
        EXPECT_EQ(s.triangleCount(), before) << name;
    }
}

// A lone object a hundred-millionth or a hundred million times the size of the one above gets
// its ground and shows its shadow as that one does: the ground's size, the probe's offsets and
// the hit test all follow the scene's size.
TEST(FirstPicture, ALoneObjectGetsItsGroundAtAnyScale) {
    for (const float scale : {1e-8f, 1e-4f, 1e4f, 1e8f}) {
        Scene s = loneObject();
        for (Vertex& v : s.vertices)
            v.position *= scale;
        s.cameras = {automaticCamera(s, ViewChoice::Auto)};
        s.lights = {defaultLightFor(s, s.cameras.front(), false)};
        s.defaultLight = true;
        applySceneEdits(s, {});
        ASSERT_TRUE(s.automaticGround) << scale;
        const glm::vec3 a = s.vertices[s.vertices.size() - 2].position;
        const float side = glm::length(s.vertices.back().position - a);
        EXPECT_NEAR(side, 9.0f * scale, 1e-4f * 9.0f * scale) << "three times the height";
        const PictureMeasure m = measurePicture(s, s.cameras.front());
        EXPECT_GE(m.castShadow, 0.01f) << scale;
        EXPECT_GE(m.subject, 0.15f) << scale;
        // Nothing in view lies before the near plane: the ground reaches nearer the camera than
        // the subject does.
        const Camera& c = s.cameras.front();
        const glm::vec3 forward = glm::normalize(c.target - c.position);
        const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
        const glm::vec3 up = glm::cross(right, forward);
        const float tanHalf = std::tan(0.5f * c.yfov);
        const TriangleBvh bvh(s);
        float nearest = std::numeric_limits<float>::max();
        for (int y = 0; y <= 8; ++y)
            for (int x = 0; x <= 8; ++x) {
                const float u = static_cast<float>(x) / 4.0f - 1.0f;
                const float v = static_cast<float>(y) / 4.0f - 1.0f;
                const glm::vec3 d =
                    glm::normalize(forward + u * tanHalf * 16.0f / 9.0f * right + v * tanHalf * up);
                if (const auto hit = bvh.firstHit({.origin = c.position, .direction = d}))
                    nearest = std::min(nearest, hit->distance * glm::dot(d, forward));
            }
        EXPECT_GT(nearest, c.znear) << scale;
    }
}

// From outside the warehouse only its roof shows; near the bulbs, their crates' shadows.
TEST(FirstPicture, ALevelLitByItsOwnBulbsIsSeenFromNearThem) {
    const Scene s = warehouse();
    const Bounds subject = subjectBounds(s);
    const Camera outside = exteriorCamera(s, subject);
    EXPECT_LT(viewCensus(s, outside, s.lights[0], subject).castShadow, 0.01f);
    const auto near = cameraFromLights(s, outside, true);
    ASSERT_TRUE(near.has_value());
    EXPECT_EQ(near->name, "auto (from the lights)");
    EXPECT_TRUE(glm::all(glm::lessThan(glm::vec3(-20, 0, -15), near->position)) &&
                glm::all(glm::lessThan(near->position, glm::vec3(20, 6, 15))))
        << "inside the warehouse";
    float most = 0.0f;
    for (const Light& l : s.lights)
        most = std::max(most, viewCensus(s, *near, l, subject).castShadow);
    EXPECT_GE(most, 0.01f);
    EXPECT_GE(viewCensus(s, *near, s.lights[0], subject).subject, kLeastSubject);
    // Not a level, framed well from outside: left as it is, though a view near its bulb would
    // show more (as a level it would move). Lit by suns only: nothing to seek.
    Scene lone = loneObject();
    addGround(lone);
    lone.lights = {{.type = LightType::Point, .position = {1.5f, 3, 1.2f}, .intensity = 20}};
    Camera framed = automaticCamera(lone, {});
    framed.position = framed.target + 0.8f * (framed.position - framed.target); // the model larger
    ASSERT_GE(viewCensus(lone, framed, lone.lights[0], subjectBounds(lone)).subject, kLeastSubject);
    EXPECT_FALSE(cameraFromLights(lone, framed, false).has_value());
    EXPECT_TRUE(cameraFromLights(lone, framed, true).has_value())
        << "the set-up: a view to move to";
    Scene sunny = s;
    sunny.lights = {defaultSun()};
    EXPECT_FALSE(cameraFromLights(sunny, outside, true).has_value());
}

// The loader's path: a level's own bulbs frame it; a lone model without lights or camera gets a
// ground once the scene options are applied, as every command applies them.
TEST(FirstPicture, TheLoaderFramesALevelFromItsBulbsAndGroundsALoneModel) {
    const Scene level = loadGltf(asGltf(warehouse(), "warehouse"));
    ASSERT_EQ(level.cameras.size(), 1u);
    EXPECT_EQ(level.cameras.front().name, "auto (from the lights)");
    EXPECT_TRUE(level.cameras.front().automatic) << "framed by Penumbra: a timeline holds it";
    EXPECT_FALSE(level.defaultLight);

    Scene lone = loadGltf(asGltf(loneObject(), "lone"));
    ASSERT_TRUE(lone.defaultLight);
    const size_t triangles = lone.triangleCount();
    applySceneEdits(lone, {});
    EXPECT_TRUE(lone.automaticGround);
    EXPECT_EQ(lone.triangleCount(), triangles + 2);
    const ViewCensus v =
        viewCensus(lone, lone.cameras.front(), lone.lights.front(), subjectBounds(lone));
    EXPECT_GE(v.castShadow, 0.01f);
    EXPECT_GE(v.subject, 0.15f);
}

// A lone model whose own bulb stands between it and the automatic camera: its shadow falls behind
// it, out of sight. After the ground, the view turns round the model to where the shadow shows.
TEST(FirstPicture, AnExteriorViewTurnsToWhereItsShadowShows) {
    Scene s = loneObject();
    const Camera standard = automaticCamera(s, ViewChoice::Auto);
    ASSERT_EQ(standard.name, "auto (exterior)");
    s.cameras = {standard};
    const glm::vec3 towards = standard.position - standard.target;
    s.lights = {{.name = "bulb",
                 .type = LightType::Point,
                 .position = standard.target + 0.6f * towards + glm::vec3(0, 1, 0),
                 .intensity = 20}};
    Scene kept = s;
    applySceneEdits(kept, {}); // the ground, then the turn
    ASSERT_TRUE(kept.automaticGround);
    Scene unturned = s;
    ASSERT_TRUE(addGroundWhereNothingReceives(unturned));
    const Bounds subject = subjectBounds(s);
    const float before = viewCensus(unturned, standard, s.lights[0], subject).castShadow;
    ASSERT_LT(before, kEnoughShadow) << "the set-up: the shadow hides behind the model";
    const Camera& turned = kept.cameras.front();
    EXPECT_EQ(turned.target, standard.target);
    EXPECT_NEAR(glm::length(turned.position - turned.target), glm::length(towards), 1e-3f);
    EXPECT_NEAR(turned.position.y, standard.position.y, 1e-3f);
    EXPECT_GT(viewCensus(kept, turned, s.lights[0], subject).castShadow, before);
    EXPECT_GE(viewCensus(kept, turned, s.lights[0], subject).castShadow, kEnoughShadow);
    // A camera of the file (or the command line) stays where it is.
    Scene own = s;
    own.cameras.front().name = "eye";
    applySceneEdits(own, {});
    EXPECT_EQ(own.cameras.front().position, standard.position);
}

// A long low wall whose bulb stands between it and the camera: nothing in view is in cast
// shadow, and seen end-on the wall fills too little of the view to count. Whether or not the view
// turns, it shows the wall on at least 15% of it.
TEST(FirstPicture, AnExteriorViewTurnsOnlyToViewsThatShowTheSubject) {
    Scene s;
    MeshBuilder mb(s);
    mb.box(boxAt({0, 1.5f, 0}, {12, 3, 0.3f}), mb.material("wall", glm::vec3(0.6f)));
    const Camera standard = automaticCamera(s, ViewChoice::Auto);
    ASSERT_EQ(standard.name, "auto (exterior)");
    s.cameras = {standard};
    s.lights = {{.name = "bulb",
                 .type = LightType::Point,
                 .position = standard.target + 0.6f * (standard.position - standard.target) +
                             glm::vec3(0, 1, 0),
                 .intensity = 20}};
    const Bounds subject = subjectBounds(s);
    Camera endOn = standard;
    const glm::vec3 offset = standard.position - standard.target;
    endOn.position = standard.target + glm::vec3(std::hypot(offset.x, offset.z), offset.y, 0.0f);
    ASSERT_LT(viewCensus(s, endOn, s.lights[0], subject).subject, kLeastSubject)
        << "the set-up: end-on, the wall is a sliver";
    turnExteriorView(s);
    EXPECT_GE(viewCensus(s, s.cameras.front(), s.lights[0], subject).subject, kLeastSubject);
}

// A candidate light counts when it lights a quarter of what is in view, not less.
TEST(FirstPicture, ACandidateLightMustLightAQuarterOfWhatIsInView) {
    EXPECT_TRUE(lightsTheView({.covered = 0.8f, .lit = 0.2f}));
    EXPECT_FALSE(lightsTheView({.covered = 0.8f, .lit = 0.19f}));
    EXPECT_FALSE(lightsTheView({.covered = 1.0f, .lit = 0.2f, .castShadow = 0.8f}));
    EXPECT_TRUE(lightsTheView({}));
}

// A column of surfaces over a ground: the ray down follows at most kMostSurfacesDown of them.
// Thin closed slabs (two surfaces each), an open shelf facing up (one) and the ground (one).
TEST(FirstPicture, AColumnIsFollowedThroughSixteenSurfacesAndNoMore) {
    const auto column = [](int slabs, bool shelf) {
        Scene s;
        MeshBuilder mb(s);
        const uint32_t m = mb.material("m", glm::vec3(0.5f));
        mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, m);
        if (shelf)
            mb.quad({-1, 0.5f, 1}, {1, 0.5f, 1}, {1, 0.5f, -1}, {-1, 0.5f, -1}, m);
        for (int i = 0; i < slabs; ++i)
            mb.box(boxAt({0, 1.0f + static_cast<float>(i), 0}, {2, 0.2f, 2}), m);
        return s;
    };
    const auto ends = [](const Scene& s) {
        const TriangleBvh bvh(s);
        return endsOnAnOpenSurface(bvh, {0.1f, 40, 0.2f}, 1e-4f);
    };
    EXPECT_TRUE(ends(column(7, false)));  // 15 surfaces
    EXPECT_TRUE(ends(column(7, true)));   // 16
    EXPECT_FALSE(ends(column(8, false))); // 17: given up
    EXPECT_TRUE(ends(column(0, false)));  // the ground alone
    Scene slab;                           // a slab over nothing: its underside, met from within
    MeshBuilder mb(slab);
    mb.box(boxAt({0, 1, 0}, {2, 0.2f, 2}), mb.material("m", glm::vec3(0.5f)));
    EXPECT_FALSE(ends(slab));
}

// The grid of columns at its cells' centres: a slope (an open surface facing up) is found in
// every column, from above where the rays from within start under it; a floor under the far 5 of
// 9 rows of a floating slab in 45 of 81; a slab over nothing in none; a floor under 3 sheets
// seen from below everywhere, under 4 nowhere.
TEST(FirstPicture, TheColumnsDownCoverTheFootprintCellByCell) {
    const auto share = [](const Scene& s) { return floorShare(s, TriangleBvh(s)); };
    Scene slope;
    MeshBuilder sb(slope);
    sb.quad({0, 2, 9}, {9, 9.2f, 9}, {9, 9.2f, 0}, {0, 2, 0}, sb.material("m", glm::vec3(0.5f)));
    EXPECT_EQ(share(slope), 1.0f);
    Scene partial;
    MeshBuilder pb(partial);
    const uint32_t m = pb.material("m", glm::vec3(0.5f));
    pb.box(boxAt({4.5f, 1.5f, 4.5f}, {9, 1, 9}), m);
    pb.quad({0, 0, 9}, {9, 0, 9}, {9, 0, 4}, {0, 0, 4}, m);
    EXPECT_EQ(share(partial), 45.0f / 81.0f);
    Scene slab;
    MeshBuilder(slab).box(boxAt({4.5f, 1.5f, 4.5f}, {9, 1, 9}), m);
    EXPECT_EQ(share(slab), 0.0f);
    // A ray from within goes through 4 back faces at most: sheets facing down at 4.8, 4.6, ...,
    // a floor facing up at 4 and a last sheet facing down at 0 (so that the column from above
    // ends on a back face). The 50% ray starts at 5 (a wall at the edge makes the subject 10
    // high; rays down pass beside it).
    const auto sheets = [&](int down) {
        Scene s;
        MeshBuilder b(s);
        b.quad({9, 0, 0}, {9, 0, 9}, {9, 10, 9}, {9, 10, 0}, m);
        for (int k = 0; k < down; ++k) {
            const float y = 4.8f - 0.2f * static_cast<float>(k);
            b.quad({0, y, 0}, {9, y, 0}, {9, y, 9}, {0, y, 9}, m);
        }
        b.quad({0, 4, 9}, {9, 4, 9}, {9, 4, 0}, {0, 4, 0}, m);
        b.quad({0, 0, 0}, {9, 0, 0}, {9, 0, 9}, {0, 0, 9}, m);
        return s;
    };
    EXPECT_EQ(share(sheets(3)), 1.0f) << "a floor under 3 back faces";
    EXPECT_EQ(share(sheets(4)), 0.0f) << "a floor under 4 back faces";
}

// Nothing to stand on: no camera to measure from, or no triangles. Left as it is.
TEST(FirstPicture, AGroundNeedsACameraAndSomethingToStandUnder) {
    Scene noCamera = loneObject();
    EXPECT_FALSE(addGroundWhereNothingReceives(noCamera));
    EXPECT_EQ(noCamera.triangleCount(), loneObject().triangleCount());
    Scene empty;
    empty.cameras = {Camera{}};
    EXPECT_FALSE(addGroundWhereNothingReceives(empty));
    EXPECT_EQ(empty.triangleCount(), 0u);
}

namespace {

// The documented candidate suns: straight behind the camera, and turned 45, 85 and 135 degrees
// either way round it, at 20, 30, 45 and 60 degrees up.
std::vector<Light> documentedSuns(const Camera& camera) {
    glm::vec3 back = camera.position - camera.target;
    back.y = 0.0f;
    back = glm::normalize(back);
    std::vector<Light> suns;
    for (float turn : {0.0f, 45.0f, -45.0f, 85.0f, -85.0f, 135.0f, -135.0f})
        for (float up : {20.0f, 30.0f, 45.0f, 60.0f}) {
            const float t = glm::radians(turn), e = glm::radians(up);
            const glm::vec3 flat(std::cos(t) * back.x + std::sin(t) * back.z, 0.0f,
                                 -std::sin(t) * back.x + std::cos(t) * back.z);
            Light l = defaultSun(camera);
            l.direction = -(std::cos(e) * flat + std::sin(e) * glm::vec3(0, 1, 0));
            suns.push_back(l);
        }
    return suns;
}

} // namespace

// Where the standard sun shows too little, the chosen one shows as much as the best documented
// candidate that lights the view: on generated scenes seen from many sides and heights.
TEST(FirstPicture, TheChosenSunIsTheBestOfTheDocumentedCandidates) {
    int moved = 0, compared = 0;
    for (Scene s : {loneObject(), solidBox(), courtyard(), levelUnderSky(), buildingWithRooms()}) {
        addGround(s);
        const TriangleBvh bvh(s);
        const Bounds subject = subjectBounds(s);
        const float r = glm::length(subject.extent());
        for (int a = 0; a < 8; ++a)
            for (float height : {0.1f, 0.5f, 1.2f}) {
                const float round = glm::radians(45.0f * static_cast<float>(a) + 10.0f);
                const Camera c{.name = "probe",
                               .position = subject.center() +
                                           r * glm::vec3(std::cos(round), height, std::sin(round)),
                               .target =
                                   subject.center() +
                                   0.3f * r * glm::vec3(std::sin(round), 0, -std::cos(round))};
                const ViewProbe probe(s, bvh, c, subject);
                const Light standard = defaultSun(c);
                if (probe.measure(standard).castShadow >= kEnoughShadow)
                    continue;
                ++compared;
                float best = -1.0f;
                for (const Light& l : documentedSuns(c))
                    if (const ViewShadow v = probe.measure(l); lightsTheView(v))
                        best = std::max(best, v.castShadow);
                const Light chosen = chooseDefaultLight(s, c, standard);
                moved += chosen.direction != standard.direction;
                if (best >= 0.0f) {
                    EXPECT_GE(probe.measure(chosen).castShadow, best - 2.0f / kPixels)
                        << s.name << " camera " << a << " height " << height;
                }
            }
    }
    EXPECT_GE(compared, 10) << "the set-up: views where the standard shows too little";
    EXPECT_GE(moved, 5);
}

// The warehouse, and a third bulb far out over a pad of its own with a plate between, beyond the
// subject: a view of its spot shows a wide shadow but nothing of the subject, and is no candidate.
// The chosen camera stands at most 1.5 times its light's height over the spot away from it, with
// the spot in sight.
TEST(FirstPicture, ACameraNearTheLightsShowsTheSubjectAndSeesItsSpot) {
    Scene s = warehouse();
    MeshBuilder mb(s);
    mb.quad({230, 0, 20}, {270, 0, 20}, {270, 0, -20}, {230, 0, -20},
            mb.material("pad", glm::vec3(0.4f)));
    mb.quad({247, 2, 3}, {253, 2, 3}, {253, 2, -3}, {247, 2, -3}, 0); // its shadow on the pad
    s.lights.push_back(
        {.name = "far", .type = LightType::Point, .position = {250, 5, 0}, .intensity = 50});
    const Bounds subject = subjectBounds(s);
    ASSERT_LT(subject.max.x, 100.0f) << "the set-up: the far bulb stands beyond the subject";
    const auto near = cameraFromLights(s, exteriorCamera(s, subject), true);
    ASSERT_TRUE(near.has_value());
    const TriangleBvh bvh(s);
    const ViewProbe probe(s, bvh, *near, subject);
    EXPECT_GE(probe.subject(), kLeastSubject);
    // A bulb just outside the wall shadows most of the view and lights none of it: no shadow
    // to show.
    const Light outside{.type = LightType::Point, .position = {21, 3, 0}, .intensity = 50};
    EXPECT_GT(probe.measure(outside).castShadow, 0.25f);
    EXPECT_EQ(probe.castShadow(std::span(&outside, 1)), 0.0f);
    EXPECT_GT(probe.castShadow(std::span(&s.lights[0], 2)), 0.0f);
    const Light* light = nullptr;
    for (const Light& l : s.lights)
        if (std::abs(l.position.x - near->target.x) < 1e-3f &&
            std::abs(l.position.z - near->target.z) < 1e-3f)
            light = &l;
    ASSERT_NE(light, nullptr) << "the target is a spot straight under a bulb";
    const glm::vec3 toCamera = near->position - near->target;
    EXPECT_LE(glm::length(toCamera), 1.5f * (light->position.y - near->target.y) + 1e-3f);
    EXPECT_FALSE(bvh.occluded({.origin = near->target + 1e-3f * glm::normalize(toCamera),
                               .direction = glm::normalize(toCamera)},
                              glm::length(toCamera)));
}
