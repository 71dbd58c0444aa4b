// The edge-aware visibility filter's CPU mirror (src/shadows/visibility_filter.cpp, its weights
// shared with the shader in shaders/include/visibility_filter_weights.h) on images made in code:
// what it must keep (hard steps, depth steps, creases, linear ramps, the background) and what it
// must remove (noise, along both axes). The GPU against this mirror: FilterTest in
// tests/test_smrt_screen_passes.cpp.
#include "light_geometry.h"
#include "shadows/visibility_filter.h"
#include "surface_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

using namespace penumbra;
using test::onPlane;
using test::up;

namespace {

constexpr uint32_t kSize = 16;
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

using Surface = test::SurfaceImage;

// A kSize x kSize image of a surface: position(x, y), normal(x, y) and visibility(x, y).
Surface surface(const std::function<glm::vec3(int, int)>& position,
                const std::function<glm::vec3(int, int)>& normal,
                const std::function<float(int, int)>& visibility) {
    return test::surfaceImage(kSize, kSize, position, normal, visibility);
}

std::vector<float> filtered(const Surface& s, uint32_t radius, float tolerance) {
    return shadows::filterVisibility(kSize, kSize, s.position, s.normal, s.visibility,
                                     {.radius = radius, .tolerance = tolerance});
}

double variance(const std::vector<float>& v) {
    double mean = 0.0, square = 0.0;
    for (float x : v)
        mean += x;
    mean /= double(v.size());
    for (float x : v)
        square += (x - mean) * (x - mean);
    return square / double(v.size());
}

// Equal to rounding: a weighted mean of equal values may differ from them in the last bit.
void expectNear(const std::vector<float>& out, const std::vector<float>& expected) {
    ASSERT_EQ(out.size(), expected.size());
    for (size_t i = 0; i < out.size(); ++i)
        EXPECT_NEAR(out[i], expected[i], 1e-6f) << i;
}

} // namespace

// Noise on one plane (a checkerboard of 0.4 and 0.6, what a few rays turned per pixel give)
// averages out along rows and columns alike; the mean stays.
TEST(VisibilityFilter, AveragesNoiseOnASurfaceAlongBothAxes) {
    for (const bool alongColumns : {false, true}) {
        const Surface s = surface(
            onPlane, up, [&](int x, int y) { return ((alongColumns ? y : x) % 2) ? 0.6f : 0.4f; });
        const std::vector<float> out = filtered(s, 2, 0.7f);
        EXPECT_LT(variance(out), 0.1 * variance(s.visibility)) << alongColumns;
        double mean = 0.0;
        for (float v : out)
            mean += v;
        EXPECT_NEAR(mean / double(out.size()), 0.5, 0.01) << alongColumns;
    }
}

// A linear ramp is its own average under a symmetric kernel: interior pixels keep their value
// (an off-centre tent or a one-sided window would move them).
TEST(VisibilityFilter, KeepsALinearRamp) {
    const Surface s = surface(
        onPlane, up, [](int x, int y) { return 0.2f + 0.02f * float(x) + 0.01f * float(y); });
    const std::vector<float> out = filtered(s, 2, 1.0f);
    for (int y = 2; y < int(kSize) - 2; ++y)
        for (int x = 2; x < int(kSize) - 2; ++x)
            EXPECT_NEAR(out[y * kSize + x], s.visibility[y * kSize + x], 2e-3f) << x << "," << y;
}

