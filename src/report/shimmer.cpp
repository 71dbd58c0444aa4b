#include "report/shimmer.h"

#include "penumbra/error.h"

#include <cmath>

namespace penumbra {
namespace {

glm::vec3 positionAt(const ShimmerFrame& f, size_t i) {
    return {f.position[3 * i], f.position[3 * i + 1], f.position[3 * i + 2]};
}

// Frame t-1 interpolated at pixel coordinates (x, y) (pixel centres at k + 1/2): position,
// visibility and truth; false when a neighbour is background or not counted.
struct Sample {
    glm::vec3 position{0.0f};
    float visibility = 0.0f, truth = 0.0f;
};

bool sampleAt(const ShimmerFrame& f, float x, float y, Sample& out) {
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    if (x0 < 0.0f || y0 < 0.0f || x0 + 1.0f >= static_cast<float>(f.width) ||
        y0 + 1.0f >= static_cast<float>(f.height))
        return false;
    const float wx = fx - x0, wy = fy - y0;
    out = {};
    for (int k = 0; k < 4; ++k) {
        const size_t px = static_cast<size_t>(x0) + (k & 1),
                     py = static_cast<size_t>(y0) + (k >> 1);
        const size_t i = py * f.width + px;
        const float w = (k & 1 ? wx : 1.0f - wx) * (k >> 1 ? wy : 1.0f - wy);
        const glm::vec3 p = positionAt(f, i);
        if (!f.mask[i] || !std::isfinite(p.x) || !std::isfinite(f.visibility[i]))
            return false;
        out.position += w * p;
        out.visibility += w * f.visibility[i];
        if (!f.truth.empty())
            out.truth += w * f.truth[i];
    }
    return true;
}

} // namespace

ShimmerResult measureShimmer(std::span<const ShimmerFrame> frames) {
    ShimmerResult result;
    double sum = 0.0;
    for (size_t t = 1; t < frames.size(); ++t) {
        const ShimmerFrame& now = frames[t];
        const ShimmerFrame& before = frames[t - 1];
        PENUMBRA_CHECK(now.width == before.width && now.height == before.height,
                       "shimmer frames differ in size");
        const size_t pixels = size_t{now.width} * now.height;
        PENUMBRA_CHECK(now.visibility.size() == pixels && now.position.size() == 3 * pixels &&
                           now.mask.size() == pixels &&
                           (now.truth.empty() || now.truth.size() == pixels),
                       "shimmer frame buffers do not match its size");
        for (size_t i = 0; i < pixels; ++i) {
            const glm::vec3 p = positionAt(now, i);
            if (!now.mask[i] || !std::isfinite(p.x) || !std::isfinite(now.visibility[i]))
                continue;
            ++result.counted;
            const glm::vec4 clip = before.viewProj * glm::vec4(p, 1.0f);
            if (clip.w <= 0.0f)
                continue;
            const float x = (0.5f * clip.x / clip.w + 0.5f) * static_cast<float>(now.width);
            const float y = (0.5f * clip.y / clip.w + 0.5f) * static_cast<float>(now.height);
            Sample previous;
            if (!sampleAt(before, x, y, previous))
                continue;
            const float footprint = before.pixelAngle > 0.0f
                                        ? before.pixelAngle * glm::length(p - before.cameraPosition)
                                        : before.pixelSize;
            if (glm::length(previous.position - p) > 0.01f * footprint)
                continue; // another surface, or an edge between two
            double change = static_cast<double>(now.visibility[i]) - previous.visibility;
            if (!now.truth.empty())
                change -= static_cast<double>(now.truth[i]) - previous.truth;
            sum += std::abs(change);
            ++result.matched;
        }
    }
    result.shimmer = result.matched ? sum / static_cast<double>(result.matched) : 0.0;
    return result;
}

} // namespace penumbra
