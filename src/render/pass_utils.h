#pragma once
// Small helpers the frame's pass files share: dispatch sizes, viewport, attachments.
#include "bindings.h"
#include "vk/resources.h"

#include <vulkan/vulkan.h>

namespace penumbra::render {

// Workgroups of GROUP_SIZE covering n invocations.
inline uint32_t groups(uint32_t n) {
    return (n + GROUP_SIZE - 1) / GROUP_SIZE;
}

inline void setViewport(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
    const VkViewport viewport{.x = 0,
                              .y = 0,
                              .width = static_cast<float>(width),
                              .height = static_cast<float>(height),
                              .minDepth = 0,
                              .maxDepth = 1};
    const VkRect2D scissor{.offset = {0, 0}, .extent = {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

// An attachment cleared on load and stored; `view` when not the image's own.
inline VkRenderingAttachmentInfo attachment(const vk::Image& image, VkClearValue clear,
                                            VkImageView view = VK_NULL_HANDLE) {
    return {.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
            .imageView = view ? view : image.view.get(),
            .imageLayout = image.aspect == VK_IMAGE_ASPECT_DEPTH_BIT
                               ? VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL
                               : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
            .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
            .clearValue = clear};
}

} // namespace penumbra::render
