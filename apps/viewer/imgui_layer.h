#pragma once
// Dear ImGui on the viewer's window: its context, the GLFW and Vulkan backends (compiled from the
// sources Debian's libimgui-dev ships), and the one render pass the Vulkan backend needs (the
// accepted exception to dynamic rendering): it loads the swapchain image the frame was blitted
// into, draws the interface over it and leaves it ready to present.
#include "window.h"

#include <vector>

namespace penumbra::viewer {

using RenderPassHandle = vk::DeviceHandle<VkRenderPass, vkDestroyRenderPass>;
using FramebufferHandle = vk::DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>;
using DescriptorPoolHandle = vk::DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;

class ImGuiLayer {
public:
    ImGuiLayer(const vk::Context& ctx, const Window& window, const Swapchain& swapchain);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    // After the swapchain was remade (the device idle).
    void rebuild(const Swapchain& swapchain);
    void newFrame();
    // The render pass over swapchain image `image` (in TRANSFER_DST_OPTIMAL; PRESENT_SRC_KHR
    // after), drawing the interface built since newFrame() unless `draw` is false.
    void record(VkCommandBuffer cmd, uint32_t image, bool draw);

private:
    void initVulkan(const Swapchain& swapchain);
    void shutdown() noexcept;
    const vk::Context& mCtx;
    bool mVulkanBackend = false; // ImGui_ImplVulkan_Init has run
    DescriptorPoolHandle mPool;
    RenderPassHandle mRenderPass;
    std::vector<vk::ImageViewHandle> mViews;
    std::vector<FramebufferHandle> mFramebuffers;
    VkExtent2D mExtent{};
    VkFormat mFormat = VK_FORMAT_UNDEFINED;
};

} // namespace penumbra::viewer
