#include "report/lag.h"

#include "penumbra/error.h"

#include <algorithm>

namespace penumbra {

Lag measureLag(const std::vector<double>& rest, const std::vector<double>& moving) {
    PENUMBRA_CHECK(rest.size() == moving.size(), "measureLag: one error per frame in each");
    Lag lag;
    size_t run = 0;
    for (size_t k = 0; k < rest.size(); ++k) {
        lag.popIn = std::max(lag.popIn, moving[k] - rest[k]);
        if (rest[k] > 0.0)
            lag.popInRatio = std::max(lag.popInRatio, moving[k] / rest[k]);
        const bool lagging = moving[k] > rest[k] * (1.0 + kLagTolerance);
        run = lagging ? run + 1 : 0;
        lag.laggingFrames += lagging;
        lag.lagFrames = std::max(lag.lagFrames, run);
    }
    return lag;
}

} // namespace penumbra
