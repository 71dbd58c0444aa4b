// Generated scene families (scene/generated.h): the spec's syntax and its errors, the same scene
// from the same spec, every family's seeds valid, varied (every light type, sizes zero and not)
// and showing a cast shadow in their own camera's view, each family holding what it promises.
#include "generated_scenes.h"
#include "penumbra/error.h"
#include "scene/builtin_scenes.h"
#include "scene/first_picture.h"
#include "scene/framing.h"
#include "scene/gen_families.h"
#include "scene/generated.h"
#include "scene/mesh_closure.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <set>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kSeeds = 24;

std::string specOf(std::string_view family, int seed) {
    return "builtin:gen/" + std::string(family) + "?seed=" + std::to_string(seed);
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The scene's surfaces after the ground (its first quad): triangles joined by shared corners
// (vertices welded on a grid of 1e-4), each surface's triangle indices.
std::vector<std::vector<uint32_t>> surfaces(const Scene& s) {
    std::map<std::array<int64_t, 3>, uint32_t> cells;
    std::vector<uint32_t> parent(s.vertices.size());
    const auto find = [&](uint32_t v) {
        while (parent[v] != v)
            v = parent[v] = parent[parent[v]];
        return v;
    };
    for (uint32_t v = 4; v < s.vertices.size(); ++v) {
        parent[v] = v;
        const glm::vec3 p = s.vertices[v].position * 1e4f;
        const std::array<int64_t, 3> cell{std::llround(p.x), std::llround(p.y), std::llround(p.z)};
        for (int n = 0; n < 27; ++n) {
            const auto it =
                cells.find({cell[0] + n % 3 - 1, cell[1] + n / 3 % 3 - 1, cell[2] + n / 9 - 1});
            if (it != cells.end())
                parent[find(v)] = find(it->second);
        }
        cells.emplace(cell, v);
    }
    for (size_t t = 6; t < s.indices.size(); t += 3)
        for (int k = 1; k < 3; ++k)
            parent[find(s.indices[t + k])] = find(s.indices[t]);
    std::map<uint32_t, std::vector<uint32_t>> byRoot;
    for (uint32_t t = 2; t < s.triangleCount(); ++t)
        byRoot[find(s.indices[3 * t])].push_back(t);
    std::vector<std::vector<uint32_t>> out;
    for (auto& [root, triangles] : byRoot)
        out.push_back(std::move(triangles));
    return out;
}

} // namespace

TEST(Generated, TheSpecIsReadOrRefusedWithItsReason) {
    const GeneratedSpec plain = parseGeneratedSpec("plates");
    EXPECT_EQ(plain.family, "plates");
    EXPECT_EQ(plain.seed, 1u);
    EXPECT_EQ(plain.scale, 1.0f);
    const GeneratedSpec full = parseGeneratedSpec("long?seed=9223372036854775807&scale=0.001");
    EXPECT_EQ(full.seed, 9223372036854775807ull);
    EXPECT_EQ(full.scale, 0.001f);
    EXPECT_EQ(parseGeneratedSpec("open?scale=10000&seed=0").seed, 0u);
    const auto refused = [](const std::string& spec, const std::string& why) {
        try {
            loadScene("builtin:gen/" + spec);
            ADD_FAILURE() << spec << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.subject(), "builtin:gen/" + spec);
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
    };
    refused("nope?seed=1", "no such generated family 'nope' (families: plates, spheres");
    refused("", "no such generated family");
    refused("plates?seed=-1", "seed '-1'");
    refused("plates?seed=1.5", "seed '1.5'");
    refused("plates?seed=", "seed ''");
    refused("plates?seed=9223372036854775808", "seed '9223372036854775808'");
    refused("plates?seed=99999999999999999999999", "seed");
    refused("plates?scale=0.0009", "scale '0.0009' is not a number from 0.001 to 10000");
    refused("plates?scale=10001", "scale '10001'");
    refused("plates?scale=nan", "scale 'nan'");
    refused("plates?scale=2x", "scale '2x'");
    refused("plates?colour=red", "unknown key 'colour' (keys: seed, scale)");
    refused("plates?seed", "seed ''");
    // Every key once, every pair whole: no silent last-one-wins, no stray '&'.
    refused("plates?seed=1&seed=2", "'seed' given twice");
    refused("plates?scale=2&seed=3&scale=3", "'scale' given twice");
    refused("plates?seed=1&", "an empty key=value pair");
    refused("plates?&seed=1", "an empty key=value pair");
    refused("plates?seed=1&&scale=2", "an empty key=value pair");
    refused("plates?", "nothing after '?'");
}

