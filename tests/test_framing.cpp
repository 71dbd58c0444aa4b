// The automatic view of scenes without cameras (scene/framing.h, scene/interior.h): the subject
// without sky planes or outliers, exterior or interior by measurement, --view and --ground, and
// a default light whose cast shadow is in view. On generated scenes of each kind.
#include "generated_scenes.h"
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "scene/gltf_loader.h"
#include "scene/interior.h"
#include "scene/mesh_closure.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra;
using namespace penumbra::test;

namespace {

float elevationDegrees(const Camera& c) {
    const glm::vec3 d = glm::normalize(c.position - c.target);
    return glm::degrees(std::asin(d.y));
}

bool inside(const Bounds& b, const glm::vec3& p) {
    return glm::all(glm::lessThanEqual(b.min, p)) && glm::all(glm::lessThanEqual(p, b.max));
}

} // namespace

// The far plane of a camera placed by a rule holds the whole scene, 1.1 times its farthest
// corner, at any scale; the near plane 1e-4 of it.
TEST(Framing, DepthRangeHoldsTheSceneAtAnyScale) {
    for (float scale : {1e-3f, 1.0f, 1e3f}) {
        Scene s;
        MeshBuilder(s).box(boxAt({0, 0, 0}, glm::vec3(2.0f * scale)), 0);
        const glm::vec2 range = depthRangeFrom(s, {3.0f * scale, 0, 0});
        const float farthest = scale * std::sqrt(16.0f + 1.0f + 1.0f); // to (-1, +-1, +-1)
        EXPECT_NEAR(range.y, 1.1f * farthest, 1e-5f * farthest) << scale;
        EXPECT_NEAR(range.x, 1e-4f * range.y, 1e-9f * range.y) << scale;
    }
}

TEST(Framing, SubjectBoundsIgnoreSkyPlanesAndOutliers) {
    const Bounds s = subjectBounds(levelUnderSky());
    EXPECT_LT(s.max.y, 10.0f) << "the sky backdrop does not count";
    EXPECT_GT(s.min.z, -40.0f) << "the sky backdrop does not count";
    EXPECT_LT(s.max.x, 60.0f) << "the stray triangle at 900 does not count";
    // The blocks span x -16.5..16.5 and z -11.5..11.5; the ground counts only near them.
    EXPECT_LE(s.min.x, -16.5f);
    EXPECT_GE(s.max.x, 16.5f);
    EXPECT_LE(s.min.z, -11.5f);
    EXPECT_GT(s.min.x, -30.0f) << "the ground is cut to the region around the blocks";
    EXPECT_EQ(s.min.y, 0.0f);
    // A lone model's subject is the model itself.
    const Scene lone = loneObject();
    const Bounds l = subjectBounds(lone), all = lone.bounds();
    EXPECT_EQ(l.min, all.min);
    EXPECT_EQ(l.max, all.max);
}

TEST(Framing, RoomsAndCourtyardsOpenToTheSkyAreInteriorsModelsAndBuildingsAreNot) {
    EXPECT_TRUE(isInterior(room(true)));
    EXPECT_TRUE(isInterior(room(false))) << "an open sky above is still a room";
    EXPECT_FALSE(isInterior(solidBox())) << "from inside a closed model the rays meet back faces";
    EXPECT_FALSE(isInterior(buildingWithRooms())) << "its rooms are modelled, its facade faces out";
    EXPECT_FALSE(isInterior(courtyard())) << "the wings' outer walls face out";
    EXPECT_FALSE(isInterior(levelUnderSky()));
    EXPECT_FALSE(isInterior(loneObject()));
    Scene yard = room(false);
    yard.indices.erase(yard.indices.begin() + 6, yard.indices.begin() + 12); // no back wall
    EXPECT_FALSE(isInterior(yard)) << "three walls are not a room";

    const ViewMeasure m = measureView(room(true), subjectBounds(room(true)));
    ASSERT_TRUE(m.room.has_value());
    EXPECT_EQ(m.exteriorFront, 0.0f);
    EXPECT_EQ(measureView(buildingWithRooms(), subjectBounds(buildingWithRooms())).exteriorFront,
              1.0f);
}

