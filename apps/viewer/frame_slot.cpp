#include "frame_slot.h"

#include "shadows/technique.h"
#include "vk/check.h"

namespace penumbra::viewer {

FrameSlot::FrameSlot(const vk::Context& ctx) {
    const VkDevice device = ctx.device();
    const VkCommandPoolCreateInfo poolInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                           .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                           .queueFamilyIndex = ctx.queueFamily()};
    VkCommandPool rawPool = VK_NULL_HANDLE;
    VK_CREATE(vkCreateCommandPool(device, &poolInfo, nullptr, &rawPool));
    pool = vk::CommandPoolHandle(device, rawPool);
    const VkCommandBufferAllocateInfo allocInfo{.sType =
                                                    VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                                .commandPool = rawPool,
                                                .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                                .commandBufferCount = 1};
    VK_CREATE(vkAllocateCommandBuffers(device, &allocInfo, &cmd));
    const VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO,
                                      .flags = VK_FENCE_CREATE_SIGNALED_BIT};
    VkFence fence = VK_NULL_HANDLE;
    VK_CREATE(vkCreateFence(device, &fenceInfo, nullptr, &fence));
    done = vk::FenceHandle(device, fence);
    acquired = createSemaphore(ctx);
    const auto scopes = static_cast<uint32_t>(4 + shadows::kMaxPostPasses);
    timerA = std::make_unique<vk::GpuTimer>(ctx, scopes);
    timerB = std::make_unique<vk::GpuTimer>(ctx, scopes);
}

void FrameSlot::wait(const vk::Context& ctx) const {
    const VkFence fence = done.get();
    ctx.checkWork(vkWaitForFences(ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

} // namespace penumbra::viewer
