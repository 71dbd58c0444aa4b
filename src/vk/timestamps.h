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
    void begin(VkCommandBuffer cmd, std::string pass);
    void end(VkCommandBuffer cmd);
    // Milliseconds per pass, in first-recorded order.
    std::vector<std::pair<std::string, double>> read() const;

private:
    VkDevice mDevice;
    QueryPoolHandle mPool;
    double mPeriodNs;
    uint64_t mValidMask;
    uint32_t mMaxScopes;
    std::vector<std::string> mScopes;
    bool mOpen = false;
};

} // namespace penumbra::vk
