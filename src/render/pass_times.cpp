#include "penumbra/pass_times.h"

#include <algorithm>

namespace penumbra {

void appendFrameTimes(std::vector<PassTime>& passes, const std::vector<PassTime>& frame,
                      size_t index) {
    for (const PassTime& p : frame) {
        auto it = std::find_if(passes.begin(), passes.end(),
                               [&](const PassTime& q) { return q.pass == p.pass; });
        if (it == passes.end())
            it = passes.insert(
                passes.end(),
                {.pass = p.pass, .cost = p.cost, .frameMs = std::vector<double>(index, 0.0)});
        it->frameMs.push_back(p.medianMs);
    }
    for (PassTime& p : passes)
        if (p.frameMs.size() < index + 1) // not run in this frame
            p.frameMs.push_back(0.0);
}

void setMedians(std::vector<PassTime>& passes) {
    for (PassTime& p : passes) {
        std::vector<double> values = p.frameMs;
        std::sort(values.begin(), values.end());
        const size_t n = values.size();
        p.medianMs = n == 0       ? 0.0
                     : n % 2 == 1 ? values[n / 2]
                                  : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    }
}

} // namespace penumbra