TEST(Generated, ASpecGivesTheSameSceneEveryTimeAndSeedsDiffer) {
    for (std::string_view family : generatedFamilies()) {
        const Scene a = loadScene(specOf(family, 5)), b = loadScene(specOf(family, 5));
        EXPECT_EQ(a.name, "gen/" + std::string(family) + "?seed=5");
        ASSERT_EQ(a.vertices.size(), b.vertices.size()) << family;
        for (size_t i = 0; i < a.vertices.size(); ++i)
            ASSERT_EQ(a.vertices[i].position, b.vertices[i].position) << family;
        EXPECT_EQ(a.indices, b.indices) << family;
        EXPECT_EQ(a.lights.front().direction, b.lights.front().direction) << family;
        EXPECT_EQ(a.cameras.front().position, b.cameras.front().position) << family;
        const Scene c = loadScene(specOf(family, 6));
        EXPECT_TRUE(c.vertices.size() != a.vertices.size() ||
                    c.vertices.front().position != a.vertices.front().position ||
                    c.cameras.front().position != a.cameras.front().position)
            << family << ": seeds 5 and 6 alike";
    }
    // The family is part of the stream: one seed, two families, two lights.
    EXPECT_NE(loadScene(specOf("plates", 3)).lights.front().direction,
              loadScene(specOf("open", 3)).lights.front().direction);
}

// Every family over kSeeds seeds: finite geometry, one light and one camera, a cast shadow in the
// camera's view (measured with rays) in nearly every seed, and across the seeds every light type
// the family draws, with and without a size.
TEST(Generated, EverySeedIsAValidSceneThatShowsAShadow) {
    const std::map<std::string_view, std::set<LightType>> kinds = {
        {"plates", {LightType::Directional, LightType::Spot, LightType::Point}},
        {"spheres", {LightType::Directional, LightType::Spot, LightType::Point}},
        {"leaves", {LightType::Directional, LightType::Spot, LightType::Point}},
        {"open", {LightType::Directional, LightType::Spot, LightType::Point}},
        {"curved", {LightType::Directional, LightType::Spot, LightType::Point}},
        {"interior", {LightType::Directional, LightType::Spot, LightType::Point}},
        {"grazing", {LightType::Directional, LightType::Spot}},
        {"long", {LightType::Directional}},
        {"clutter", {LightType::Spot, LightType::Point}}};
    ASSERT_EQ(kinds.size(), generatedFamilies().size());
    for (std::string_view family : generatedFamilies()) {
        std::set<LightType> seen;
        int sized = 0, shadowed = 0;
        for (int seed = 1; seed <= kSeeds; ++seed) {
            const Scene s = loadScene(specOf(family, seed));
            ASSERT_GT(s.triangleCount(), 2u) << s.name;
            for (const Vertex& v : s.vertices)
                ASSERT_TRUE(finite(v.position) && finite(v.normal)) << s.name;
            for (uint32_t i : s.indices)
                ASSERT_LT(i, s.vertices.size()) << s.name;
            ASSERT_EQ(s.lights.size(), 1u) << s.name;
            ASSERT_EQ(s.cameras.size(), 1u) << s.name;
            const Light& l = s.lights.front();
            const Camera& c = s.cameras.front();
            EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-5f) << s.name;
            EXPECT_GT(l.intensity, 0.0f) << s.name;
            EXPECT_LT(c.znear, c.zfar) << s.name;
            EXPECT_GT(glm::length(c.target - c.position), c.znear) << s.name;
            seen.insert(l.type);
            sized += l.hasSize();
            const TriangleBvh bvh(s);
            shadowed += ViewProbe(s, bvh, c).measure(l).castShadow >= 0.005f;
        }
        EXPECT_EQ(seen, kinds.at(family)) << family;
        EXPECT_GE(sized, kSeeds / 2) << family;
        EXPECT_LT(sized, kSeeds) << family << ": some lights without a size";
        EXPECT_GE(shadowed, kSeeds * 9 / 10) << family << ": seeds showing a cast shadow";
    }
}

