#include "report/light_mask.h"
#include "report/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

namespace penumbra {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// One light's synthetic images; every pixel counted unless a test clears its mask.
struct Images {
    uint32_t width, height;
    std::vector<float> visibility, truth;
    std::vector<uint8_t> mask;

    Images(uint32_t w, uint32_t h, float v = 0, float t = 0)
        : width(w), height(h), visibility(size_t{w} * h, v), truth(size_t{w} * h, t),
          mask(size_t{w} * h, 1) {}
    size_t at(uint32_t x, uint32_t y) const { return size_t{y} * width + x; }
    MetricLayer layer() const { return {visibility, truth, mask}; }
    ErrorMetrics metrics(int edgeBand = 2) const {
        MetricLayer l = layer();
        return computeMetrics(width, height, std::span(&l, 1), edgeBand);
    }
};

// 8x8, truth 0 in columns 0-3 and 1 in columns 4-7, visibility equal to truth.
Images halfAndHalf() {
    Images im(8, 8);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 4; x < 8; ++x)
            im.truth[im.at(x, y)] = im.visibility[im.at(x, y)] = 1;
    return im;
}

TEST(Metrics, ExactMatchIsAllZero) {
    ErrorMetrics m = halfAndHalf().metrics();
    EXPECT_EQ(m.rmse, 0);
    EXPECT_EQ(m.mae, 0);
    EXPECT_EQ(m.max, 0);
    EXPECT_EQ(m.misclassified, 0);
    EXPECT_EQ(m.misclassifiedOutsideEdges, 0);
    EXPECT_EQ(m.acne, 0);
    EXPECT_EQ(m.leak, 0);
    EXPECT_EQ(m.pixels, 64u);
    // Boundary columns 3 and 4, band 1..6: only columns 0 and 7 lie outside, and only there
    // are pixels judged for acne (column 7, lit) and leak (column 0, shadowed).
    EXPECT_EQ(m.truthLit, 8u);
    EXPECT_EQ(m.truthShadowed, 8u);
    EXPECT_EQ(m.pixelsOutsideEdges, 16u);
}

// Per channel against a coloured truth: a row's own channels, or its grey value in each; only the
// pixels the mask counts with every value finite.
TEST(Metrics, RmsePerChannelCountsWhatTheMetricsCount) {
    const std::vector<float> truth{0.5f, 1.0f, 0.0f, 1.0f, 1.0f, 1.0f, 0.2f, 0.2f, 0.2f};
    const std::vector<float> rgb{0.5f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, NAN, 0.2f, 0.2f};
    const std::vector<uint8_t> mask{1, 1, 1};
    const std::array<double, 3> own = rmsePerChannel(rgb, {}, truth, mask);
    EXPECT_DOUBLE_EQ(own[0], 0.0);                  // pixel 2 has a NaN: left out whole
    EXPECT_DOUBLE_EQ(own[1], std::sqrt(1.0 / 2.0)); // 1 off in one of the two counted
    EXPECT_DOUBLE_EQ(own[2], 0.0);
    // A row with both (the translucent layer's) is measured by its colour.
    EXPECT_EQ(rmsePerChannel(rgb, std::vector<float>{0.0f, 0.0f, 0.0f}, truth, mask), own);
    const std::vector<float> grey{0.5f, 1.0f, 0.2f};
    const std::vector<uint8_t> firstTwo{1, 1, 0};
    const std::array<double, 3> g = rmsePerChannel({}, grey, truth, firstTwo);
    EXPECT_DOUBLE_EQ(g[0], 0.0);
    EXPECT_DOUBLE_EQ(g[1], std::sqrt(0.25 / 2.0));
    EXPECT_DOUBLE_EQ(g[2], std::sqrt(0.25 / 2.0));
    EXPECT_EQ(rmsePerChannel({}, grey, truth, std::vector<uint8_t>{0, 0, 0}),
              (std::array<double, 3>{0.0, 0.0, 0.0}));
}

