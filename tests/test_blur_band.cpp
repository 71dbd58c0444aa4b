// The blur band of acne_beyond_blur / leak_beyond_blur (src/report/blur_band.h): a technique's
// declared blur radius, in texels, as pixels on the screen, for each kind of light's view.
#include "report/blur_band.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A w x h G-buffer of the plane z = 0 seen straight down, `spacing` world units per pixel,
// centred on the origin (pixel (w/2, h/2) at (0, 0, 0)).
RenderResult planeGbuffer(uint32_t w, uint32_t h, float spacing) {
    RenderResult r;
    r.width = w;
    r.height = h;
    r.visibility.assign(1, std::vector<float>(size_t{w} * h, 1.0f));
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            r.position.push_back((float(x) - float(w / 2)) * spacing);
            r.position.push_back((float(y) - float(h / 2)) * spacing);
            r.position.push_back(0.0f);
        }
    return r;
}

ShadowViewInfo view(const char* projection, float texelWorldSize, glm::mat4 worldToShadow) {
    return {
        .projection = projection, .texelWorldSize = texelWorldSize, .worldToShadow = worldToShadow};
}

LightShadow shadowWith(const char* projection, std::vector<ShadowViewInfo> views) {
    return {
        .sceneLight = 0, .visibilityIndex = 0, .projection = projection, .views = std::move(views)};
}

float at(const std::vector<float>& band, const RenderResult& r, uint32_t x, uint32_t y) {
    return band[size_t{y} * r.width + x];
}

TEST(BlurBand, SunStraightOnIsRadiusTimesTexelOverPixel) {
    RenderResult g = planeGbuffer(9, 7, 0.02f);
    Light sun{.type = LightType::Directional, .direction = {0, 0, -1}};
    const LightShadow s = shadowWith("orthographic", {view("orthographic", 0.05f, {})});
    const std::vector<float> band = blurBandPixels(sun, s, g, 3.0);
    for (uint32_t y = 0; y < 7; ++y)
        for (uint32_t x = 0; x < 9; ++x)
            EXPECT_NEAR(at(band, g, x, y), 3.0 * 0.05 / 0.02, 1e-4) << x << "," << y;
}

TEST(BlurBand, ASlantedLightStretchesTheBlurAcrossTheFootprintsShortSide) {
    RenderResult g = planeGbuffer(9, 7, 0.02f);
    // 60 degrees from the normal, tilted in y: a pixel's y step spans cos 60 across the rays.
    const float a = glm::radians(60.0f);
    Light sun{.type = LightType::Directional, .direction = {0, std::sin(a), -std::cos(a)}};
    const LightShadow s = shadowWith("orthographic", {view("orthographic", 0.05f, {})});
    const std::vector<float> band = blurBandPixels(sun, s, g, 3.0);
    EXPECT_NEAR(at(band, g, 4, 3), 3.0 * 0.05 / (0.02 * 0.5), 1e-3);
}

TEST(BlurBand, ASpotLightsTexelGrowsWithDistance) {
    RenderResult g = planeGbuffer(9, 7, 0.02f);
    Light spot{.type = LightType::Spot, .position = {0, 0, 10}, .direction = {0, 0, -1}};
    glm::mat4 m(1.0f);
    m[2][3] = -1.0f; // w = 10 - z: the distance along the spot's axis
    m[3][3] = 10.0f;
    const LightShadow s = shadowWith("perspective", {view("perspective", 0.001f, m)});
    const std::vector<float> band = blurBandPixels(spot, s, g, 2.0);
    EXPECT_NEAR(at(band, g, 4, 3), 2.0 * 0.001 * 10.0 / 0.02, 1e-3); // straight under the light
}

TEST(BlurBand, APointLightUsesTheCubeFaceThatHoldsThePixel) {
    RenderResult g = planeGbuffer(9, 7, 0.02f);
    Light point{.type = LightType::Point, .position = {0, 0, 4}};
    glm::mat4 plusX(0.0f); // looks along +x: every point of the plane lies behind it (w < 0)
    plusX[0][3] = 1.0f;
    plusX[3][3] = -1.0f;
    glm::mat4 minusZ(0.0f); // looks along -z: u, v = 0.5 + 0.5 (x, y) / w, w = 4 - z
    minusZ[0][0] = 0.5f;
    minusZ[2][0] = -0.5f;
    minusZ[3][0] = 2.0f;
    minusZ[1][1] = 0.5f;
    minusZ[2][1] = -0.5f;
    minusZ[3][1] = 2.0f;
    minusZ[3][2] = 0.5f;
    minusZ[2][3] = -1.0f;
    minusZ[3][3] = 4.0f;
    const LightShadow s =
        shadowWith("cube", {view("perspective", 1.0f, plusX), view("perspective", 0.002f, minusZ)});
    const std::vector<float> band = blurBandPixels(point, s, g, 5.0);
    EXPECT_NEAR(at(band, g, 4, 3), 5.0 * 0.002 * 4.0 / 0.02, 1e-3);
}

