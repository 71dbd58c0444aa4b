#include "report/metrics.h"

#include "penumbra/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace penumbra {
namespace {

// Bits of the per-pixel scratch byte used while building the edge band.
constexpr uint8_t kBoundary = 1; // truth class differs from a 4-neighbour's
constexpr uint8_t kRowBand = 2;  // within edgeBand of a boundary pixel along the row
constexpr uint8_t kBand = 4;     // within edgeBand in Chebyshev distance

bool isLit(float truth) {
    return truth >= 0.5f;
}

// Marks the pixels within Chebyshev distance `band` of a truth-class boundary. The square
// dilation is separable (rows, then columns), and each 1-D pass tracks the nearest marked pixel
// on either side, so the cost is O(pixels) whatever the band width.
std::vector<uint8_t> edgeBandMask(uint32_t width, uint32_t height, std::span<const float> truth,
                                  int band) {
    std::vector<uint8_t> bits(size_t{width} * height, 0);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            size_t i = size_t{y} * width + x;
            if (!std::isfinite(truth[i]))
                continue;
            // Checking the right and lower neighbours visits every 4-neighbour pair once.
            if (x + 1 < width && std::isfinite(truth[i + 1]) &&
                isLit(truth[i]) != isLit(truth[i + 1])) {
                bits[i] |= kBoundary;
                bits[i + 1] |= kBoundary;
            }
            size_t below = i + width;
            if (y + 1 < height && std::isfinite(truth[below]) &&
                isLit(truth[i]) != isLit(truth[below])) {
                bits[i] |= kBoundary;
                bits[below] |= kBoundary;
            }
        }
    }

    const int64_t reach = band;
    constexpr int64_t kFar = std::numeric_limits<int32_t>::max();
    for (uint32_t y = 0; y < height; ++y) {
        uint8_t* row = bits.data() + size_t{y} * width;
        int64_t last = -kFar;
        for (int64_t x = 0; x < int64_t{width}; ++x) {
            if (row[x] & kBoundary)
                last = x;
            if (x - last <= reach)
                row[x] |= kRowBand;
        }
        int64_t next = kFar;
        for (int64_t x = int64_t{width} - 1; x >= 0; --x) {
            if (row[x] & kBoundary)
                next = x;
            if (next - x <= reach)
                row[x] |= kRowBand;
        }
    }

    // Columns are swept a whole row at a time so memory is read in order.
    std::vector<int64_t> nearest(width, -kFar);
    for (int64_t y = 0; y < int64_t{height}; ++y) {
        uint8_t* row = bits.data() + size_t(y) * width;
        for (uint32_t x = 0; x < width; ++x) {
            if (row[x] & kRowBand)
                nearest[x] = y;
            if (y - nearest[x] <= reach)
                row[x] |= kBand;
        }
    }
    std::fill(nearest.begin(), nearest.end(), kFar);
    for (int64_t y = int64_t{height} - 1; y >= 0; --y) {
        uint8_t* row = bits.data() + size_t(y) * width;
        for (uint32_t x = 0; x < width; ++x) {
            if (row[x] & kRowBand)
                nearest[x] = y;
            if (nearest[x] - y <= reach)
                row[x] |= kBand;
        }
    }
    return bits;
}

double fraction(uint64_t count, uint64_t total) {
    return total == 0 ? 0.0 : static_cast<double>(count) / static_cast<double>(total);
}

} // namespace

ErrorMetrics computeMetrics(uint32_t width, uint32_t height, std::span<const MetricLayer> layers,
                            int edgeBand) {
    PENUMBRA_CHECK(edgeBand >= 0, "edge band must not be negative");
    const uint64_t count = uint64_t{width} * height;
    double sumSquared = 0, sumAbsolute = 0, maxAbsolute = 0;
    uint64_t misclassified = 0, misclassifiedOutside = 0, acne = 0, leak = 0;
    ErrorMetrics m;
    for (const MetricLayer& layer : layers) {
        PENUMBRA_CHECK(layer.visibility.size() == count, "visibility size != width * height");
        PENUMBRA_CHECK(layer.truth.size() == count, "truth size != width * height");
        PENUMBRA_CHECK(layer.mask.size() == count, "mask size != width * height");
        const std::vector<uint8_t> bits = edgeBandMask(width, height, layer.truth, edgeBand);
        for (size_t i = 0; i < count; ++i) {
            const float v = layer.visibility[i], t = layer.truth[i];
            if (layer.mask[i] == 0 || !std::isfinite(v) || !std::isfinite(t))
                continue;
            const double error = double{v} - double{t};
            const double absolute = std::abs(error);
            const bool wrongClass = absolute > 0.5;
            ++m.pixels;
            sumSquared += error * error;
            sumAbsolute += absolute;
            maxAbsolute = std::max(maxAbsolute, absolute);
            misclassified += wrongClass;
            if (!(bits[i] & kBand)) {
                ++m.pixelsOutsideEdges;
                misclassifiedOutside += wrongClass;
            }
            // Acne and leak are errors away from shadow edges (self-shadowing, missing
            // shadow): on an edge, a filter's blur or a hard map's aliasing would swamp them.
            // Tolerances absorb float round-off in "fully lit" / "fully shadowed" truth.
            if (bits[i] & kBand)
                continue;
            if (t >= 1.0f - 1e-6f) {
                ++m.truthLit;
                acne += v < 0.9f;
            } else if (t <= 1e-6f) {
                ++m.truthShadowed;
                leak += v > 0.1f;
            }
        }
    }
    if (m.pixels > 0) {
        m.rmse = std::sqrt(sumSquared / static_cast<double>(m.pixels));
        m.mae = sumAbsolute / static_cast<double>(m.pixels);
        m.max = maxAbsolute;
    }
    m.misclassified = fraction(misclassified, m.pixels);
    m.misclassifiedOutsideEdges = fraction(misclassifiedOutside, m.pixelsOutsideEdges);
    m.acne = fraction(acne, m.truthLit);
    m.leak = fraction(leak, m.truthShadowed);
    return m;
}

} // namespace penumbra