// `scale` makes the whole scene larger and leaves what the light does to it as it was.
TEST(Generated, AScaledSceneIsTheSameSceneLarger) {
    for (std::string_view family : {"spheres", "clutter", "interior"})
        for (float scale : {0.01f, 250.0f}) {
            const Scene one = loadScene(specOf(family, 4));
            const Scene big =
                loadScene(specOf(family, 4) + "&scale=" + (scale < 1 ? "0.01" : "250"));
            EXPECT_NE(big.name.find("&scale="), std::string::npos);
            ASSERT_EQ(one.vertices.size(), big.vertices.size());
            for (size_t i = 0; i < one.vertices.size(); i += 7)
                EXPECT_NEAR(
                    glm::distance(big.vertices[i].position, scale * one.vertices[i].position), 0.0f,
                    1e-5f * scale * (1.0f + glm::length(one.vertices[i].position)));
            const Light &a = one.lights.front(), &b = big.lights.front();
            EXPECT_NEAR(b.radius, scale * a.radius, 1e-5f * scale);
            EXPECT_EQ(b.angularDiameter, a.angularDiameter);
            const glm::vec3 at = one.cameras.front().target;
            if (a.type != LightType::Directional) {
                const float before = a.intensity / glm::dot(a.position - at, a.position - at);
                const glm::vec3 bAt = big.cameras.front().target;
                const float after = b.intensity / glm::dot(b.position - bAt, b.position - bAt);
                EXPECT_NEAR(after, before, 1e-3f * before) << family;
            }
            EXPECT_NEAR(big.cameras.front().zfar, scale * one.cameras.front().zfar,
                        1e-4f * scale * one.cameras.front().zfar);
        }
}

// Each family holds what its name promises.
TEST(Generated, EachFamilyHoldsWhatItPromises) {
    int misWound = 0, openEdged = 0, alpha = 0, inside = 0, grazing = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        Scene open = loadScene(specOf("open", seed));
        open.indices.erase(open.indices.begin(), open.indices.begin() + 6); // the ground
        const MeshClosure closure = meshClosure(open);
        openEdged += closure.open > 0;
        misWound += closure.misWound > 0;
        const Scene leaves = loadScene(specOf("leaves", seed));
        for (const Material& m : leaves.materials)
            alpha += m.alphaMode == AlphaMode::Mask && m.baseColorTexture >= 0;
        // Seen from inside: the camera within the walls, a ceiling above it, walls without windows
        // beside and behind it.
        const Scene room = loadScene(specOf("interior", seed));
        const glm::vec3 eye = room.cameras.front().position;
        const TriangleBvh walls(room);
        bool enclosed = walls.firstHit({.origin = eye, .direction = {0, 1, 0}}).has_value();
        for (const glm::vec3 d : {glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, -1, 0)})
            enclosed = enclosed && walls.firstHit({.origin = eye, .direction = d}).has_value();
        inside += enclosed && glm::all(glm::lessThan(room.bounds().min, eye)) &&
                  glm::all(glm::lessThan(eye, room.bounds().max));
        const Light& low = loadScene(specOf("grazing", seed)).lights.front();
        grazing += low.type == LightType::Spot ||
                   (-low.direction.y <= std::sin(glm::radians(12.0f)) + 1e-6f &&
                    -low.direction.y >= std::sin(glm::radians(3.0f)) - 1e-6f);
        const Scene far = loadScene(specOf("long", seed));
        EXPECT_GE(far.bounds().extent().z, 300.0f);
        const Scene clutter = loadScene(specOf("clutter", seed));
        EXPECT_GE(clutter.triangleCount(), 30u * 12u / 2);
        const Bounds b = subjectBounds(clutter);
        EXPECT_LE(clutter.lights.front().position.y, b.max.y + 1.0f + 1e-4f) << "close";
    }
    EXPECT_GE(openEdged, kSeeds / 2);
    EXPECT_GE(misWound, kSeeds / 4);
    EXPECT_EQ(alpha, kSeeds);
    EXPECT_EQ(inside, kSeeds);
    EXPECT_EQ(grazing, kSeeds);
}

