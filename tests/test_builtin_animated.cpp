// The animated built-ins besides the pendulum (test_gltf_posed.cpp): builtin:town's sun crossing
// the sky and builtin:fan's turning blades, posed from their kTown* and kFan* constants and
// checked against closed forms and rays cast against the posed geometry.
#include "penumbra/scene.h"
#include "scene/builtin_scenes.h"
#include "scene/ray_cast.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace penumbra;
using namespace penumbra::builtin;

namespace {

bool near(glm::vec3 got, glm::vec3 want, float tolerance = 1e-5f) {
    return glm::length(got - want) < tolerance;
}

// Whether the ground point `p` sees the sun of `s` (its first light) without a hit.
bool sunlit(const Scene& s, glm::vec3 p) {
    return !firstHit(s, p + glm::vec3(0, 1e-3f, 0), -s.lights[0].direction);
}

} // namespace

TEST(GltfPosed, TheBuiltinTownsSunCrossesTheSkyFromEastToWest) {
    const float c55 = std::cos(0.9599f), s55 = std::sin(0.9599f);
    const float c15 = std::cos(0.2618f), s15 = std::sin(0.2618f);
    const struct {
        double time;
        glm::vec3 towardsSun;
    } poses[] = {
        {0.0, {c15, s15 * s55, -s15 * c55}},   // sunrise, low in the east
        {6.0, {0.0f, s55, -c55}},              // noon, 55 degrees up in the south
        {12.0, {-c15, s15 * s55, -s15 * c55}}, // sunset, low in the west
        {20.0, {-c15, s15 * s55, -s15 * c55}}, // after the day: held
    };
    for (const auto& [time, towardsSun] : poses) {
        const Scene s = loadScene("builtin:town", {.time = time, .animation = "day"});
        EXPECT_EQ(s.animation, "day");
        EXPECT_EQ(s.animationDuration, float(kTownDaySeconds));
        ASSERT_EQ(s.lights.size(), 1u);
        EXPECT_TRUE(near(s.lights[0].direction, -towardsSun, 2e-4f)) << time;
        EXPECT_NEAR(glm::length(s.lights[0].direction), 1.0f, 1e-6f);
    }
    // At 3 s a quarter of the way: the arc's angle is 15 + 150 / 4 degrees.
    const double arc = 0.2618 + (std::numbers::pi - 2 * 0.2618) / 4;
    EXPECT_TRUE(near(townSunDirection(3.0),
                     -glm::vec3(std::cos(arc), std::sin(arc) * s55, -std::sin(arc) * c55), 1e-5f));
    // The tower's shadow sweeps: west of it in the morning, north of it at noon, east at dusk.
    const glm::vec3 west(-4.0f, 0.0f, 0.6f), north(0.0f, 0.0f, 3.0f), east(4.0f, 0.0f, 0.6f);
    const Scene morning = loadScene("builtin:town", {.time = 0.0});
    const Scene noon = loadScene("builtin:town", {.time = 6.0});
    const Scene evening = loadScene("builtin:town", {.time = 12.0});
    EXPECT_FALSE(sunlit(morning, west));
    EXPECT_TRUE(sunlit(morning, east));
    EXPECT_TRUE(sunlit(noon, west));
    EXPECT_FALSE(sunlit(noon, north));
    EXPECT_TRUE(sunlit(noon, east));
    EXPECT_FALSE(sunlit(evening, east));
    EXPECT_TRUE(sunlit(evening, west));
}

TEST(GltfPosed, TheBuiltinFansThinBladesTurnOnceInTheirTurnTime) {
    const float tip = kFanBladeLength;
    for (const double time : {0.0, 0.03, 0.125, 0.2, 0.25, 1.07}) {
        const Scene s = loadScene("builtin:fan", {.time = time, .animation = "spin"});
        EXPECT_EQ(s.animation, "spin");
        EXPECT_EQ(s.animationDuration, float(kFanTurnSeconds));
        const double turns = time / kFanTurnSeconds;
        const float angle = float(2 * std::numbers::pi * (turns - std::floor(turns)));
        EXPECT_NEAR(fanAngle(time), angle, 1e-5f) << time;
        // Each blade's outer end: its corners at the tip's radius, turned by the blade's angle
        // (right-hand rule about +y: x towards -z), half the width to either side.
        for (int b = 0; b < 3; ++b) {
            const float a = angle + float(b) * 2.0f * std::numbers::pi_v<float> / 3.0f;
            const glm::vec3 along(std::cos(a), 0.0f, -std::sin(a)),
                across(std::sin(a), 0, std::cos(a));
            const glm::vec3 corner = glm::vec3(0, kFanHeight + kFanBladeThickness / 2, 0) +
                                     tip * along + (kFanBladeWidth / 2) * across;
            size_t found = 0;
            for (const Vertex& v : s.vertices)
                found += near(v.position, corner, 1e-4f);
            EXPECT_GT(found, 0u) << "blade " << b << " at " << time << " s";
        }
        ASSERT_EQ(s.lights.size(), 1u);
        EXPECT_EQ(s.lights[0].type, LightType::Spot);
        EXPECT_EQ(s.lights[0].position, kFanSpotPosition);
    }
    // A blade is thin: its shadow holds a point under it, and a quarter of a turn later (a
    // third of the way to the next blade) the point is lit.
    // The ray from here to the spot crosses the blades' height at (1, 2.5, 0): blade 0 at angle 0.
    const glm::vec3 under(1.36f, 0.0f, -0.18f);
    const auto lit = [&](double time) {
        const Scene s = loadScene("builtin:fan", {.time = time});
        const glm::vec3 towardsLight = glm::normalize(kFanSpotPosition - under);
        return !firstHit(s, under + glm::vec3(0, 1e-3f, 0), towardsLight);
    };
    EXPECT_FALSE(lit(0.0));
    EXPECT_TRUE(lit(kFanTurnSeconds / 6.0));
}
