#include "report/shimmer.h"

#include "penumbra/error.h"

#include <cmath>

namespace penumbra {

namespace {

// The mean |change| over the counted pixels; `unchangedOnly`: only where the truth held still.
ShimmerResult meanChange(std::span<const ShimmerPair> pairs, bool unchangedOnly) {
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
            const double truthChange =
                withTruth ? static_cast<double>(p.truth[i]) - p.previousTruth[i] : 0.0;
            if (unchangedOnly && !(std::abs(truthChange) <= kUnchangedTruth))
                continue;
            change -= truthChange;
            sum += std::abs(change);
            ++result.pixels;
        }
    }
    result.shimmer = result.pixels ? sum / static_cast<double>(result.pixels) : 0.0;
    return result;
}

} // namespace

ShimmerResult measureShimmer(std::span<const ShimmerPair> pairs) {
    return meanChange(pairs, false);
}

ShimmerResult measureFlicker(std::span<const ShimmerPair> pairs) {
    for (const ShimmerPair& p : pairs)
        PENUMBRA_CHECK(!p.truth.empty(), "flicker needs each frame's truth");
    return meanChange(pairs, true);
}

} // namespace penumbra