// Over 200 seeds, the shares the docs give: a grazing scene's light is a low spot in about 3 of
// 10; a long view looks 40 to 120 ahead, near and far; a room's table stands left and right.
TEST(Generated, TheDrawsFollowTheDocumentedShares) {
    int spots = 0, tablesLeft = 0, tablesRight = 0;
    float nearest = 1e9f, farthest = 0.0f;
    for (int seed = 1; seed <= 200; ++seed) {
        spots += loadScene(specOf("grazing", seed)).lights.front().type == LightType::Spot;
        // A room's camera looks at its table, anywhere in the middle half of the room's width.
        const Scene room = loadScene(specOf("interior", seed));
        const float tableX = room.cameras.front().target.x / room.bounds().max.x;
        EXPECT_LE(std::abs(tableX), 0.5f) << room.name;
        tablesLeft += tableX<-0.25f, tablesRight += tableX> 0.25f;
        const Camera c = loadScene(specOf("long", seed)).cameras.front();
        const float ahead = c.position.z - c.target.z - 10.0f; // the camera stands at z = 10
        EXPECT_GE(ahead, 40.0f - 10.0f);
        EXPECT_LE(ahead, 120.0f);
        nearest = std::min(nearest, ahead), farthest = std::max(farthest, ahead);
    }
    EXPECT_GE(spots, 40);
    EXPECT_LE(spots, 80);
    EXPECT_LT(nearest, 50.0f);
    EXPECT_GT(farthest, 110.0f);
    EXPECT_GE(tablesLeft, 25);
    EXPECT_GE(tablesRight, 25);
}

// A grazing scene's sun, 3 degrees up at the least, lays every block's shadow on its ground (the
// ramp's, up to 2 high, may run off it); a
// room's sun comes through the window at -z, 20 to 55 degrees up, aside by at most half its
// run; a room is clear from wall to wall: from its centre, +x is as far as -x (or open).
TEST(Generated, ShadowsFallOnTheGroundAndSunsThroughTheWindow) {
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Scene low = loadScene(specOf("grazing", seed));
        const Light& sun = low.lights.front();
        const float half = low.vertices[0].position.x > 0 ? low.vertices[0].position.x
                                                          : -low.vertices[0].position.x;
        if (sun.type == LightType::Directional)
            for (size_t v = 4; v + 4 < low.vertices.size(); ++v) { // the blocks, not the ramp
                const glm::vec3 p = low.vertices[v].position;
                const glm::vec3 ground = p - (p.y / sun.direction.y) * sun.direction;
                EXPECT_LE(std::max(std::abs(ground.x), std::abs(ground.z)), half + 1e-3f)
                    << low.name << " vertex " << v;
            }
        const Scene room = loadScene(specOf("interior", seed));
        const Light& l = room.lights.front();
        if (l.type == LightType::Directional) {
            ASSERT_GT(l.direction.z, 0.0f) << room.name;
            const float up = std::atan(-l.direction.y / l.direction.z);
            EXPECT_GE(up, glm::radians(20.0f) - 1e-4f) << room.name;
            EXPECT_LE(up, glm::radians(55.0f) + 1e-4f) << room.name;
            EXPECT_LE(std::abs(l.direction.x / l.direction.z), 0.5f + 1e-5f) << room.name;
        }
        const Bounds b = room.bounds();
        const glm::vec3 centre(0.0f, 0.5f * b.max.y, 0.0f);
        const TriangleBvh walls(room);
        const auto left = walls.firstHit({.origin = centre, .direction = {-1, 0, 0}});
        const auto right = walls.firstHit({.origin = centre, .direction = {1, 0, 0}});
        ASSERT_TRUE(left.has_value()) << room.name;
        if (right) {
            EXPECT_GE(right->distance, left->distance - 1e-4f) << room.name;
        }
    }
}

