#pragma once
// A render pass that only clears one attachment, colour or depth, to `value`: how the frame graph's
// device tests write a known value into an image (or one of its layer or level views).
#include <vulkan/vulkan.h>

namespace penumbra::test {

inline void clearThrough(VkCommandBuffer cmd, VkImageView view, VkExtent2D extent, bool depth,
                         float value) {
    VkRenderingAttachmentInfo target{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                     .imageView = view,
                                     .imageLayout = depth
                                                        ? VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL
                                                        : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
    if (depth)
        target.clearValue.depthStencil = {.depth = value};
    else
        target.clearValue.color = {.float32 = {value, 0, 0, 0}};
    const VkRenderingInfo rendering{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                                    .renderArea = {{0, 0}, extent},
                                    .layerCount = 1,
                                    .colorAttachmentCount = depth ? 0u : 1u,
                                    .pColorAttachments = depth ? nullptr : &target,
                                    .pDepthAttachment = depth ? &target : nullptr};
    vkCmdBeginRendering(cmd, &rendering);
    vkCmdEndRendering(cmd);
}

} // namespace penumbra::test