TEST(Metrics, FlippedPixelsGiveExactFractions) {
    Images im = halfAndHalf();
    im.visibility[im.at(0, 0)] = 1; // shadowed -> lit, outside the band: leak
    im.visibility[im.at(7, 7)] = 0; // lit -> shadowed, outside the band: acne
    im.visibility[im.at(4, 2)] = 0; // lit -> shadowed, inside the band: an edge error, not acne
    ErrorMetrics m = im.metrics();
    EXPECT_DOUBLE_EQ(m.misclassified, 3.0 / 64);
    EXPECT_DOUBLE_EQ(m.misclassifiedOutsideEdges, 2.0 / 16);
    EXPECT_DOUBLE_EQ(m.acne, 1.0 / 8);
    EXPECT_DOUBLE_EQ(m.leak, 1.0 / 8);
    EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(3.0 / 64));
    EXPECT_DOUBLE_EQ(m.mae, 3.0 / 64);
    EXPECT_DOUBLE_EQ(m.max, 1.0);
}

TEST(Metrics, ConstantOffset) {
    Images im(8, 8, 0.5f, 0.25f);
    ErrorMetrics m = im.metrics();
    EXPECT_DOUBLE_EQ(m.rmse, 0.25);
    EXPECT_DOUBLE_EQ(m.mae, 0.25);
    EXPECT_DOUBLE_EQ(m.max, 0.25);
    EXPECT_EQ(m.misclassified, 0);
    // Truth is neither fully lit nor fully shadowed: empty denominators give 0.
    EXPECT_EQ(m.truthLit, 0u);
    EXPECT_EQ(m.truthShadowed, 0u);
    EXPECT_EQ(m.acne, 0);
    EXPECT_EQ(m.leak, 0);
    // No boundary at all: every pixel lies outside the edge band.
    EXPECT_EQ(m.pixelsOutsideEdges, 64u);
}

TEST(Metrics, NegativeOffsetUsesAbsoluteMax) {
    Images im(4, 4, 0.25f, 0.5f);
    ErrorMetrics m = im.metrics();
    EXPECT_DOUBLE_EQ(m.max, 0.25);
    EXPECT_DOUBLE_EQ(m.mae, 0.25);
}

TEST(Metrics, AcneAndLeakThresholds) {
    // Uniform truth, so no edge band: every pixel is judged. Lit truth (one just below 1
    // within the tolerance) counts acne below 0.9; shadowed truth counts leak above 0.1.
    Images lit(5, 1);
    const float litT[5] = {1, 1, 1, 1, 1 - 1e-7f};
    const float litV[5] = {0.89f, 0.9f, 0.95f, 1.0f, 0.5f}; // acne: 0.89 and 0.5
    Images shadow(5, 1);
    const float shadowV[5] = {0.1f, 0.11f, 0.0f, 0.05f, 0.6f}; // leak: 0.11 and 0.6
    for (uint32_t x = 0; x < 5; ++x) {
        lit.truth[x] = litT[x], lit.visibility[x] = litV[x];
        shadow.truth[x] = x == 4 ? 1e-7f : 0.0f, shadow.visibility[x] = shadowV[x];
    }
    const ErrorMetrics a = lit.metrics(), l = shadow.metrics();
    EXPECT_EQ(a.truthLit, 5u);
    EXPECT_DOUBLE_EQ(a.acne, 2.0 / 5);
    EXPECT_EQ(l.truthShadowed, 5u);
    EXPECT_DOUBLE_EQ(l.leak, 2.0 / 5);
    // In-between truth is neither, whatever its visibility.
    Images mid(4, 1, 0.0f, 0.6f);
    const ErrorMetrics m = mid.metrics();
    EXPECT_EQ(m.truthLit + m.truthShadowed, 0u);
    EXPECT_EQ(m.acne + m.leak, 0.0);
}