// The leaf texture holds as many leaves as asked: none is no leaf; more cover more.
TEST(Generated, TheLeafTextureHoldsTheLeavesAsked) {
    const auto covered = [](int count) {
        const TextureImage image = builtin::leafImage(7, count);
        size_t n = 0;
        for (size_t i = 3; i < image.rgba.size(); i += 4)
            n += image.rgba[i] > 0;
        return n;
    };
    EXPECT_EQ(covered(0), 0u);
    EXPECT_GT(covered(1), 0u);
    EXPECT_LT(covered(60), covered(200));
}

// A camera drawn round the content keeps every object in view (all but the ground's corners
// project inside the 16:9 frame, in front of the camera).
TEST(Generated, TheCameraKeepsTheContentInView) {
    for (std::string_view family : {"plates", "spheres", "leaves", "open", "curved", "clutter"})
        for (int seed = 1; seed <= kSeeds; ++seed) {
            const Scene s = loadScene(specOf(family, seed));
            const Camera& c = s.cameras.front();
            const glm::mat4 view = glm::lookAt(c.position, c.target, c.up);
            const glm::mat4 projection = glm::perspective(c.yfov, 16.0f / 9.0f, c.znear, c.zfar);
            int outside = 0;
            for (size_t v = 4; v < s.vertices.size(); ++v) {
                const glm::vec4 clip = projection * view * glm::vec4(s.vertices[v].position, 1);
                outside += !(clip.w > 0.0f && std::abs(clip.x) <= clip.w * 1.0001f &&
                             std::abs(clip.y) <= clip.w * 1.0001f);
            }
            EXPECT_EQ(outside, 0) << s.name;
        }
}

// The camera round the content centres on it and stands as near as keeps a sphere round it in the
// view's height: the content is the family's footprint and every vertex after the ground's (so
// nothing a family adds is left out of the light's aim or the frame, and nothing else is in).
TEST(Generated, TheCameraFramesTheFootprintAndEveryObject) {
    const auto check = [](std::string_view family, int seed, Bounds content) {
        const Scene s = loadScene(specOf(family, seed));
        for (size_t v = 4; v < s.vertices.size(); ++v)
            content.grow(s.vertices[v].position);
        const Camera& c = s.cameras.front();
        const float radius = 0.5f * glm::length(content.extent());
        EXPECT_LT(glm::length(c.target - content.center()), 1e-4f * radius) << s.name;
        EXPECT_NEAR(glm::length(c.position - c.target) * std::sin(0.5f * c.yfov), radius,
                    1e-4f * radius)
            << s.name;
    };
    for (int seed = 1; seed <= kSeeds; ++seed) {
        for (std::string_view family : {"plates", "spheres", "leaves", "open", "curved"})
            check(family, seed, {.min = {-3, 0, -3}, .max = {3, 0, 3}});
        check("grazing", seed, {.min = {-4, 0, -4}, .max = {4, 0.5f, 4}});
    }
}

// Each object of the curved family is one surface: 2 to 5 of them a seed (a corrugated sheet's
// strips meet along their creases; spheres, tori and tubes are whole).
TEST(Generated, EachCurvedObjectIsOneSurface) {
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Scene s = loadScene(specOf("curved", seed));
        EXPECT_GE(surfaces(s).size(), 2u) << s.name;
        EXPECT_LE(surfaces(s).size(), 5u) << s.name;
    }
}

