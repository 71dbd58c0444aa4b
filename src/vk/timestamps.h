#pragma once
// GPU time per named pass from timestamp queries. One frame: reset(), then begin()/end() around
// each pass, then read() after the frame's fence. Passes with the same name add up (one shadow
// pass per light counts as "shadow").
#include "vk/context.h"
#include "vk/handles.h"

#include <string>
#include <utility>
#include <vector>

namespace penumbra::vk {

class GpuTimer {
public:
    GpuTimer(const Context& ctx, uint32_t maxScopes);
    void reset(VkCommandBuffer cmd);
    void begin(VkCommandBuffer cmd, std::string pass, CostGroup group);
    void end(VkCommandBuffer cmd);
    // Milliseconds per pass (PassTime::medianMs: this frame's), in first-recorded order.
    std::vector<PassTime> read() const;

private:
    VkDevice mDevice;
    QueryPoolHandle mPool;
    double mPeriodNs;
    uint64_t mValidMask;
    uint32_t mMaxScopes;
    std::vector<std::pair<std::string, CostGroup>> mScopes;
    bool mOpen = false;
};

// Each scope's milliseconds added up by name, in first-recorded order (what read() returns).
std::vector<PassTime> addUpByName(const std::vector<std::pair<std::string, CostGroup>>& scopes,
                                  const std::vector<double>& ms);

} // namespace penumbra::vk
