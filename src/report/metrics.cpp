#include "report/metrics.h"

#include "penumbra/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace penumbra {
namespace {

bool isLit(float truth) {
    return truth >= 0.5f;
}

// Per pixel, the Chebyshev distance to the nearest boundary pixel (one whose lit/shadowed truth
// class differs from a 4-neighbour's), saturated at `cap`. Two raster sweeps of the 3x3
// chamfer with unit weights give the exact Chebyshev distance in O(pixels).
std::vector<uint8_t> edgeDistance(uint32_t width, uint32_t height, std::span<const float> truth,
                                  uint8_t cap) {
    std::vector<uint8_t> d(size_t{width} * height, cap);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            size_t i = size_t{y} * width + x;
            if (!std::isfinite(truth[i]))
                continue;
            // Checking the right and lower neighbours visits every 4-neighbour pair once.
            if (x + 1 < width && std::isfinite(truth[i + 1]) &&
                isLit(truth[i]) != isLit(truth[i + 1]))
                d[i] = d[i + 1] = 0;
            size_t below = i + width;
            if (y + 1 < height && std::isfinite(truth[below]) &&
                isLit(truth[i]) != isLit(truth[below]))
                d[i] = d[below] = 0;
        }
    }
    const auto relax = [&](size_t i, size_t from) {
        d[i] = std::min<uint8_t>(d[i], static_cast<uint8_t>(std::min<int>(d[from] + 1, cap)));
    };
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            size_t i = size_t{y} * width + x;
            if (x > 0)
                relax(i, i - 1);
            if (y > 0) {
                relax(i, i - width);
                if (x > 0)
                    relax(i, i - width - 1);
                if (x + 1 < width)
                    relax(i, i - width + 1);
            }
        }
    for (uint32_t y = height; y-- > 0;)
        for (uint32_t x = width; x-- > 0;) {
            size_t i = size_t{y} * width + x;
            if (x + 1 < width)
                relax(i, i + 1);
            if (y + 1 < height) {
                relax(i, i + width);
                if (x + 1 < width)
                    relax(i, i + width + 1);
                if (x > 0)
                    relax(i, i + width - 1);
            }
        }
    return d;
}

// The blur band's radius at a pixel, in whole pixels (a distance on the pixel grid is whole).
int blurRadiusAt(std::span<const float> blurBand, size_t i) {
    if (blurBand.empty() || std::isnan(blurBand[i]))
        return static_cast<int>(kMinBlurBand);
    return static_cast<int>(
        std::floor(std::clamp(double{blurBand[i]}, kMinBlurBand, kMaxBlurBand)));
}

double fraction(uint64_t count, uint64_t total) {
    return total == 0 ? 0.0 : static_cast<double>(count) / static_cast<double>(total);
}

} // namespace

ErrorMetrics computeMetrics(uint32_t width, uint32_t height, std::span<const MetricLayer> layers,
                            int edgeBand) {
    PENUMBRA_CHECK(edgeBand >= 0 && edgeBand < 255, "edge band must lie in [0, 254]");
    const uint64_t count = uint64_t{width} * height;
    double sumSquared = 0, sumAbsolute = 0, maxAbsolute = 0;
    uint64_t misclassified = 0, misclassifiedOutside = 0, acne = 0, leak = 0;
    uint64_t acneBeyondBlur = 0, leakBeyondBlur = 0, leakNearContact = 0;
    ErrorMetrics m;
    for (const MetricLayer& layer : layers) {
        PENUMBRA_CHECK(layer.visibility.size() == count, "visibility size != width * height");
        PENUMBRA_CHECK(layer.truth.size() == count, "truth size != width * height");
        PENUMBRA_CHECK(layer.mask.size() == count, "mask size != width * height");
        PENUMBRA_CHECK(layer.blurBand.empty() || layer.blurBand.size() == count,
                       "blur band size != width * height");
        PENUMBRA_CHECK(layer.occluderDistance.empty() || layer.occluderDistance.size() == count,
                       "occluder distance size != width * height");
        // Distances past both bands all read the same: saturate just beyond the wider.
        const int cap = std::max(edgeBand, static_cast<int>(kMaxBlurBand)) + 1;
        const std::vector<uint8_t> distance =
            edgeDistance(width, height, layer.truth, static_cast<uint8_t>(std::min(cap, 255)));
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
            // Acne and leak are errors away from shadow edges (self-shadowing, missing
            // shadow): on an edge, a filter's blur or a hard map's aliasing would swamp them.
            // Tolerances absorb float round-off in "fully lit" / "fully shadowed" truth.
            const bool lit = t >= 1.0f - 1e-6f, shadowed = t <= 1e-6f;
            if (distance[i] > edgeBand) {
                ++m.pixelsOutsideEdges;
                misclassifiedOutside += wrongClass;
                m.truthLit += lit;
                acne += lit && v < 0.9f;
                m.truthShadowed += shadowed;
                leak += shadowed && v > 0.1f;
            }
            if (!layer.occluderDistance.empty() && t < 0.5f &&
                layer.occluderDistance[i] <= layer.contactBand) {
                ++m.nearContact;
                leakNearContact += v >= 0.5f;
            }
            // Beyond the blur band and the edge band both: a subset of the pixels acne and leak
            // judge, so the beyond-blur figures cannot exceed theirs.
            if (distance[i] > edgeBand && distance[i] > blurRadiusAt(layer.blurBand, i)) {
                ++m.pixelsBeyondBlur;
                m.truthLitBeyondBlur += lit;
                acneBeyondBlur += lit && v < 0.9f;
                m.truthShadowedBeyondBlur += shadowed;
                leakBeyondBlur += shadowed && v > 0.1f;
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
    m.acneBeyondBlur = fraction(acneBeyondBlur, m.truthLit);
    m.leakBeyondBlur = fraction(leakBeyondBlur, m.truthShadowed);
    m.leakNearContact = fraction(leakNearContact, m.nearContact);
    m.misclassifiedPixels = misclassified;
    m.misclassifiedOutsideEdgesPixels = misclassifiedOutside;
    m.acnePixels = acne;
    m.leakPixels = leak;
    m.acneBeyondBlurPixels = acneBeyondBlur;
    m.leakBeyondBlurPixels = leakBeyondBlur;
    m.leakNearContactPixels = leakNearContact;
    return m;
}

std::array<double, 3> rmsePerChannel(std::span<const float> rgb, std::span<const float> grey,
                                     std::span<const float> truthRgb,
                                     std::span<const uint8_t> mask) {
    const size_t count = mask.size();
    PENUMBRA_CHECK(truthRgb.size() == 3 * count, "rmsePerChannel: truth size != 3 * mask size");
    PENUMBRA_CHECK(rgb.empty() ? grey.size() == count : rgb.size() == 3 * count,
                   "rmsePerChannel: the row's size disagrees with the mask's");
    std::array<double, 3> sum{};
    size_t counted = 0;
    for (size_t i = 0; i < count; ++i) {
        if (mask[i] == 0)
            continue;
        std::array<double, 3> error{};
        bool finite = true;
        for (size_t c = 0; c < 3; ++c) {
            const float v = rgb.empty() ? grey[i] : rgb[3 * i + c], t = truthRgb[3 * i + c];
            finite = finite && std::isfinite(v) && std::isfinite(t);
            error[c] = double{v} - t;
        }
        if (!finite)
            continue;
        ++counted;
        for (size_t c = 0; c < 3; ++c)
            sum[c] += error[c] * error[c];
    }
    for (double& c : sum)
        c = counted == 0 ? 0.0 : std::sqrt(c / static_cast<double>(counted));
    return sum;
}

} // namespace penumbra
