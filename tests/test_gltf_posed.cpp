// Animated glTF scenes posed at a time (issue 59): the loader samples the chosen animation and
// flattens the posed nodes, so meshes, children, lights and cameras move. Expected positions are
// worked out here by hand (a straight slide, a turn about y, a Hermite step), not by the loader's
// own code; malformed animations are refused with the file and the JSON path.
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "posed_gltf.h"
#include "scene/builtin_scenes.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

constexpr float kFloat = 5e-6f; // world coordinates of a few units, in float

int floats(GltfBuilder& b, const std::vector<float>& v, const char* type) {
    const size_t per = std::string(type) == "SCALAR" ? 1 : std::string(type) == "VEC3" ? 3 : 4;
    return floatAccessor(b, v, type, per);
}

J channel(int sampler, int node, const char* path) {
    return {{"sampler", sampler}, {"target", {{"node", node}, {"path", path}}}};
}
J sampler(int input, int output, const char* interpolation = "LINEAR") {
    return {{"input", input}, {"output", output}, {"interpolation", interpolation}};
}

// The mover: a small triangle (0,0,0), (0.5,0,0), (0,0,0.5) in its node's space.
const std::vector<glm::vec3> kMoverCorners = {{0, 0, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}};

struct Rig {
    GltfBuilder b;
    int mover = -1, arm = -1; // nodes: the mover under the arm, the arm a root
};

// A ground, an arm at the origin (a point light child at (0, 2, 0) of the mover) and the mover
// 2 units along the arm's x; "slide" moves the mover from (2, 1, 0) to (6, 1, 0) over 2 s,
// "spin" turns the arm a quarter turn about +y over 1 s.
Rig rig() {
    Rig r;
    GltfBuilder& b = r.b;
    b.ground();
    const int tri = b.positions({0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f});
    const int lamp = b.node(
        {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {0, 2, 0}}},
        false);
    r.mover =
        b.node({{"mesh", b.mesh(tri)}, {"translation", {2, 3, 0}}, {"children", {lamp}}}, false);
    r.arm = b.node({{"children", {r.mover}}});
    b.j["extensions"] = {
        {"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 5.0}}}}}}};
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    const int slideTimes = keyframeTimes(b, {0.0f, 2.0f});
    const int slideValues = floats(b, {2, 1, 0, 6, 1, 0}, "VEC3");
    const float h = std::sqrt(0.5f);
    const int spinTimes = keyframeTimes(b, {0.0f, 1.0f});
    const int spinValues = floats(b, {0, 0, 0, 1, 0, h, 0, h}, "VEC4");
    b.j["animations"] = {{{"name", "slide"},
                          {"channels", {channel(0, r.mover, "translation")}},
                          {"samplers", {sampler(slideTimes, slideValues)}}},
                         {{"name", "spin"},
                          {"channels", {channel(0, r.arm, "rotation")}},
                          {"samplers", {sampler(spinTimes, spinValues)}}}};
    return r;
}

fs::path write(GltfBuilder& b, const std::string& name) {
    return b.writeGltf(scratchDir("posed", name, true) / "a.gltf");
}

// Every corner of the mover, placed by `world`, is a vertex of the scene.
void expectMoverAt(const Scene& s, const std::function<glm::vec3(glm::vec3)>& world,
                   const std::string& what) {
    for (const glm::vec3& corner : kMoverCorners) {
        const glm::vec3 want = world(corner);
        float nearest = INFINITY;
        for (const Vertex& v : s.vertices)
            nearest = std::min(nearest, glm::length(v.position - want));
        EXPECT_LT(nearest, kFloat)
            << what << ": no vertex at (" << want.x << ", " << want.y << ", " << want.z << ")";
    }
}

using Bad = Refusal<Rig>;

} // namespace

TEST(GltfPosed, ANodeIsPosedAtTheTimeAndHeldPastItsEnds) {
    Rig r = rig();
    const fs::path f = write(r.b, "slide");
    for (const double t : {0.0, 0.5, 1.25, 2.0, 7.0}) {
        const float x = 2.0f + 2.0f * static_cast<float>(std::min(t, 2.0));
        const Scene s = loadAt(f, t);
        EXPECT_EQ(s.animation, "slide");
        EXPECT_EQ(s.time, t);
        expectMoverAt(
            s, [&](glm::vec3 p) { return p + glm::vec3(x, 1, 0); },
            "slide at " + std::to_string(t));
        // The point light is the mover's child, 2 above it.
        ASSERT_EQ(s.lights.size(), 1u);
        EXPECT_NEAR(glm::length(s.lights[0].position - glm::vec3(x, 3, 0)), 0.0f, kFloat) << t;
    }
}