// 1 to 5 spheres, each one surface; the open family's walls stand alone (a box replaced by a
// wall is gone: no box has a wall's centre), in some seeds.
TEST(Generated, SpheresAndWallsAreAsManyAsTheDocsSay) {
    int walls = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Scene balls = loadScene(specOf("spheres", seed));
        EXPECT_GE(surfaces(balls).size(), 1u) << balls.name;
        EXPECT_LE(surfaces(balls).size(), 5u) << balls.name;
        const Scene open = loadScene(specOf("open", seed));
        const std::vector<std::vector<uint32_t>> parts = surfaces(open);
        const auto centreOf = [&](const std::vector<uint32_t>& part) {
            glm::vec3 sum(0.0f);
            for (uint32_t t : part)
                for (int k = 0; k < 3; ++k)
                    sum += open.vertices[open.indices[3 * size_t{t} + k]].position;
            return sum / (3.0f * static_cast<float>(part.size()));
        };
        for (const std::vector<uint32_t>& wall : parts) {
            if (wall.size() != 2)
                continue;
            ++walls;
            for (const std::vector<uint32_t>& box : parts)
                if (box.size() == 12) {
                    EXPECT_GT(glm::length(centreOf(box) - centreOf(wall)), 1e-3f)
                        << open.name << ": a wall in a box";
                }
        }
    }
    EXPECT_GT(walls, 0);
}

// Every face of the open family stands upright or lies flat (boxes turned about the vertical,
// walls standing); the plates' slabs are turned any way about the vertical (0 to 90 degrees) and
// every face of theirs is a rectangle.
TEST(Generated, FacesStandAsTheirFamiliesSay) {
    const auto normal = [](const Scene& s, size_t t) {
        const glm::vec3 a = s.vertices[s.indices[t]].position;
        return glm::normalize(glm::cross(s.vertices[s.indices[t + 1]].position - a,
                                         s.vertices[s.indices[t + 2]].position - a));
    };
    int turned = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Scene open = loadScene(specOf("open", seed));
        for (size_t t = 0; t < open.indices.size(); t += 3) {
            const float up = std::abs(normal(open, t).y);
            EXPECT_TRUE(up < 1e-4f || up > 1.0f - 1e-4f) << open.name << " triangle " << t / 3;
        }
        const Scene plates = loadScene(specOf("plates", seed));
        // Slabs, shelves and posts are boxes and quads: rectangles, two triangles of one area.
        const auto area = [&](size_t t) {
            const glm::vec3 a = plates.vertices[plates.indices[t]].position;
            return glm::length(glm::cross(plates.vertices[plates.indices[t + 1]].position - a,
                                          plates.vertices[plates.indices[t + 2]].position - a));
        };
        for (size_t t = 0; t < plates.indices.size(); t += 6)
            EXPECT_NEAR(area(t), area(t + 3), 1e-4f * area(t)) << plates.name << " quad " << t / 6;
        for (size_t t = 0; t < plates.indices.size(); t += 3) {
            const glm::vec3 n = normal(plates, t);
            const float angle = std::fmod(glm::degrees(std::atan2(n.z, n.x)) + 360.0f, 90.0f);
            turned += std::abs(n.y) < 1e-4f && angle > 40.0f && angle < 85.0f;
        }
    }
    EXPECT_GT(turned, 0) << "slab sides between 40 and 85 degrees round";
}