TEST(Metrics, EdgeBandAroundVerticalBoundary) {
    // 16x5, truth boundary between columns 6 and 7.
    Images im(16, 5);
    for (uint32_t y = 0; y < 5; ++y)
        for (uint32_t x = 7; x < 16; ++x)
            im.truth[im.at(x, y)] = im.visibility[im.at(x, y)] = 1;
    EXPECT_EQ(im.metrics(2).pixelsOutsideEdges, 10u * 5); // band: columns 4..9
    EXPECT_EQ(im.metrics(1).pixelsOutsideEdges, 12u * 5); // band: columns 5..8
    EXPECT_EQ(im.metrics(0).pixelsOutsideEdges, 14u * 5); // band: columns 6 and 7
    EXPECT_EQ(im.metrics(20).pixelsOutsideEdges, 0u);
}

TEST(Metrics, NaNNeighboursMakeNoBoundary) {
    Images im(9, 4);
    for (uint32_t y = 0; y < 4; ++y)
        im.truth[im.at(4, y)] = kNaN; // background column between two shadowed regions
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 5; x < 9; ++x)
            im.truth[im.at(x, y)] = 1; // lit, but only ever next to NaN
    ErrorMetrics m = im.metrics();
    EXPECT_EQ(m.pixels, 32u);
    EXPECT_EQ(m.pixelsOutsideEdges, 32u);
}

// Brute-force Chebyshev band (radius band(x, y) around each pixel), to check the O(pixels)
// version on random images.
template <class Band>
uint64_t bruteForceOutsideBand(const Images& im, Band bandAt) {
    auto cls = [&](int64_t x, int64_t y) { return im.truth[im.at(uint32_t(x), uint32_t(y))]; };
    auto boundary = [&](int64_t x, int64_t y) {
        const float t = cls(x, y);
        if (!std::isfinite(t))
            return false;
        const int64_t d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        for (const auto& o : d) {
            int64_t nx = x + o[0], ny = y + o[1];
            if (nx < 0 || ny < 0 || nx >= im.width || ny >= im.height)
                continue;
            const float n = cls(nx, ny);
            if (std::isfinite(n) && (n >= 0.5f) != (t >= 0.5f))
                return true;
        }
        return false;
    };
    uint64_t outside = 0;
    for (int64_t y = 0; y < im.height; ++y)
        for (int64_t x = 0; x < im.width; ++x) {
            const size_t i = im.at(uint32_t(x), uint32_t(y));
            if (!std::isfinite(im.truth[i]) || !std::isfinite(im.visibility[i]) || !im.mask[i])
                continue;
            bool inBand = false;
            const int64_t band = bandAt(x, y);
            for (int64_t dy = -band; dy <= band && !inBand; ++dy)
                for (int64_t dx = -band; dx <= band && !inBand; ++dx) {
                    int64_t nx = x + dx, ny = y + dy;
                    inBand =
                        nx >= 0 && ny >= 0 && nx < im.width && ny < im.height && boundary(nx, ny);
                }
            outside += !inBand;
        }
    return outside;
}

uint64_t bruteForceOutside(const Images& im, int band) {
    return bruteForceOutsideBand(im, [&](int64_t, int64_t) { return band; });
}

TEST(Metrics, EdgeBandMatchesBruteForce) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0, 1);
    for (int trial = 0; trial < 6; ++trial) {
        Images im(23 + uint32_t(trial), 17);
        for (size_t i = 0; i < im.truth.size(); ++i) {
            const float r = uniform(rng);
            // Sparse boundaries, so the band is neither empty nor everything.
            im.truth[i] = r < 0.03f ? 1.0f : r < 0.05f ? kNaN : 0.0f;
            im.mask[i] = uniform(rng) < 0.9f;
        }
        for (int band : {0, 1, 2, 3})
            EXPECT_EQ(im.metrics(band).pixelsOutsideEdges, bruteForceOutside(im, band))
                << "trial " << trial << " band " << band;
    }
}

// 24x3, truth shadowed in columns 0-11 and lit in 12-23; the visibility is wrong (0.5) on every
// pixel, so acne and leak count exactly the pixels each band leaves.
Images wrongEverywhere() {
    Images im(24, 3, 0.5f, 0.0f);
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 12; x < 24; ++x)
            im.truth[im.at(x, y)] = 1;
    return im;
}