TEST(GltfPosed, WithoutATimeTheNodesRestAndTheWarningSaysHowToPoseThem) {
    Rig r = rig();
    const fs::path f = write(r.b, "rest");
    std::vector<std::string> warnings;
    const Scene s = loadAt(f, std::nullopt, "", &warnings);
    EXPECT_FALSE(s.time.has_value());
    EXPECT_EQ(s.animation, "slide");
    EXPECT_EQ(s.animationDuration, 2.0f);
    expectMoverAt(
        s, [](glm::vec3 p) { return p + glm::vec3(2, 3, 0); }, "at rest");
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("2 animation(s); the scene is drawn at rest (--time T poses it in "
                               "animation 'slide', 2 s long)"),
              std::string::npos)
        << warnings[0];
    // Posed, it says nothing.
    warnings.clear();
    loadAt(f, 1.0, "", &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(GltfPosed, ChildrenAndLightsFollowATurningParentChosenByNameOrIndex) {
    Rig r = rig();
    const fs::path f = write(r.b, "spin");
    for (const std::string& choice : {std::string("spin"), std::string("1")})
        for (const double t : {0.25, 0.5, 1.0}) {
            const Scene s = loadAt(f, t, choice);
            EXPECT_EQ(s.animation, "spin");
            EXPECT_EQ(s.animationDuration, 1.0f);
            // A quarter turn about +y over 1 s, at a constant rate (slerp): (x, z) turns by
            // angle a as x' = x cos a + z sin a, z' = z cos a - x sin a.
            const float a = static_cast<float>(t * std::numbers::pi / 2);
            const auto turn = [a](glm::vec3 p) {
                return glm::vec3(p.x * std::cos(a) + p.z * std::sin(a), p.y,
                                 p.z * std::cos(a) - p.x * std::sin(a));
            };
            expectMoverAt(
                s, [&](glm::vec3 p) { return turn(p + glm::vec3(2, 3, 0)); },
                choice + " at " + std::to_string(t));
            EXPECT_NEAR(glm::length(s.lights[0].position - turn(glm::vec3(2, 5, 0))), 0.0f, kFloat);
        }
}

TEST(GltfPosed, CubicSplineAndNormalizedRotationsThroughTheLoader) {
    Rig r = rig();
    GltfBuilder& b = r.b;
    // y(t) on [0, 2]: from 1 to 3 with slopes 0 and 3 (the tangents are per second and scaled
    // by the span): Hermite with u = t/2: y = h00*1 + h01*3 + h11*2*3.
    const int input = keyframeTimes(b, {0.0f, 2.0f});
    const int output = floats(b,
                              {0, 0, 0, 2, 1, 0, 0, 0, 0, // in-tangent, value, out-tangent
                               0, 3, 0, 2, 3, 0, 0, 0, 0},
                              "VEC3");
    // A quarter turn about +y stored as normalized shorts (32767 is 1).
    const int turnInput = keyframeTimes(b, {0.0f, 1.0f});
    const int16_t h = 23170; // round(32767 * sqrt(1/2))
    const int turn =
        b.accessor(b.view(std::vector<int16_t>{0, 0, 0, 32767, 0, h, 0, h}), 5122, 2, "VEC4", true);
    b.j["animations"].push_back(
        {{"name", "hop"},
         {"channels", {channel(0, r.mover, "translation"), channel(1, r.arm, "rotation")}},
         {"samplers", {sampler(input, output, "CUBICSPLINE"), sampler(turnInput, turn, "STEP")}}});
    const fs::path f = write(b, "hop");
    for (const double t : {0.0, 0.5, 1.0, 1.5}) {
        const double u = t / 2;
        const double y = (2 * u * u * u - 3 * u * u + 1) * 1 + (-2 * u * u * u + 3 * u * u) * 3 +
                         (u * u * u - u * u) * 2 * 3;
        const Scene s = loadAt(f, t, "hop");
        EXPECT_EQ(s.animationDuration, 2.0f) << "the longest channel's, not the last one's";
        // STEP holds no turn until 1 s, then the quarter turn: (x, z) -> (z, -x).
        const bool turned = t >= 1.0;
        expectMoverAt(
            s,
            [&](glm::vec3 p) {
                const glm::vec3 q = p + glm::vec3(2, static_cast<float>(y), 0);
                return turned ? glm::vec3(q.z, q.y, -q.x) : q;
            },
            "hop at " + std::to_string(t));
    }
}

TEST(GltfPosed, RotationsOfNormalizedSignedBytesTurnBothWays) {
    Rig r = rig();
    // A quarter turn about -y as signed bytes (127 is 1, -90 about -0.709): the sampler
    // normalizes the keyframe, so the turn is exact.
    const int bytes = r.b.accessor(r.b.view(std::vector<int8_t>{0, 0, 0, 127, 0, -90, 0, 90}), 5120,
                                   2, "VEC4", true);
    r.b.j["animations"][1]["samplers"][0]["output"] = bytes;
    r.b.j["animations"][1]["samplers"][0]["interpolation"] = "STEP";
    const Scene s = loadAt(write(r.b, "signed-bytes"), 1.0, "spin");
    // (x, z) -> (-z, x).
    expectMoverAt(
        s, [](glm::vec3 p) { return glm::vec3(-p.z, p.y + 3, p.x + 2); }, "spin back at 1");
}

TEST(GltfPosed, MorphWeightsTakeOneValueAKeyframePerTarget) {
    Rig r = rig();
    GltfBuilder& b = r.b;
    // Two morph targets on the mover's mesh (nudges along x and z).
    const int nudgeX = b.positions({1, 0, 0, 1, 0, 0, 1, 0, 0});
    const int nudgeZ = b.positions({0, 0, 1, 0, 0, 1, 0, 0, 1});
    const int mesh = b.j["nodes"][r.mover]["mesh"];
    b.j["meshes"][mesh]["primitives"][0]["targets"] = {{{"POSITION", nudgeX}},
                                                       {{"POSITION", nudgeZ}}};
    const int input = keyframeTimes(b, {0.0f, 1.0f, 2.0f});
    const int weights = floats(b, {0, 0, 1, 0, 0, 1}, "SCALAR"); // 3 keyframes x 2 targets
    b.j["animations"].push_back({{"name", "morph"},
                                 {"channels", {channel(0, r.mover, "weights")}},
                                 {"samplers", {sampler(input, weights)}}});
    const fs::path f = write(b, "morph");
    const Scene s = loadAt(f, 1.5, "morph");
    EXPECT_EQ(s.animation, "morph");
    EXPECT_EQ(s.animationDuration, 2.0f);
    // A third keyframe of one value too few is refused.
    b.j["accessors"][weights]["count"] = 5;
    const fs::path shorter = write(b, "morph-short");
    expectInputError([&] { loadAt(shorter, 1.5, "morph"); }, shorter.string(),
                     "animations[2].samplers[0]: 5 values for 3 keyframes of 2 components (6 "
                     "expected)");
}

TEST(GltfPosed, ChoosingAnAnimationOrATimeThatIsNotThereIsRefusedOrSaid) {
    Rig r = rig();
    const fs::path f = write(r.b, "choose");
    expectInputError([&] { loadAt(f, 1.0, "walk"); }, "--animation",
                     "'walk' is neither a name nor an index of the animations in '" + f.string() +
                         "' (0 'slide', 1 'spin')");
    expectInputError([&] { loadAt(f, 1.0, "2"); }, "--animation", "0 'slide', 1 'spin'");
    expectInputError([&] { loadAt(f, 1.0, "1abc"); }, "--animation", "'1abc' is neither");
    expectInputError([&] { loadAt(f, -0.5); }, "--time", "-0.5 is not a time in seconds from 0");
    expectInputError([&] { loadAt(f, std::nan("")); }, "--time", "is not a time in seconds");
    expectInputError([&] { loadScene("builtin:demo", {.animation = "0"}); }, "--animation",
                     "'builtin:demo' has no animations");
    GltfBuilder still;
    still.ground();
    const fs::path stillFile = write(still, "still");
    expectInputError([&] { loadAt(stillFile, 1.0, "0"); }, "--animation", "has no animations");
    std::vector<std::string> warnings;
    loadAt(stillFile, 1.5, "", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], stillFile.string() +
                               ": --time 1.5: the scene has no animations; it is drawn at rest");
    warnings.clear();
    loadScene("builtin:demo", {.warnings = &warnings, .time = 0.0});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], "builtin:demo: --time 0: the scene has no animations; it is drawn at "
                           "rest");
}