TEST(Framing, ARoomIsSeenFromItsMostOpenPointAndLitUnderItsCeiling) {
    const Scene closed = room(true);
    const Camera c = interiorCamera(closed);
    EXPECT_EQ(c.position, glm::vec3(0, 2, 0)) << "the centre is the most open point";
    EXPECT_NEAR(std::abs(glm::normalize(c.target - c.position).x), 1.0f, 1e-6f)
        << "along the longer horizontal side";
    EXPECT_LT(c.znear, 0.01f);

    // The standard bulb; tests/test_first_picture.cpp checks where it goes when its shadows
    // are out of view.
    const Light l = standardLightFor(closed, c, true);
    ASSERT_EQ(l.type, LightType::Point);
    EXPECT_NEAR(l.position.x, 0.0f, 1e-4f);
    EXPECT_NEAR(l.position.z, 0.0f, 1e-4f);
    EXPECT_NEAR(l.position.y, 3.0f, 1e-4f) << "half way from the camera (y 2) to the ceiling";
    // The floor under it receives the default sun's irradiance: I / d^2 with d = 3.
    EXPECT_NEAR(l.intensity / 9.0f, defaultSun().intensity, 1e-3f);

    const Light open = defaultLightFor(room(false), interiorCamera(room(false)), true);
    EXPECT_EQ(open.type, LightType::Directional) << "without a roof the sun reaches the room";
}

// A room open on one side: the closed room with a doorway 3 wide and 3 high in the middle of its
// front wall. From the points in line with the doorway one of the eight horizontal rays leaves
// the room; the room is still a room, seen from its centre, the most open point.
TEST(Framing, ARoomWithADoorwayIsStillARoomSeenFromItsCentre) {
    Scene s = room(true);
    s.name = "room with a doorway";
    s.indices.erase(s.indices.begin() + 12, s.indices.begin() + 18); // the front wall
    MeshBuilder mb(s);
    const uint32_t m = 0;
    const float z = 6.0f;
    const auto wall = [&](float a, float b, float y0, float y1) { // facing -z, as the room's
        mb.quad({b, y0, z}, {a, y0, z}, {a, y1, z}, {b, y1, z}, m);
    };
    wall(-10.0f, -1.5f, 0.0f, 4.0f);
    wall(1.5f, 10.0f, 0.0f, 4.0f);
    wall(-1.5f, 1.5f, 3.0f, 4.0f); // the lintel
    ASSERT_EQ(subjectBounds(s).max.z, 6.0f);
    EXPECT_TRUE(isInterior(s));
    const Camera c = interiorCamera(s);
    EXPECT_EQ(c.position, glm::vec3(0, 2, 0)) << "the doorway's ray does not rule out the centre";
    const Bounds all = s.bounds();
    for (int k = 0; k < 8; ++k) { // every corner of the scene lies within the far plane
        const glm::vec3 corner((k & 1) ? all.max.x : all.min.x, (k & 2) ? all.max.y : all.min.y,
                               (k & 4) ? all.max.z : all.min.z);
        EXPECT_LT(glm::length(corner - c.position), c.zfar) << k;
    }
    const Light l = defaultLightFor(s, c, true);
    EXPECT_EQ(l.type, LightType::Point) << "under the ceiling";
    // Two doorways facing each other leave two rays of eight: the line through them is no
    // room's centre any more, though the rest of the room still is a room.
    Scene two = s;
    two.indices.erase(two.indices.begin() + 6, two.indices.begin() + 12); // the back wall
    MeshBuilder back(two);
    const auto backWall = [&](float a, float b, float y0, float y1) { // facing +z
        back.quad({a, y0, -z}, {b, y0, -z}, {b, y1, -z}, {a, y1, -z}, m);
    };
    backWall(-10.0f, -1.5f, 0.0f, 4.0f);
    backWall(1.5f, 10.0f, 0.0f, 4.0f);
    backWall(-1.5f, 1.5f, 3.0f, 4.0f);
    EXPECT_TRUE(isInterior(two));
    EXPECT_NE(interiorCamera(two).position.x, 0.0f) << "six of eight rays are not enough";
}

