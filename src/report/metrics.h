#pragma once
// Error of a shadow technique's visibility against the ray-traced ground truth (docs/cli.md,
// compare): the numbers behind metrics.json and the report's table.
#include <array>
#include <cstdint>
#include <span>

namespace penumbra {

// Aggregate error over the counted pixels of one or more lights; fractions lie in [0, 1].
struct ErrorMetrics {
    double rmse = 0, mae = 0, max = 0;    // of v - truth over counted pixels (max: of |v - truth|)
    double misclassified = 0;             // fraction with |v - truth| > 0.5
    double misclassifiedOutsideEdges = 0; // same, over counted pixels outside the edge band
    // Both outside the edge band, where filtering and aliasing cannot explain them:
    double acne = 0; // among counted pixels with truth == 1: fraction with v < 0.9
    double leak = 0; // among counted pixels with truth == 0: fraction with v > 0.1
    // The same errors outside the blur band too, whose radius per pixel is the technique's blur
    // radius on the screen (MetricLayer::blurBand) clamped to [kMinBlurBand, kMaxBlurBand]: what
    // is left is self-shadowing and missing shadow, not the blur a wide kernel is meant to make.
    // Fractions of the same pixels as acne and leak (truthLit, truthShadowed), so never larger.
    double acneBeyondBlur = 0, leakBeyondBlur = 0;
    // Near contacts: among counted pixels the truth shadows (truth < 0.5) from an occluder within
    // the contact band along the ray to the light's centre (MetricLayer::occluderDistance), the
    // fraction the technique leaves lit (v >= 0.5): what a bias that detaches shadows from their
    // casters (peter-panning) loses, and contact shadows give back.
    double leakNearContact = 0;
    uint64_t nearContact = 0;
    uint64_t pixels = 0, pixelsOutsideEdges = 0, truthLit = 0, truthShadowed = 0;
    uint64_t pixelsBeyondBlur = 0, truthLitBeyondBlur = 0, truthShadowedBeyondBlur = 0;
    // The numerators of the fractions above, in pixels.
    uint64_t misclassifiedPixels = 0, misclassifiedOutsideEdgesPixels = 0, acnePixels = 0,
             leakPixels = 0, acneBeyondBlurPixels = 0, leakBeyondBlurPixels = 0,
             leakNearContactPixels = 0;
};

// Fewer fully lit or fully shadowed pixels away from edges than this and acne or leak rest on too
// few pixels to rank techniques by (one pixel would move them by more than 0.2%): the report and
// metrics.json say so.
inline constexpr uint64_t kFewJudgedPixels = 500;

// The blur band's radius never falls below the fixed edge band nor exceeds 8 pixels (a blur
// wider than that on the screen is a soft shadow the truth has too, or a scene seen at grazing
// angles, where a wider band would leave little to judge).
inline constexpr double kMinBlurBand = 2.0, kMaxBlurBand = 8.0;

// One light's images, each width * height values, rows top to bottom.
struct MetricLayer {
    std::span<const float> visibility, truth;
    std::span<const uint8_t> mask; // 1 = counted (faces the light and lies in its frustum)
    // Per pixel, how far (pixels) the technique's filter reaches on the screen there
    // (report/blur_band.h); empty: no blur beyond the fixed band (beyond-blur = outside edges).
    std::span<const float> blurBand = {};
    // Per pixel, the truth's distance to the nearest occluder towards the light's centre
    // (ReferenceResult::occluderDistance), and the band (world units) within which it counts as
    // a contact; empty: no near-contact measure.
    std::span<const float> occluderDistance = {};
    double contactBand = 0.0;
};

// Pools the counted pixels of every layer (several lights -> one set of numbers). A pixel counts
// when its mask is non-zero and both values are finite; the edge band is every pixel within
// Chebyshev distance edgeBand (>= 0) of a pixel whose lit/shadowed truth class differs from a
// 4-neighbour's; the blur band every pixel p within clamp(blurBand[p], 2, 8) of one (a
// NaN blurBand counts as 2, an infinite one as 8). Span sizes that disagree with width * height are
// a programmer error.
ErrorMetrics computeMetrics(uint32_t width, uint32_t height, std::span<const MetricLayer> layers,
                            int edgeBand = 2);

// A coloured truth's error per channel (red, green, blue): the RMSE of `rgb` (3 floats a pixel, a
// technique's light per channel) or, where it is empty, of `grey` in every channel, against
// `truthRgb` (3 floats a pixel), over the pixels computeMetrics counts (mask non-zero, values
// finite). All zeros where none counts. Sizes that disagree are a programmer error.
std::array<double, 3> rmsePerChannel(std::span<const float> rgb, std::span<const float> grey,
                                     std::span<const float> truthRgb,
                                     std::span<const uint8_t> mask);

} // namespace penumbra
