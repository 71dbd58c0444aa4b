#include "vk/sync.h"

namespace penumbra::vk {

namespace {

VkImageMemoryBarrier2 barrierOf(VkImage image, const ImageState& from, const ImageState& to,
                                const VkImageSubresourceRange& range) {
    return {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
            .srcStageMask = from.stage,
            .srcAccessMask = from.access,
            .dstStageMask = to.stage,
            .dstAccessMask = to.access,
            .oldLayout = from.layout,
            .newLayout = to.layout,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .image = image,
            .subresourceRange = range};
}

} // namespace

Barriers& Barriers::image(const Image& image, const ImageState& from, const ImageState& to,
                          SubresourceRange range) {
    mImages.push_back(barrierOf(
        image.get(), from, to,
        {.aspectMask = image.aspect,
         .baseMipLevel = range.baseMip,
         .levelCount = range.mipCount ? range.mipCount : image.mipLevels - range.baseMip,
         .baseArrayLayer = range.baseLayer,
         .layerCount = range.layerCount ? range.layerCount : image.layers - range.baseLayer}));
    return *this;
}

Barriers& Barriers::buffer(VkBuffer buffer, const BufferState& from, const BufferState& to) {
    mBuffers.push_back({.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                        .srcStageMask = from.stage,
                        .srcAccessMask = from.access,
                        .dstStageMask = to.stage,
                        .dstAccessMask = to.access,
                        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                        .buffer = buffer,
                        .offset = 0,
                        .size = VK_WHOLE_SIZE});
    return *this;
}

void Barriers::record(VkCommandBuffer cmd) {
    if (empty())
        return;
    const VkDependencyInfo dependency{
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .bufferMemoryBarrierCount = static_cast<uint32_t>(mBuffers.size()),
        .pBufferMemoryBarriers = mBuffers.data(),
        .imageMemoryBarrierCount = static_cast<uint32_t>(mImages.size()),
        .pImageMemoryBarriers = mImages.data()};
    vkCmdPipelineBarrier2(cmd, &dependency);
    mImages.clear();
    mBuffers.clear();
}

void imageBarrier(VkCommandBuffer cmd, const Image& image, const ImageState& from,
                  const ImageState& to, uint32_t baseMip, uint32_t mipCount) {
    Barriers().image(image, from, to, {.baseMip = baseMip, .mipCount = mipCount}).record(cmd);
}

void colorImageBarrier(VkCommandBuffer cmd, VkImage image, const ImageState& from,
                       const ImageState& to) {
    const VkImageMemoryBarrier2 barrier =
        barrierOf(image, from, to, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1});
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

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    const VkMemoryBarrier2 barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                                   .srcStageMask = srcStage,
                                   .srcAccessMask = srcAccess,
                                   .dstStageMask = dstStage,
                                   .dstAccessMask = dstAccess};
    const VkDependencyInfo dependency{.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
                                      .memoryBarrierCount = 1,
                                      .pMemoryBarriers = &barrier};
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void copyImageToBuffer(VkCommandBuffer cmd, const Image& image, VkBuffer buffer) {
    const VkBufferImageCopy region{.bufferOffset = 0,
                                   .imageSubresource = {.aspectMask = image.aspect,
                                                        .mipLevel = 0,
                                                        .baseArrayLayer = 0,
                                                        .layerCount = image.layers},
                                   .imageExtent = {image.width, image.height, image.depth}};
    vkCmdCopyImageToBuffer(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1,
                           &region);
}

} // namespace penumbra::vk