TEST(BlurBand, BackgroundAndShadowlessLightsGiveNaNAndSilhouettesUseTheNearerNeighbour) {
    RenderResult g = planeGbuffer(9, 7, 0.02f);
    for (int c = 0; c < 3; ++c)
        g.position[3 * (3 * 9 + 2) + size_t(c)] = kNaN; // background at (2, 3)
    for (uint32_t y = 0; y < 7; ++y) // a far surface from column 6 on: a silhouette at 5 | 6
        g.position[3 * (size_t{y} * 9 + 6) + 2] = -50.0f;
    Light sun{.type = LightType::Directional, .direction = {0, 0, -1}};
    const LightShadow s = shadowWith("orthographic", {view("orthographic", 0.05f, {})});
    const std::vector<float> band = blurBandPixels(sun, s, g, 3.0);
    EXPECT_TRUE(std::isnan(at(band, g, 2, 3)));
    // Column 5's left neighbour is on its surface; its right one is far off and not used.
    EXPECT_NEAR(at(band, g, 5, 3), 3.0 * 0.05 / 0.02, 1e-4);
    // Column 1 has only its left neighbour along x at row 3: still the plane's own spacing.
    EXPECT_NEAR(at(band, g, 1, 3), 3.0 * 0.05 / 0.02, 1e-4);
    LightShadow none = s;
    none.visibilityIndex = -1;
    for (float v : blurBandPixels(sun, none, g, 3.0))
        EXPECT_TRUE(std::isnan(v));
}

TEST(BlurBand, MetricsAgainstTruthLeaveTheBlurOut) {
    // 40 x 3 pixels of the plane, truth lit from column 20; the technique blurs the edge over
    // 6 pixels each side (3 texels of 0.04 at 0.02 per pixel), which beyond-blur must not count.
    RenderResult g = planeGbuffer(40, 3, 0.02f);
    std::vector<float> truth(40 * 3);
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 0; x < 40; ++x) {
            truth[y * 40 + x] = x >= 20 ? 1.0f : 0.0f;
            g.visibility[0][y * 40 + x] = std::clamp((float(x) - 13.5f) / 13.0f, 0.0f, 1.0f);
        }
    g.lights = {shadowWith("orthographic", {view("orthographic", 0.04f, {})})};
    Scene lit;
    lit.lights = {Light{.type = LightType::Directional, .direction = {0, 0, -1}}};
    const std::vector<std::vector<float>> truths{truth};
    const std::vector<std::vector<uint8_t>> masks{std::vector<uint8_t>(40 * 3, 1)};
    const ErrorMetrics m = metricsAgainstTruth(lit, g, truths, masks, 3.0);
    EXPECT_GT(m.acne, 0.0); // the fixed 2-pixel band sees the blur as acne and leak
    EXPECT_GT(m.leak, 0.0);
    EXPECT_EQ(m.acneBeyondBlur, 0.0);
    EXPECT_EQ(m.leakBeyondBlur, 0.0);
    // A blur twice as wide as declared is counted.
    const ErrorMetrics narrow = metricsAgainstTruth(lit, g, truths, masks, 1.0);
    EXPECT_GT(narrow.acneBeyondBlur, 0.0);
    // A cube face's own radius (the soft members' cubeRadius) counts under a point light only.
    EXPECT_EQ(metricsAgainstTruth(lit, g, truths, masks, BlurReach(1.0, 3.0)).acneBeyondBlur,
              narrow.acneBeyondBlur);
    lit.lights = {Light{.type = LightType::Point, .position = {0.4f, 0.03f, 10.0f}}};
    EXPECT_EQ(metricsAgainstTruth(lit, g, truths, masks, BlurReach(1.0, 3.0)).acneBeyondBlur, 0.0);
    EXPECT_GT(metricsAgainstTruth(lit, g, truths, masks, BlurReach(1.0)).acneBeyondBlur, 0.0);
}

} // namespace
} // namespace penumbra