TEST(Framing, ExteriorViewsFillTheFrameAndShowACastShadow) {
    struct Case {
        Scene scene;
        float minSubject, maxElevation, minShadow;
    };
    Scene lone = loneObject();
    const Bounds loneSubject = subjectBounds(lone);
    const Camera loneCamera = automaticCamera(lone, ViewChoice::Auto);
    addGround(lone); // --ground, after the framing as applySceneEdits does
    // Nothing catches the building's and the box's shadows but themselves.
    const Case cases[] = {{levelUnderSky(), 0.35f, 50.5f, 0.01f},
                          {courtyard(), 0.3f, 50.5f, 0.02f},
                          {buildingWithRooms(), 0.4f, 50.5f, 0.0f},
                          {solidBox(), 0.2f, 20.5f, 0.0f}};
    for (const Case& k : cases) {
        const Camera c = automaticCamera(k.scene, ViewChoice::Auto);
        EXPECT_EQ(c.name, "auto (exterior)") << k.scene.name;
        EXPECT_LE(elevationDegrees(c), k.maxElevation) << k.scene.name;
        EXPECT_GE(elevationDegrees(c), 19.5f) << k.scene.name;
        const ViewCensus v = viewCensus(k.scene, c, defaultSun(c), subjectBounds(k.scene));
        EXPECT_GE(v.subject, k.minSubject) << k.scene.name;
        EXPECT_GE(v.castShadow, k.minShadow) << k.scene.name;
    }
    EXPECT_NEAR(elevationDegrees(loneCamera), 20.0f + 30.0f * 0.0f, 0.5f)
        << "a model taller than wide is seen from low down";
    const ViewCensus v = viewCensus(lone, loneCamera, defaultSun(loneCamera), loneSubject);
    EXPECT_GE(v.subject, 0.15f);
    EXPECT_GE(v.castShadow, 0.004f) << "--ground catches the model's shadow";
    const ViewCensus level = viewCensus(levelUnderSky(), automaticCamera(levelUnderSky(), {}),
                                        defaultSun(), subjectBounds(levelUnderSky()));
    EXPECT_GE(level.subject, 0.35f) << "framed without the sky backdrop";
}

TEST(Framing, ViewOverridesTheMeasurement) {
    const Scene building = buildingWithRooms();
    const Camera in = automaticCamera(building, ViewChoice::Interior);
    EXPECT_EQ(in.name, "auto (interior)");
    EXPECT_TRUE(in.automatic) << "framed by Penumbra";
    EXPECT_TRUE(inside(building.bounds(), in.position));
    const Camera out = automaticCamera(room(true), ViewChoice::Exterior);
    EXPECT_EQ(out.name, "auto (exterior)");
    EXPECT_TRUE(out.automatic) << "framed by Penumbra";
    EXPECT_FALSE(inside(room(true).bounds(), out.position));

    Scene s = room(true);
    s.lights = {defaultLightFor(s, interiorCamera(s), true)};
    s.defaultLight = true;
    applySceneEdits(s, {.view = ViewChoice::Exterior, .ground = true});
    EXPECT_EQ(s.cameras.front().name, "auto (exterior)");
    EXPECT_EQ(s.lights.front().type, LightType::Directional) << "the default light follows";
    EXPECT_EQ(s.materials.back().name, "ground (--ground)");
    EXPECT_EQ(parseViewChoice("interior"), ViewChoice::Interior);
    EXPECT_THROW(parseViewChoice("inside"), InputError);
}