TEST(GltfPosed, ChannelsOfExtensionsAndWithoutANodeAreSkipped) {
    Rig r = rig();
    r.b.j["animations"][0]["channels"].push_back(
        {{"sampler", 0}, {"target", {{"path", "translation"}}}}); // no node: ignored (spec)
    r.b.j["animations"][1]["channels"].push_back(
        {{"sampler", 0}, {"target", {{"node", r.mover}, {"path", "pointer"}}}});
    const fs::path f = write(r.b, "skipped");
    std::vector<std::string> warnings;
    const Scene s = loadAt(f, 1.0, "spin", &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], f.string() + ": animations[1].channels[1].target.path: 'pointer' is "
                                        "not animated here (only translation, rotation, scale "
                                        "and weights); the channel is skipped");
    expectMoverAt(
        s, [](glm::vec3 p) { return glm::vec3(p.z, p.y + 3, -p.x - 2); }, "spin at 1");
}

namespace {

class GltfPosedRefused : public ::testing::TestWithParam<Bad> {};

} // namespace

TEST_P(GltfPosedRefused, WithTheFileAndItsJsonPath) {
    Rig r = rig();
    GetParam().change(r);
    const fs::path f = write(r.b, std::string("refused-") + GetParam().name);
    expectRefusedAtRestAndPosed(f, GetParam().expected, "1");
}