ErrorMetrics withBlurBand(const Images& im, const std::vector<float>& band) {
    MetricLayer l = im.layer();
    l.blurBand = band;
    return computeMetrics(im.width, im.height, std::span(&l, 1));
}

TEST(MetricsBeyondBlur, ExcludesThePixelsWithinEachPixelsOwnRadius) {
    Images im = wrongEverywhere();
    // Boundary columns 11 and 12. Radius 5: lit pixels judged from column 18 (distance 6 from
    // column 12), shadowed ones up to column 5.
    ErrorMetrics m = withBlurBand(im, std::vector<float>(im.truth.size(), 5.0f));
    EXPECT_EQ(m.truthLitBeyondBlur, 6u * 3);
    EXPECT_EQ(m.truthShadowedBeyondBlur, 6u * 3);
    EXPECT_EQ(m.pixelsBeyondBlur, 12u * 3);
    // Fractions of the pixels acne and leak judge (9 columns each side of the fixed band 2).
    EXPECT_EQ(m.acneBeyondBlurPixels, 6u * 3);
    EXPECT_EQ(m.leakBeyondBlurPixels, 6u * 3);
    EXPECT_DOUBLE_EQ(m.acneBeyondBlur, 6.0 / 9.0);
    EXPECT_DOUBLE_EQ(m.leakBeyondBlur, 6.0 / 9.0);
    EXPECT_EQ(m.acnePixels, 9u * 3);
    EXPECT_DOUBLE_EQ(m.acne, 1.0);
    // The fixed band (2) is unchanged by it.
    EXPECT_EQ(m.truthLit, 9u * 3);
    // Only the pixel's own radius matters: a wide radius on the lit side alone.
    std::vector<float> band(im.truth.size(), 2.0f);
    for (uint32_t y = 0; y < 3; ++y)
        for (uint32_t x = 12; x < 24; ++x)
            band[im.at(x, y)] = 7.5f; // whole pixels: 7
    m = withBlurBand(im, band);
    EXPECT_EQ(m.truthLitBeyondBlur, 4u * 3);      // columns 20..23
    EXPECT_EQ(m.truthShadowedBeyondBlur, 9u * 3); // columns 0..8
}

TEST(MetricsBeyondBlur, RadiusIsClampedToTwoAndEightPixels) {
    Images im(40, 2, 1.0f, 0.0f);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 20; x < 40; ++x)
            im.truth[im.at(x, y)] = 1; // boundary columns 19 and 20; visibility 1 everywhere
    const auto shadowedBeyond = [&](float r) {
        return withBlurBand(im, std::vector<float>(im.truth.size(), r)).truthShadowedBeyondBlur;
    };
    EXPECT_EQ(shadowedBeyond(100.0f), 11u * 2); // 8: columns 0..10
    EXPECT_EQ(shadowedBeyond(INFINITY), 11u * 2);
    EXPECT_EQ(shadowedBeyond(8.0f), 11u * 2);
    EXPECT_EQ(shadowedBeyond(7.0f), 12u * 2);
    EXPECT_EQ(shadowedBeyond(0.0f), 17u * 2); // 2: columns 0..16
    EXPECT_EQ(shadowedBeyond(kNaN), 17u * 2);
    EXPECT_EQ(shadowedBeyond(3.0f), 16u * 2);
    // Every shadowed pixel leaks (visibility 1): the fraction is over the pixels leak judges
    // (columns 0..16), of which those beyond the band (0..13) leak beyond blur.
    const ErrorMetrics five = withBlurBand(im, std::vector<float>(im.truth.size(), 5.0f));
    EXPECT_EQ(five.leakPixels, 17u * 2);
    EXPECT_EQ(five.leakBeyondBlurPixels, 14u * 2);
    EXPECT_DOUBLE_EQ(five.leakBeyondBlur, 14.0 / 17.0);
    // No band given: beyond blur is outside the 2-pixel edge band.
    const ErrorMetrics plain = im.metrics();
    EXPECT_EQ(plain.truthShadowedBeyondBlur, plain.truthShadowed);
    EXPECT_EQ(plain.leakBeyondBlur, plain.leak);
}