// The lights the docs promise (docs/scenes.md, "Generated scenes"), drawn over a content box: one
// in five without a size, suns 0.25 to 8 degrees wide, spot and bulb radii 0.005 to 0.1 of the
// content's size, each as bright on the content's centre as the default sun (irradiance 2), a
// spot aimed at the centre with a cone that holds the content; the ranges used end to end.
TEST(Generated, LightsAreAsTheDocsSay) {
    const Bounds content{.min = {-3, 0, -3}, .max = {3, 2.5f, 3}};
    const float size = glm::length(content.extent());
    int sizeless = 0, lights = 0;
    float narrowest = 1e9f, widest = 0.0f, smallest = 1e9f, largest = 0.0f;
    float tightest = 10.0f, loosest = 0.0f;
    for (uint64_t seed = 1; seed <= 600; ++seed) {
        GenRandom random(seed * 7919);
        const Light l = gen::drawLight(random, content, {});
        ++lights;
        if (!l.hasSize()) {
            ++sizeless;
            continue;
        }
        if (l.type == LightType::Directional) {
            EXPECT_GE(l.angularDiameter, 0.25f - 1e-5f);
            EXPECT_LE(l.angularDiameter, 8.0f + 1e-4f);
            narrowest = std::min(narrowest, l.angularDiameter);
            widest = std::max(widest, l.angularDiameter);
            continue;
        }
        const float ratio = l.radius / size;
        EXPECT_GE(ratio, 0.005f - 1e-6f);
        EXPECT_LE(ratio, 0.1f + 1e-6f);
        smallest = std::min(smallest, ratio), largest = std::max(largest, ratio);
        const glm::vec3 toCentre = content.center() - l.position;
        EXPECT_NEAR(l.intensity / glm::dot(toCentre, toCentre), 2.0f, 2e-4f) << seed;
        if (l.type != LightType::Spot)
            continue;
        EXPECT_GT(glm::dot(glm::normalize(toCentre), l.direction), 0.9999f) << seed;
        EXPECT_LT(l.outerConeAngle, glm::radians(80.0f)) << seed << ": past one map's cone";
        EXPECT_LT(l.innerConeAngle, l.outerConeAngle);
        for (int k = 0; k < 8; ++k) { // every corner of the content inside the cone
            const glm::vec3 c{k & 1 ? content.max.x : content.min.x,
                              k & 2 ? content.max.y : content.min.y,
                              k & 4 ? content.max.z : content.min.z};
            const float angle = std::acos(glm::dot(glm::normalize(c - l.position), l.direction));
            EXPECT_LE(angle, l.outerConeAngle) << seed << " corner " << k;
            tightest = std::min(tightest, l.outerConeAngle - angle);
        }
        loosest = std::max(loosest, l.outerConeAngle);
    }
    EXPECT_NEAR(double(sizeless) / lights, 0.2, 0.05);
    EXPECT_LT(narrowest, 0.35f);
    EXPECT_GT(widest, 6.0f);
    EXPECT_LT(smallest, 0.007f);
    EXPECT_GT(largest, 0.08f);
    EXPECT_LT(loosest, 1.2f) << "cones wider than the content needs";
}

// Spheres rest on the ground or float above it, never sink into it; a stack's slabs and shelves
// rise one above the other (0.15 to 1.2 apart), so that some stack stands well over the highest
// first layer (1.0).
TEST(Generated, SpheresStandOnTheGroundAndPlatesStack) {
    int resting = 0;
    float highestLayer = 0.0f;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Scene s = loadScene(specOf("spheres", seed));
        for (const std::vector<uint32_t>& surface : surfaces(s)) {
            float lowest = 1e9f;
            for (uint32_t t : surface)
                for (int k = 0; k < 3; ++k)
                    lowest = std::min(lowest, s.vertices[s.indices[3 * t + k]].position.y);
            EXPECT_GE(lowest, -1e-4f) << s.name;
            resting += lowest < 0.02f;
        }
        const Scene p = loadScene(specOf("plates", seed));
        for (const std::vector<uint32_t>& surface : surfaces(p)) {
            float lowest = 1e9f, highest = -1e9f;
            for (uint32_t t : surface)
                for (int k = 0; k < 3; ++k) {
                    const float y = p.vertices[p.indices[3 * t + k]].position.y;
                    lowest = std::min(lowest, y), highest = std::max(highest, y);
                }
            if (highest - lowest < 0.2f) // a slab or a shelf, not a post
                highestLayer = std::max(highestLayer, lowest);
        }
    }
    EXPECT_GE(resting, 3) << "some spheres rest on the ground";
    EXPECT_GT(highestLayer, 2.0f) << "layers stacked on the ones below";
}