// What must stay sharp: a visibility step beyond the tolerance, a depth step, a crease.
TEST(VisibilityFilter, KeepsHardEdgesDepthStepsAndCreases) {
    auto half = [](int x, float left, float right) { return x < 8 ? left : right; };
    // A hard shadow edge on one plane: 0 | 1 stays 0 | 1 exactly.
    const Surface hard = surface(onPlane, up, [&](int x, int) { return half(x, 0.0f, 1.0f); });
    EXPECT_EQ(filtered(hard, 3, 0.7f), hard.visibility);
    // Two planes a unit apart in depth, 0.3 and 0.5 (within the tolerance): no mixing.
    const Surface step = surface(
        [&](int x, int y) { return onPlane(x, y) + glm::vec3(0.0f, 0.0f, half(x, 0.0f, 1.0f)); },
        up, [&](int x, int) { return half(x, 0.3f, 0.5f); });
    expectNear(filtered(step, 3, 0.7f), step.visibility);
    // One plane whose normal turns by 60 degrees at x = 8 (a crease seen flat): no mixing.
    const Surface crease = surface(
        onPlane,
        [&](int x, int) {
            return x < 8 ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.866025f, 0.0f, 0.5f);
        },
        [&](int x, int) { return half(x, 0.3f, 0.5f); });
    expectNear(filtered(crease, 3, 0.7f), crease.visibility);
    // ... while the same 0.3 | 0.5 on one flat plane does mix (the three above are not vacuous).
    const Surface flat = surface(onPlane, up, [&](int x, int) { return half(x, 0.3f, 0.5f); });
    const std::vector<float> mixed = filtered(flat, 3, 0.7f);
    EXPECT_GT(mixed[5 * kSize + 7], 0.32f);
    EXPECT_LT(mixed[5 * kSize + 8], 0.48f);
}

// Background pixels (NaN) pass through and never enter a neighbour's average; radius 0 is the
// identity.
TEST(VisibilityFilter, LeavesTheBackgroundOutAndRadiusZeroAlone) {
    Surface s = surface(onPlane, up, [](int x, int y) { return (x + y) % 2 ? 0.6f : 0.4f; });
    for (int y = 0; y < int(kSize); ++y)
        for (int x = 10; x < int(kSize); ++x) {
            const size_t i = size_t(y) * kSize + size_t(x);
            s.position[3 * i] = s.normal[3 * i] = s.visibility[i] = kNan;
        }
    const std::vector<float> out = filtered(s, 2, 0.7f);
    for (size_t i = 0; i < out.size(); ++i) {
        EXPECT_EQ(std::isnan(out[i]), std::isnan(s.visibility[i])) << i;
        if (!std::isnan(out[i])) {
            EXPECT_GE(out[i], 0.4f);
            EXPECT_LE(out[i], 0.6f);
        }
    }
    const std::vector<float> same = filtered(s, 0, 0.7f);
    for (size_t i = 0; i < same.size(); ++i) {
        if (!std::isnan(s.visibility[i])) {
            EXPECT_EQ(same[i], s.visibility[i]);
        }
    }
}

// Where the range and geometry factors are all near one (a small bump on a flat plane, a
// tolerance of 1), the filter is the separable tent: a bump of e at one pixel keeps
// (R + 1)^2 / (R + 1)^4 of it there and gives its row neighbour R (R + 1) / (R + 1)^4 and its
// diagonal neighbour R^2 / (R + 1)^4 (for R = 1: 1/4, 1/8, 1/16). A box, a wider or narrower
// window, or one axis alone each give other fractions.
TEST(VisibilityFilter, SpreadsABumpAsTheSeparableTent) {
    constexpr float e = 1e-3f;
    const Surface s =
        surface(onPlane, up, [&](int x, int y) { return x == 8 && y == 8 ? 0.5f + e : 0.5f; });
    const std::vector<float> out = filtered(s, 1, 1.0f);
    auto excess = [&](int x, int y) { return (out[size_t(y) * kSize + size_t(x)] - 0.5f) / e; };
    EXPECT_NEAR(excess(8, 8), 0.25f, 0.005f);
    EXPECT_NEAR(excess(9, 8), 0.125f, 0.005f);
    EXPECT_NEAR(excess(8, 7), 0.125f, 0.005f);
    EXPECT_NEAR(excess(7, 9), 0.0625f, 0.005f);
    EXPECT_NEAR(excess(10, 8), 0.0f, 0.005f);
}

// Point lights take the cube radius, spots and suns the other; a filter runs if either is set.
TEST(VisibilityFilter, PointLightsTakeTheCubeRadius) {
    const shadows::VisibilityFilter filter{.radius = 1, .cubeRadius = 3};
    EXPECT_EQ(filter.radiusFor(LIGHT_POINT), 3u);
    EXPECT_EQ(filter.radiusFor(LIGHT_SPOT), 1u);
    EXPECT_EQ(filter.radiusFor(LIGHT_DIRECTIONAL), 1u);
    EXPECT_TRUE((shadows::VisibilityFilter{.cubeRadius = 2}.runs()));
    EXPECT_TRUE((shadows::VisibilityFilter{.radius = 2}.runs()));
    EXPECT_FALSE(shadows::VisibilityFilter{}.runs());
}