INSTANTIATE_TEST_SUITE_P(
    Animations, GltfPosedRefused,
    ::testing::Values(
        Bad{"no_channels", [](Rig& r) { r.b.j["animations"][1]["channels"] = J::array(); },
            "animations[1].channels: empty; an animation has at least one"},
        Bad{"no_samplers", [](Rig& r) { r.b.j["animations"][0]["samplers"] = J::array(); },
            "animations[0].samplers: empty; an animation has at least one"},
        Bad{"keyframes_not_increasing",
            [](Rig& r) {
                r.b.j["animations"][1]["samplers"][0]["input"] = keyframeTimes(r.b, {1, 1});
            },
            "animations[1].samplers[0]: keyframe 1's time 1 is not after keyframe 0's 1"},
        Bad{"times_of_integers",
            [](Rig& r) {
                r.b.j["animations"][0]["samplers"][0]["input"] =
                    r.b.accessor(r.b.view(std::vector<uint8_t>{0, 2, 0, 0}), 5121, 2, "SCALAR");
            },
            "animations[0].samplers[0].input: accessors[7] is SCALAR of integers; keyframe "
            "times are SCALAR floats"},
        Bad{"times_of_vectors",
            [](Rig& r) {
                r.b.j["animations"][0]["samplers"][0]["input"] =
                    floats(r.b, {0, 0, 0, 1, 1, 1}, "VEC3");
            },
            "animations[0].samplers[0].input: accessors[7] is VEC3; keyframe times are SCALAR"},
        Bad{"translation_of_vec4",
            [](Rig& r) {
                r.b.j["animations"][0]["samplers"][0]["output"] =
                    floats(r.b, {0, 0, 0, 1, 1, 1, 1, 1}, "VEC4");
            },
            "animations[0].samplers[0].output: accessors[7] is VEC4 of floats; a translation "
            "takes VEC3 floats"},
        Bad{"scale_of_normalized_shorts",
            [](Rig& r) {
                r.b.j["animations"][0]["channels"][0]["target"]["path"] = "scale";
                r.b.j["animations"][0]["samplers"][0]["output"] = r.b.accessor(
                    r.b.view(std::vector<int16_t>{1, 1, 1, 2, 2, 2}), 5122, 2, "VEC3", true);
            },
            "a scale takes VEC3 floats"},
        Bad{"translation_of_normalized_shorts",
            [](Rig& r) {
                r.b.j["animations"][0]["samplers"][0]["output"] = r.b.accessor(
                    r.b.view(std::vector<int16_t>{1, 1, 1, 2, 2, 2}), 5122, 2, "VEC3", true);
            },
            "animations[0].samplers[0].output: accessors[7] is VEC3 of integers; a translation "
            "takes VEC3 floats"},
        Bad{"rotation_of_plain_shorts",
            [](Rig& r) {
                r.b.j["animations"][1]["samplers"][0]["output"] = r.b.accessor(
                    r.b.view(std::vector<int16_t>{0, 0, 0, 1, 0, 1, 0, 1}), 5122, 2, "VEC4");
            },
            "animations[1].samplers[0].output: accessors[7] is VEC4 of integers; a rotation "
            "takes VEC4 floats or normalized integers"},
        Bad{"too_few_values",
            [](Rig& r) {
                r.b.j["animations"][0]["samplers"][0]["output"] = floats(r.b, {2, 1, 0}, "VEC3");
            },
            "animations[0].samplers[0]: 3 values for 2 keyframes of 3 components (6 expected)"},
        Bad{"cubic_without_tangents",
            [](Rig& r) { r.b.j["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE"; },
            "6 values for 2 keyframes of 3 components with in- and out-tangents (18 expected)"},
        Bad{"unknown_interpolation",
            [](Rig& r) { r.b.j["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH"; },
            "animations[0].samplers[0].interpolation: 'SMOOTH' is not LINEAR, STEP or "
            "CUBICSPLINE"},
        Bad{"sampler_out_of_range",
            [](Rig& r) { r.b.j["animations"][1]["channels"][0]["sampler"] = 1; },
            "animations[1].channels[0].sampler: index 1 is out of range (1 samplers)"},
        Bad{"node_out_of_range",
            [](Rig& r) { r.b.j["animations"][0]["channels"][0]["target"]["node"] = 9; },
            "animations[0].channels[0].target.node: index 9 is out of range (4 nodes)"},
        Bad{"input_out_of_range",
            [](Rig& r) { r.b.j["animations"][0]["samplers"][0]["input"] = 40; },
            "animations[0].samplers[0].input: index 40 is out of range"},
        Bad{"output_out_of_range",
            [](Rig& r) { r.b.j["animations"][1]["samplers"][0]["output"] = 41; },
            "animations[1].samplers[0].output: index 41 is out of range"},
        Bad{"animated_matrix",
            [](Rig& r) {
                r.b.j["nodes"][r.arm]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
            },
            "animations[1].channels[0].target.node: nodes[3] has a matrix; an animated node has "
            "translation, rotation and scale instead"},
        Bad{"target_twice",
            [](Rig& r) {
                r.b.j["animations"][0]["channels"].push_back(channel(0, r.mover, "translation"));
            },
            "animations[0].channels[1].target: nodes[2]'s translation is animated twice by this "
            "animation"},
        Bad{"weights_without_morph_targets",
            [](Rig& r) {
                r.b.j["animations"][0]["channels"][0]["target"]["path"] = "weights";
                r.b.j["animations"][0]["samplers"][0]["output"] = floats(r.b, {0, 1}, "SCALAR");
            },
            "animations[0].samplers[0]: animates the weights of nodes[2], which has no morph "
            "targets"},
        Bad{"rotation_not_finite",
            [](Rig& r) {
                r.b.j["animations"][1]["samplers"][0]["output"] =
                    floats(r.b, {0, 0, 0, 1, 0, NAN, 0, 1}, "VEC4");
            },
            "animations[1].samplers[0]: value 5 is not a finite number"}),
    [](const auto& row) { return std::string(row.param.name); });

// builtin:pendulum, posed from its constants alone: the ball's centre at the swing's closed form,
// straight below the pivot a quarter period in, at the far end half a period in.
TEST(GltfPosed, TheBuiltinPendulumSwingsAsItsConstantsSay) {
    using namespace penumbra::builtin;
    for (const double t : {0.0, 0.25, 0.5, 1.0, 1.7, 12.5}) {
        const Scene s = loadScene("builtin:pendulum", {.time = t, .animation = "swing"});
        EXPECT_EQ(s.animation, "swing");
        EXPECT_EQ(s.animationDuration, float(kPendulumPeriod));
        EXPECT_EQ(s.time, t);
        const double angle = kPendulumAmplitude * std::cos(2 * std::numbers::pi * t / 2.0);
        const glm::vec3 centre =
            kPendulumPivot +
            kPendulumLength * glm::vec3(float(std::sin(angle)), -float(std::cos(angle)), 0);
        size_t onTheBall = 0;
        for (const Vertex& v : s.vertices)
            onTheBall += std::abs(glm::length(v.position - centre) - kPendulumBobRadius) < 1e-5f;
        EXPECT_GE(onTheBall, 100u) << "the ball's surface around its centre at " << t << " s";
    }
    const glm::vec3 lowest = pendulumBob(0.5);
    EXPECT_NEAR(lowest.x, 0.0f, 1e-6f);
    EXPECT_NEAR(lowest.y - kPendulumBobRadius, 0.2f, 1e-6f) << "a hand's width above the floor";
    EXPECT_NEAR(pendulumBob(1.0).x, -kPendulumLength * std::sin(0.8f), 1e-5f);
    expectInputError([] { loadScene("builtin:pendulum", {.animation = "walk"}); }, "--animation",
                     "'builtin:pendulum' has one animation, 0 'swing'");
    std::vector<std::string> warnings;
    loadScene("builtin:pendulum", {.warnings = &warnings, .time = 1.0, .animation = "0"});
    EXPECT_TRUE(warnings.empty());
}
