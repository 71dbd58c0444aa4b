#include "vk/timestamps.h"

#include "penumbra/error.h"
#include "vk/check.h"

#include <algorithm>

namespace penumbra::vk {

GpuTimer::GpuTimer(const Context& ctx, uint32_t maxScopes)
    : mDevice(ctx.device()), mPeriodNs(ctx.limits().timestampPeriod), mMaxScopes(maxScopes) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &count, families.data());
    const uint32_t bits = families[ctx.queueFamily()].timestampValidBits;
    mValidMask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
    const VkQueryPoolCreateInfo info{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                     .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                     .queryCount = 2 * maxScopes};
    VkQueryPool pool = VK_NULL_HANDLE;
    VK_CREATE(vkCreateQueryPool(mDevice, &info, nullptr, &pool));
    mPool = QueryPoolHandle(mDevice, pool);
}

void GpuTimer::reset(VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, mPool.get(), 0, 2 * mMaxScopes);
    mScopes.clear();
}

void GpuTimer::begin(VkCommandBuffer cmd, std::string pass, CostGroup group) {
    PENUMBRA_CHECK(!mOpen && mScopes.size() < mMaxScopes, "GpuTimer scopes misnested or full");
    for (const auto& [name, declared] : mScopes)
        PENUMBRA_CHECK(name != pass || declared == group,
                       "GpuTimer: pass " + pass + " timed under two cost groups");
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, mPool.get(),
                         static_cast<uint32_t>(2 * mScopes.size()));
    mScopes.emplace_back(std::move(pass), group);
    mOpen = true;
}

void GpuTimer::end(VkCommandBuffer cmd) {
    PENUMBRA_CHECK(mOpen, "GpuTimer::end without begin");
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, mPool.get(),
                         static_cast<uint32_t>(2 * mScopes.size() - 1));
    mOpen = false;
}

std::vector<PassTime> GpuTimer::read() const {
    if (mScopes.empty())
        return {};
    std::vector<uint64_t> ticks(2 * mScopes.size());
    VK_CHECK(vkGetQueryPoolResults(mDevice, mPool.get(), 0, static_cast<uint32_t>(ticks.size()),
                                   ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    std::vector<double> ms(mScopes.size());
    for (size_t i = 0; i < mScopes.size(); ++i) {
        const uint64_t elapsed =
            ((ticks[2 * i + 1] & mValidMask) - (ticks[2 * i] & mValidMask)) & mValidMask;
        ms[i] = static_cast<double>(elapsed) * mPeriodNs * 1e-6;
    }
    return addUpByName(mScopes, ms);
}

std::vector<PassTime> addUpByName(const std::vector<std::pair<std::string, CostGroup>>& scopes,
                                  const std::vector<double>& ms) {
    std::vector<PassTime> result;
    for (size_t i = 0; i < scopes.size(); ++i) {
        const auto& [name, group] = scopes[i];
        auto it = std::find_if(result.begin(), result.end(),
                               [&](const PassTime& entry) { return entry.pass == name; });
        if (it == result.end())
            result.push_back({.pass = name, .cost = group, .medianMs = ms.at(i)});
        else
            it->medianMs += ms.at(i);
    }
    return result;
}

} // namespace penumbra::vk
