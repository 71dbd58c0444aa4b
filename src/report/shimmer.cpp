#include "report/shimmer.h"

#include "penumbra/error.h"

#include <cmath>

namespace penumbra {

ShimmerResult measureShimmer(std::span<const ShimmerPair> pairs) {
    ShimmerResult result;
    double sum = 0.0;
    for (const ShimmerPair& p : pairs) {
        const size_t n = p.visibility.size();
        const bool withTruth = !p.truth.empty();
        PENUMBRA_CHECK(p.previous.size() == n && p.mask.size() == n && p.previousMask.size() == n &&
                           (!withTruth || (p.truth.size() == n && p.previousTruth.size() == n)),
                       "shimmer pair sizes differ");
        for (size_t i = 0; i < n; ++i) {
            if (!p.mask[i] || !p.previousMask[i] || !std::isfinite(p.visibility[i]) ||
                !std::isfinite(p.previous[i]))
                continue;
            double change = static_cast<double>(p.visibility[i]) - p.previous[i];
            if (withTruth)
                change -= static_cast<double>(p.truth[i]) - p.previousTruth[i];
            sum += std::abs(change);
            ++result.pixels;
        }
    }
    result.shimmer = result.pixels ? sum / static_cast<double>(result.pixels) : 0.0;
    return result;
}

} // namespace penumbra