TEST(Framing, AGltfRoomWithoutLightsOrCamerasIsLitAndSeenFromInside) {
    GltfBuilder b;
    // The closed room of room(true) without its table: floor, four walls and ceiling.
    const float x = 10, y = 4, z = 6;
    const int p = b.positions(
        {-x, 0, z, x, 0, z, x, 0, -z, -x, 0, -z, -x, y, z, x, y, z, x, y, -z, -x, y, -z});
    const std::vector<uint16_t> quads = {0, 1, 2, 3, /*floor*/ 3, 2, 6, 7, /*back*/
                                         1, 0, 4, 5, /*front*/ 0, 3, 7, 4, /*left*/
                                         2, 1, 5, 6, /*right*/ 7, 6, 5, 4 /*ceiling*/};
    std::vector<uint16_t> tris;
    for (size_t q = 0; q < quads.size(); q += 4)
        tris.insert(tris.end(),
                    {quads[q], quads[q + 1], quads[q + 2], quads[q], quads[q + 2], quads[q + 3]});
    b.node({{"mesh", b.mesh(p, b.accessor(b.view(tris), 5123, tris.size(), "SCALAR"))}});
    const Scene s = loadGltf(b.writeGltf(scratchDir("gltf", "interior") / "room.gltf"));
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(s.defaultLight);
    EXPECT_EQ(s.lights[0].type, LightType::Point);
    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_EQ(s.camera("").name, "auto (interior)");
    EXPECT_EQ(s.camera("").position, glm::vec3(0, 2, 0));
}

TEST(Framing, ClosureCountsOpenAndMisWoundTriangles) {
    EXPECT_TRUE(meshClosure(solidBox()).closed());
    EXPECT_EQ(meshClosure(solidBox()).triangles, 12u);
    Scene holed = solidBox();
    holed.indices.erase(holed.indices.begin(), holed.indices.begin() + 6); // one face gone
    const MeshClosure h = meshClosure(holed);
    EXPECT_EQ(h.open, 4u) << "one triangle of each neighbouring face meets the hole";
    EXPECT_EQ(h.misWound, 0u);
    Scene flipped = solidBox();
    std::swap(flipped.indices[1], flipped.indices[2]); // one face turned inside out
    std::swap(flipped.indices[4], flipped.indices[5]);
    const MeshClosure f = meshClosure(flipped);
    EXPECT_EQ(f.open, 0u);
    EXPECT_EQ(f.misWound, 6u) << "the face and a triangle of each neighbour";
    EXPECT_EQ(meshClosure(courtyard()).open, 2u) << "the paved floor is an open quad";
}

TEST(Framing, AutomaticExposureBringsPhotometricLightsToTheDefaultSun) {
    Scene s = solidBox();
    const auto withLight = [&](Light l) {
        s.lights = {l};
        return automaticExposure(s);
    };
    EXPECT_EQ(withLight({.type = LightType::Directional, .intensity = 2.0f}), 0.0f);
    EXPECT_EQ(withLight({.type = LightType::Directional, .intensity = 7.9f}), 0.0f)
        << "within a factor 4: authored for display";
    EXPECT_EQ(withLight({.type = LightType::Directional, .intensity = 0.6f}), 0.0f);
    EXPECT_EQ(withLight({.type = LightType::Directional, .intensity = 9.0f}), -2.0f)
        << "log2(2 / 9) = -2.17, to half a stop";
    EXPECT_EQ(withLight({.type = LightType::Directional, .intensity = 100000.0f}), -15.5f);
    EXPECT_EQ(withLight({.type = LightType::Directional, .intensity = 0.01f}), 7.5f);
    // 4000 cd, 5 from the subject's centre (0, 2, 0): 160 lux, log2(2 / 160) = -6.32.
    EXPECT_EQ(withLight({.type = LightType::Point, .position = {0, 2, 5}, .intensity = 4000.0f}),
              -6.5f);
    EXPECT_EQ(withLight({.type = LightType::Point,
                         .position = {0, 2, 5},
                         .color = glm::vec3(0.0f, 0.5f, 0.0f),
                         .intensity = 4000.0f}),
              -5.5f)
        << "its brightest channel counts";
}