TEST(MetricsBeyondBlur, NeverExceedsThePlainFigures) {
    // A blur band narrower than the edge band (3) used to judge pixels the plain figures skip.
    Images im = wrongEverywhere();
    MetricLayer l = im.layer();
    const std::vector<float> band(im.truth.size(), 2.0f);
    l.blurBand = band;
    const ErrorMetrics m = computeMetrics(im.width, im.height, std::span(&l, 1), 3);
    EXPECT_EQ(m.truthLit, 8u * 3);
    EXPECT_EQ(m.acneBeyondBlurPixels, m.acnePixels);
    EXPECT_EQ(m.leakBeyondBlurPixels, m.leakPixels);
    EXPECT_LE(m.acneBeyondBlur, m.acne);
    EXPECT_LE(m.leakBeyondBlur, m.leak);
    EXPECT_EQ(m.pixelsBeyondBlur, 16u * 3);
}

TEST(MetricsBeyondBlur, VariableBandMatchesBruteForce) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uniform(0, 1);
    for (int trial = 0; trial < 6; ++trial) {
        Images im(37 + uint32_t(trial), 29);
        std::vector<float> band(im.truth.size());
        for (size_t i = 0; i < im.truth.size(); ++i) {
            const float r = uniform(rng);
            im.truth[i] = r < 0.01f ? 1.0f : r < 0.015f ? kNaN : 0.0f;
            im.mask[i] = uniform(rng) < 0.9f;
            band[i] = 12.0f * uniform(rng) - 1.0f;
        }
        const auto radius = [&](int64_t x, int64_t y) {
            return int64_t(
                std::floor(std::clamp(band[im.at(uint32_t(x), uint32_t(y))], 2.0f, 8.0f)));
        };
        EXPECT_EQ(withBlurBand(im, band).pixelsBeyondBlur, bruteForceOutsideBand(im, radius))
            << "trial " << trial;
    }
}

TEST(Metrics, MaskedAndNonFinitePixelsAreSkipped) {
    Images im(4, 4, 0.0f, 0.0f);
    im.mask[0] = 0, im.visibility[0] = 1;                      // masked out
    im.visibility[1] = kNaN;                                   // no technique value
    im.truth[2] = kNaN, im.visibility[2] = 1;                  // background
    im.visibility[3] = std::numeric_limits<float>::infinity(); // broken value
    ErrorMetrics m = im.metrics();
    EXPECT_EQ(m.pixels, 12u);
    EXPECT_EQ(m.truthShadowed, 12u);
    EXPECT_EQ(m.rmse, 0);
    EXPECT_EQ(m.max, 0);
    EXPECT_EQ(m.leak, 0);
}

TEST(Metrics, LayersArePooled) {
    Images exact(4, 4, 0.0f, 0.0f), wrong(4, 4, 1.0f, 0.0f);
    const MetricLayer layers[2] = {exact.layer(), wrong.layer()};
    ErrorMetrics m = computeMetrics(4, 4, layers);
    EXPECT_EQ(m.pixels, 32u);
    EXPECT_EQ(m.truthShadowed, 32u);
    EXPECT_DOUBLE_EQ(m.misclassified, 0.5);
    EXPECT_DOUBLE_EQ(m.leak, 0.5);
    EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(0.5));
    EXPECT_DOUBLE_EQ(m.mae, 0.5);
    EXPECT_DOUBLE_EQ(m.max, 1.0);
}

TEST(Metrics, ATruthOfExactlyOneHalfCountsAsLitForBoundaries) {
    // Columns 0..6 hold a truth of 0.5 (lit: truth >= 0.5), columns 7.. hold 0.4 (shadowed).
    Images im(16, 5);
    for (uint32_t y = 0; y < 5; ++y)
        for (uint32_t x = 0; x < 16; ++x)
            im.truth[im.at(x, y)] = im.visibility[im.at(x, y)] = x < 7 ? 0.5f : 0.4f;
    EXPECT_EQ(im.metrics(2).pixelsOutsideEdges, 10u * 5); // a boundary: band columns 4..9
    for (uint32_t y = 0; y < 5; ++y)
        for (uint32_t x = 7; x < 16; ++x)
            im.truth[im.at(x, y)] = 0.5f;
    EXPECT_EQ(im.metrics(2).pixelsOutsideEdges, 16u * 5); // 0.5 everywhere: no boundary
}

