// The crease rule of bias.mode=adaptive (shaders/include/bias.h: creaseTests; its maths in
// test_adaptive_bias.cpp) on boxes standing on a floor under each light type: the acne it takes
// off wide kernels against the ray-traced truth, with nothing lost elsewhere.
#include "analytic_scenes.h"
#include "truth_fixture.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace penumbra;
using penumbra::test::BiasTest;

namespace {

glm::mat4 boxBetween(const glm::vec3& lo, const glm::vec3& hi) {
    return glm::scale(glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)), hi - lo);
}

// Boxes standing on a floor in a ring round the light's foot, seen from high above: the floor
// along every lit face is a concave crease.
Scene boxesOnAFloor(const Light& light) {
    Scene scene;
    scene.name = "boxes on a floor";
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("floor", {0.7f, 0.7f, 0.7f});
    const uint32_t blue = mb.material("boxes", {0.3f, 0.4f, 0.7f});
    mb.quad({-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, {-20, 0, -20}, grey);
    for (int i = 0; i < 6; ++i) {
        const float a = 6.2831853f * float(i) / 6.0f + 0.3f;
        const glm::vec3 c(2.4f * std::cos(a), 0.0f, 2.4f * std::sin(a));
        mb.box(boxBetween(c - glm::vec3(0.4f, 0.0f, 0.5f), c + glm::vec3(0.4f, 1.2f, 0.5f)), blue);
    }
    scene.lights.push_back(light);
    scene.cameras.push_back({.name = "above",
                             .position = {0.0f, 5.5f, 3.0f},
                             .target = {0.0f, 0.0f, 0.0f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

TEST_F(BiasTest, TheCreaseRuleTakesWideKernelsAcneOffCreasesForEveryLightType) {
    const Light spot{.name = "spot",
                     .type = LightType::Spot,
                     .position = {0.5f, 6.0f, 0.8f},
                     .direction = glm::normalize(glm::vec3(-0.5f, -6.0f, -0.8f)),
                     .intensity = 40.0f,
                     .outerConeAngle = 0.9f,
                     .radius = 0.3f};
    const Light point{.name = "bulb",
                      .type = LightType::Point,
                      .position = {0.3f, 3.0f, 0.2f},
                      .intensity = 8.0f,
                      .radius = 0.3f};
    for (const Light& light : {spot, test::acceptanceSun(3.0f), point}) {
        const test::Truth t =
            test::groundTruth(boxesOnAFloor(light),
                              {.width = 320, .height = 240, .shadowMapSize = 1024, .samples = 64});
        for (const auto& [technique, sets] :
             std::vector<std::pair<Technique, std::vector<std::pair<std::string, std::string>>>>{
                 {Technique::Pcf, {{"pcf.size", "11"}}}, {Technique::Pcss, {}}}) {
            auto with = sets, without = sets;
            without.push_back({"bias.crease", "0"});
            const ErrorMetrics on =
                test::errorBeyondBlur(t, test::renderRow(t, technique, with), technique, with);
            const ErrorMetrics off = test::errorBeyondBlur(
                t, test::renderRow(t, technique, without), technique, without);
            const std::string what = light.name + " " + std::string(techniqueName(technique));
            std::printf("%s: acne beyond blur %.3f%% -> %.3f%%, leak %.3f%% -> %.3f%%, RMSE "
                        "%.4f -> %.4f\n",
                        what.c_str(), 100 * off.acneBeyondBlur, 100 * on.acneBeyondBlur,
                        100 * off.leakBeyondBlur, 100 * on.leakBeyondBlur, off.rmse, on.rmse);
            // pcf's 11x11 kernel shows the creases under every light; pcss's search, as wide as
            // the light, under the spot and the bulb (under the 3-degree sun it barely does).
            if (technique == Technique::Pcf) {
                EXPECT_GT(off.acneBeyondBlur, 0.0015) << what << ": no crease acne to take off";
            }
            if (off.acneBeyondBlur > 0.001) {
                EXPECT_LE(on.acneBeyondBlur, 0.3 * off.acneBeyondBlur) << what;
            } else {
                EXPECT_LE(on.acneBeyondBlur, off.acneBeyondBlur) << what;
            }
            EXPECT_LE(on.leakBeyondBlur, off.leakBeyondBlur + 2e-4) << what;
            EXPECT_LT(on.rmse, off.rmse) << what;
        }
    }
}

} // namespace

// A wall the light grazes at 6 degrees. Under lights 24 degrees wide (a sun, and a spot and a
// bulb of radius 2.08 at distance 10) the light straddles the wall's plane: the floor at its foot
// is partly shadowed by it, and the rule must leave the wall's taps alone there (cot 6 deg = 9.5
// is past cot 12 deg = 4.7, creaseLimit's slope for this light, though within bias.crease's 20):
// the floor reads as with the rule off, to the bit. Under the same lights 1 degree wide it lets
// them through (the floor's pixels at the foot move).
TEST_F(BiasTest, TheCreaseRuleLeavesAWallAloneWhereTheLightStraddlesItsPlane) {
    const glm::vec3 travel = glm::normalize(glm::vec3(-0.105f, -1.0f, 0.0f)); // 6 deg off the wall
    const glm::vec3 at = -10.0f * travel; // 10 from the wall's foot
    for (const float degrees : {24.0f, 1.0f}) {
        const float radius = 10.0f * std::sin(glm::radians(0.5f * degrees));
        const std::vector<Light> lights{{.name = "sun",
                                         .type = LightType::Directional,
                                         .direction = travel,
                                         .angularDiameter = degrees},
                                        {.name = "spot",
                                         .type = LightType::Spot,
                                         .position = at,
                                         .direction = travel,
                                         .intensity = 400.0f,
                                         .outerConeAngle = 0.5f,
                                         .radius = radius},
                                        {.name = "bulb",
                                         .type = LightType::Point,
                                         .position = at,
                                         .intensity = 400.0f,
                                         .radius = radius}};
        for (const Light& light : lights) {
            Scene scene;
            scene.name = "a wall grazed by the light";
            MeshBuilder mb(scene);
            mb.quad({-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, {-20, 0, -20},
                    mb.material("floor", {0.7f, 0.7f, 0.7f}));
            mb.box(boxBetween({-0.2f, 0.0f, -2.0f}, {0.0f, 2.0f, 2.0f}),
                   mb.material("wall", {0.3f, 0.4f, 0.7f}));
            scene.lights.push_back(light);
            scene.cameras.push_back({.name = "facing the wall",
                                     .position = {3.5f, 2.5f, 2.0f},
                                     .target = {0.3f, 0.3f, 0.0f},
                                     .yfov = 0.9f,
                                     .znear = 0.1f,
                                     .zfar = 100.0f});
            RenderOptions o{.width = 256,
                            .height = 192,
                            .shadowMapSize = 1024,
                            .frames = 1,
                            .technique = Technique::Pcf};
            o.parameters.set("pcf.size", "11");
            const RenderResult on = test::sharedRenderer().render(scene, o);
            o.parameters.set("bias.crease", "0");
            const RenderResult off = test::sharedRenderer().render(scene, o);
            size_t floor = 0, moved = 0;
            for (size_t i = 0; i < on.visibility[0].size(); ++i) {
                const glm::vec3 p(on.position[3 * i], on.position[3 * i + 1],
                                  on.position[3 * i + 2]);
                const float a = on.visibility[0][i], b = off.visibility[0][i];
                if (!std::isnan(a) && std::abs(p.y) < 1e-3f && p.x > 0.02f && p.x < 1.5f &&
                    std::abs(p.z) < 1.8f) {
                    ++floor;
                    moved += a != b;
                }
            }
            const std::string what = fmt::format("{} {} degrees", light.name, degrees);
            std::printf("%s: %zu of %zu floor pixels at the wall's foot moved by the rule\n",
                        what.c_str(), moved, floor);
            ASSERT_GT(floor, 2000u) << what;
            if (degrees > 12.0f) {
                EXPECT_EQ(moved, 0u) << what;
            } else {
                EXPECT_GT(moved, 20u) << what << ": the rule does nothing at the foot";
            }
        }
    }
}

// The crease rule is bias.mode=adaptive's alone (receiver.glsl, noAdaptiveTerms): under the fixed
// bias a wide kernel on a floor the light sees tilted reaches taps of that floor nearer the light
// than the receiver, and without the receiver plane they shadow it (the acne the plane is for,
// [Isidoro 2006]); the rule would take them as the receiver's own plane and hide it. So with the
// fixed bias and no receiver plane most of the lit floor shows acne under every light type (on
// lavapipe: spot 98%, sun 72%, bulb 51%; the rule on would leave the spot 23% and the sun 6%),
// and the receiver plane takes most of it off.
TEST_F(BiasTest, OutsideAdaptiveBiasAWideKernelFindsItsOwnTiltedFloor) {
    const std::vector<Light> lights{{.name = "spot",
                                     .type = LightType::Spot,
                                     .position = {5.0f, 4.0f, 0.5f},
                                     .direction = glm::normalize(glm::vec3(-5.0f, -4.0f, -0.5f)),
                                     .intensity = 60.0f,
                                     .outerConeAngle = 0.9f},
                                    {.name = "sun",
                                     .type = LightType::Directional,
                                     .direction = glm::normalize(glm::vec3(-1.0f, -0.8f, -0.1f))},
                                    {.name = "bulb",
                                     .type = LightType::Point,
                                     .position = {0.3f, 2.5f, 0.2f},
                                     .intensity = 8.0f}};
    for (const Light& light : lights) {
        const test::Truth t =
            test::groundTruth(boxesOnAFloor(light),
                              {.width = 240, .height = 180, .shadowMapSize = 1024, .samples = 1});
        std::vector<std::pair<std::string, std::string>> sets{{"pcf.filter", "box"},
                                                              {"pcf.size", "15"},
                                                              {"bias.mode", "fixed"},
                                                              {"bias.receiver", "off"}};
        const ErrorMetrics off = test::measure(t, Technique::Pcf, sets);
        sets.back().second = "light";
        const ErrorMetrics plane = test::measure(t, Technique::Pcf, sets);
        std::printf("%s: fixed bias, pcf box 15: acne %.3f%% without the receiver plane, %.3f%% "
                    "with it\n",
                    light.name.c_str(), 100 * off.acne, 100 * plane.acne);
        EXPECT_GT(off.acne, 0.4) << light.name;
        EXPECT_LT(plane.acne, 0.5 * off.acne) << light.name;
    }
}