TEST(Framing, DoubleSidedMakesEveryMaterialDoubleSided) {
    Scene s = room(true);
    for (Material& m : s.materials)
        m.doubleSided = false;
    applySceneEdits(s, {.doubleSided = true});
    for (const Material& m : s.materials)
        EXPECT_TRUE(m.doubleSided) << m.name;
}

// The footprint a room covers is the box of the walls its rays meet, wherever in the room the
// candidate stands: a room the width of the ground along one side covers 10 x 3.4 of 10 x 10,
// measured from a candidate off its centre (a box taken through the candidate, mirrored, would
// poke out of the ground and cover less).
TEST(Framing, ARoomsCoverageIsTheBoxOfItsWalls) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = mb.material("m", glm::vec3(0.5f));
    mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, m);
    mb.box(boxAt({0, 1, -3.3f}, glm::vec3(10.0f, 2.0f, 3.4f)), m);
    for (size_t t = 6; t + 2 < s.indices.size(); t += 3)
        std::swap(s.indices[t + 1], s.indices[t + 2]); // walls facing in
    const ViewMeasure v = measureView(s, subjectBounds(s));
    ASSERT_TRUE(v.room.has_value());
    const glm::vec2 offCentre(v.room->position.x, v.room->position.z + 3.3f);
    EXPECT_GT(glm::length(offCentre), 0.05f) << "the test needs a candidate off the centre";
    EXPECT_NEAR(v.room->coverage, 10.0f * 3.4f / 100.0f, 2e-3f);
}

TEST(Framing, AnInsideOutBoxOnAWideGroundIsAMisWoundModelNotARoom) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = mb.material("m", glm::vec3(0.5f));
    mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, m);
    mb.box(boxAt({0, 1, 0}, glm::vec3(2.0f)), m);
    for (size_t t = 6; t + 2 < s.indices.size(); t += 3)
        std::swap(s.indices[t + 1], s.indices[t + 2]); // the box inside out
    const ViewMeasure v = measureView(s, subjectBounds(s));
    ASSERT_TRUE(v.room.has_value()) << "from inside, its walls face in";
    EXPECT_LT(v.room->coverage, 0.1f);
    EXPECT_FALSE(v.interior());
    EXPECT_NEAR(measureView(room(true), subjectBounds(room(true))).room->coverage, 1.0f, 1e-3f);
    // A larger inside-out box, between a quarter and a half of the footprint: still no room.
    Scene wide;
    MeshBuilder wb(wide);
    const uint32_t wm = wb.material("m", glm::vec3(0.5f));
    wb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, wm);
    wb.box(boxAt({0, 1, 0}, glm::vec3(6.4f, 2.0f, 6.4f)), wm);
    for (size_t t = 6; t + 2 < wide.indices.size(); t += 3)
        std::swap(wide.indices[t + 1], wide.indices[t + 2]);
    const ViewMeasure w = measureView(wide, subjectBounds(wide));
    ASSERT_TRUE(w.room.has_value());
    EXPECT_GT(w.room->coverage, 0.25f);
    EXPECT_LT(w.room->coverage, 0.5f);
    EXPECT_FALSE(w.interior());
}

// The camera a viewer follows as the scene plays: the file's own, never one Penumbra framed
// (which holds the first frame's view), nor an index past the cameras or the automatic view's -1.
TEST(Framing, OnlyAFilesOwnCameraIsFollowed) {
    Scene s;
    s.cameras = {{.name = "auto", .automatic = true}, {.name = "eye"}, {.name = "other"}};
    EXPECT_FALSE(ownCamera(s, 0).has_value());
    EXPECT_EQ(ownCamera(s, 1), std::optional<size_t>(1));
    EXPECT_EQ(ownCamera(s, 2), std::optional<size_t>(2));
    EXPECT_FALSE(ownCamera(s, 3).has_value());
    EXPECT_FALSE(ownCamera(s, -1).has_value());
}