TEST(Metrics, NoLayersIsAllZero) {
    ErrorMetrics m = computeMetrics(4, 4, {});
    EXPECT_EQ(m.pixels, 0u);
    EXPECT_EQ(m.rmse, 0);
    EXPECT_EQ(m.misclassifiedOutsideEdges, 0);
}

TEST(MetricsDeathTest, SizeMismatchIsAProgrammerError) {
    Images im(4, 4);
    im.mask.pop_back();
    EXPECT_DEATH(im.metrics(), "mask size");
}

TEST(MetricsMask, CountsPixelsTheLightReachesJudgedFromTheLightItself) {
    // A sun travelling +z; a spot at the origin pointing +z with a 0.3 rad outer cone and range
    // 10; a point light at the origin with range 10; one without a range.
    const Light sun{.type = LightType::Directional, .direction = {0, 0, 1}};
    const Light spot{.type = LightType::Spot,
                     .direction = {0, 0, 1},
                     .range = 10.0f,
                     .innerConeAngle = 0.2f,
                     .outerConeAngle = 0.3f};
    const Light point{.type = LightType::Point, .range = 10.0f};
    const Light endless{.type = LightType::Point};
    const float edge = 5.0f * std::tan(0.3f); // the cone's radius at z = 5
    struct Pixel {
        glm::vec3 p, n;
        uint8_t sun, spot, point, endless; // expected mask for each light
    };
    const Pixel pixels[] = {
        {{0, 0, 5}, {0, 0, -1}, 1, 1, 1, 1},            // on the axis, facing all
        {{0, 0, 5}, {0, 0, 1}, 0, 0, 0, 0},             // facing away
        {{0, 0, 5}, {1, 0, 0}, 0, 0, 0, 0},             // edge-on
        {{0, 0.99f * edge, 5}, {0, 0, -1}, 1, 1, 1, 1}, // just inside the cone
        {{0, 1.01f * edge, 5}, {0, 0, -1}, 1, 0, 1, 1}, // just outside it
        {{0, 0, 9.99f}, {0, 0, -1}, 1, 1, 1, 1},        // just inside the range
        {{0, 0, 10.01f}, {0, 0, -1}, 1, 0, 0, 1},       // just beyond it
        {{0, 0, -5}, {0, 0, 1}, 0, 0, 1, 1},            // behind the spot, facing back
        {{6, 0, 0}, {-1, 0, 0}, 0, 0, 1, 1},            // beside: only the point lights
        {{0, 0, 300}, {0, 0, -1}, 1, 0, 0, 1},          // far away
    };
    RenderResult g{.width = std::size(pixels), .height = 1};
    for (const Pixel& px : pixels)
        for (int c = 0; c < 3; ++c)
            g.position.push_back(px.p[c]), g.normal.push_back(px.n[c]);
    for (int c = 0; c < 3; ++c) // and a background pixel
        g.position.push_back(std::nanf("")), g.normal.push_back(std::nanf(""));
    g.width += 1;
    const Light* lights[] = {&sun, &spot, &point, &endless};
    for (int l = 0; l < 4; ++l) {
        const std::vector<uint8_t> mask = lightMask(*lights[l], g);
        ASSERT_EQ(mask.size(), g.width);
        for (size_t i = 0; i < std::size(pixels); ++i) {
            const uint8_t want[] = {pixels[i].sun, pixels[i].spot, pixels[i].point,
                                    pixels[i].endless};
            EXPECT_EQ(mask[i], want[l]) << "light " << l << ", pixel " << i;
        }
        EXPECT_EQ(mask.back(), 0) << "background";
    }
}

} // namespace
} // namespace penumbra
