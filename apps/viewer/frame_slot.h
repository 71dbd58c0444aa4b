#pragma once
// One of the viewer's two frames in flight: its command buffer, the fence that says it is done,
// the semaphore its swapchain image is acquired with, and the timers of its passes.
#include "render/frame.h"
#include "vk/context.h"
#include "vk/timestamps.h"
#include "window.h"

#include <memory>

namespace penumbra::viewer {

struct FrameSlot {
    vk::CommandPoolHandle pool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vk::FenceHandle done;
    SemaphoreHandle acquired;
    std::unique_ptr<vk::GpuTimer> timerA, timerB;
    bool pending = false; // submitted, its timings not read yet
    bool timedB = false;  // it recorded technique B

    explicit FrameSlot(const vk::Context& ctx);
    // Waits for the frame this slot last carried.
    void wait(const vk::Context& ctx) const;
};

} // namespace penumbra::viewer