// smrt.filterWide: inside a wide penumbra (every neighbour out to the wide radius, on the image
// and on the surface, neither 0 nor 1) a pixel reaches that far, and the result is the wider
// filter's; nearer the image's border it reaches only as far as the image goes.
TEST(VisibilityFilter, WidensInsideAWidePenumbra) {
    // Noise that a radius of 1 leaves much of (a checkerboard it would take out whole).
    const Surface s = surface(
        onPlane, up, [](int x, int y) { return 0.5f + 0.05f * float((x * 7 + y * 13) % 5 - 2); });
    const std::vector<float> wide =
        shadows::filterVisibility(kSize, kSize, s.position, s.normal, s.visibility,
                                  {.radius = 1, .tolerance = 1.0f, .wide = 3});
    const std::vector<float> three = filtered(s, 3, 1.0f), one = filtered(s, 1, 1.0f);
    for (int y = 3; y < int(kSize) - 3; ++y)
        for (int x = 3; x < int(kSize) - 3; ++x)
            EXPECT_NEAR(wide[y * kSize + x], three[y * kSize + x], 1e-6f) << x << "," << y;
    EXPECT_LT(variance(wide), 0.5 * variance(one));
    // At the border's first pixel the run is 0: the rows reach 1, not 3.
    const std::vector<float> rowsOne = shadows::filterVisibility(
        kSize, 1, std::span(s.position).first(3 * kSize), std::span(s.normal).first(3 * kSize),
        std::span(s.visibility).first(kSize), {.radius = 1, .tolerance = 1.0f, .wide = 3});
    const std::vector<float> rowsRadiusOne = shadows::filterVisibility(
        kSize, 1, std::span(s.position).first(3 * kSize), std::span(s.normal).first(3 * kSize),
        std::span(s.visibility).first(kSize), {.radius = 1, .tolerance = 1.0f});
    EXPECT_NEAR(rowsOne[0], rowsRadiusOne[0], 1e-6f);
    EXPECT_GT(std::abs(rowsOne[3] - rowsRadiusOne[3]), 1e-3f);
}

// A narrow penumbra (four pixels between a 0 and a 1) stays within the radius: its runs end at
// the settled pixels beside it, so the wide radius changes nothing there, nor on either side.
TEST(VisibilityFilter, KeepsNarrowPenumbraeToTheRadius) {
    const Surface s = surface(onPlane, up, [](int x, int) {
        return x <= 5 ? 0.0f : x >= 10 ? 1.0f : 0.2f * float(x - 5);
    });
    const std::vector<float> wide =
        shadows::filterVisibility(kSize, kSize, s.position, s.normal, s.visibility,
                                  {.radius = 1, .tolerance = 1.0f, .wide = 3});
    expectNear(wide, filtered(s, 1, 1.0f));
}

// The wide radius under each light: point lights the cube's; never below the radius; none where
// the radius is 0 (no filter).
TEST(VisibilityFilter, WideRadiusFollowsTheLightsRadius) {
    const shadows::VisibilityFilter filter{.radius = 1, .cubeRadius = 2, .wide = 4, .cubeWide = 0};
    EXPECT_EQ(filter.wideFor(LIGHT_SPOT), 4u);
    EXPECT_EQ(filter.wideFor(LIGHT_DIRECTIONAL), 4u);
    EXPECT_EQ(filter.wideFor(LIGHT_POINT), 2u);
    EXPECT_EQ((shadows::VisibilityFilter{.radius = 3, .wide = 2}.wideFor(LIGHT_SPOT)), 3u);
    EXPECT_EQ((shadows::VisibilityFilter{.wide = 4}.wideFor(LIGHT_SPOT)), 0u);
    EXPECT_EQ((shadows::VisibilityFilter{.cubeRadius = 1, .cubeWide = 5}.wideFor(LIGHT_POINT)), 5u);
}
