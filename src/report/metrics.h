#pragma once
// Error of a shadow technique's visibility against the ray-traced ground truth (design.md §1):
// the numbers behind metrics.json and the report's table.
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
    uint64_t pixels = 0, pixelsOutsideEdges = 0, truthLit = 0, truthShadowed = 0;
};

// One light's images, each width * height values, rows top to bottom.
struct MetricLayer {
    std::span<const float> visibility, truth;
    std::span<const uint8_t> mask; // 1 = counted (faces the light and lies in its frustum)
};

// Pools the counted pixels of every layer (several lights -> one set of numbers). A pixel counts
// when its mask is non-zero and both values are finite; the edge band is every pixel within
// Chebyshev distance edgeBand (>= 0) of a pixel whose lit/shadowed truth class differs from a
// 4-neighbour's. Span sizes that disagree with width * height are a programmer error.
ErrorMetrics computeMetrics(uint32_t width, uint32_t height, std::span<const MetricLayer> layers,
                            int edgeBand = 2);

} // namespace penumbra
