#include "vk/sync.h"

namespace penumbra::vk {

void imageBarrier(VkCommandBuffer cmd, const Image& image, const ImageState& from,
                  const ImageState& to, uint32_t baseMip, uint32_t mipCount) {
    const VkImageMemoryBarrier2 barrier{
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
        .srcStageMask = from.stage,
        .srcAccessMask = from.access,
        .dstStageMask = to.stage,
        .dstAccessMask = to.access,
        .oldLayout = from.layout,
        .newLayout = to.layout,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = image.get(),
        .subresourceRange = {.aspectMask = image.aspect,
                             .baseMipLevel = baseMip,
                             .levelCount = mipCount ? mipCount : image.mipLevels - baseMip,
                             .baseArrayLayer = 0,
                             .layerCount = image.layers}};
    const VkDependencyInfo dependency{.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
                                      .imageMemoryBarrierCount = 1,
                                      .pImageMemoryBarriers = &barrier};
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void bufferBarrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 srcStage,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess) {
    const VkBufferMemoryBarrier2 barrier{.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                                         .srcStageMask = srcStage,
                                         .srcAccessMask = srcAccess,
                                         .dstStageMask = dstStage,
                                         .dstAccessMask = dstAccess,
                                         .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                         .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                         .buffer = buffer,
                                         .offset = 0,
                                         .size = VK_WHOLE_SIZE};
    const VkDependencyInfo dependency{.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
                                      .bufferMemoryBarrierCount = 1,
                                      .pBufferMemoryBarriers = &barrier};
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void copyImageToBuffer(VkCommandBuffer cmd, const Image& image, VkBuffer buffer) {
    const VkBufferImageCopy region{.bufferOffset = 0,
                                   .imageSubresource = {.aspectMask = image.aspect,
                                                        .mipLevel = 0,
                                                        .baseArrayLayer = 0,
                                                        .layerCount = image.layers},
                                   .imageExtent = {image.width, image.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1,
                           &region);
}

} // namespace penumbra::vk
