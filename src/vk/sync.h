#pragma once
// sync2 barriers through a few named states. A barrier names where the image comes from and
// where it goes: `imageBarrier(cmd, shadowMap, kDepthWrite, kComputeSampled)`.
#include "vk/resources.h"

#include <vulkan/vulkan.h>

#include <vector>

namespace penumbra::vk {

struct ImageState {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
};

inline constexpr ImageState kUndefined{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                                       VK_IMAGE_LAYOUT_UNDEFINED};
inline constexpr ImageState kDepthWrite{
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL};
inline constexpr ImageState kColorWrite{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                        VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
inline constexpr ImageState kFragmentSampled{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
inline constexpr ImageState kComputeSampled{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
inline constexpr ImageState kComputeWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                          VK_IMAGE_LAYOUT_GENERAL};
inline constexpr ImageState kComputeReadWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                              VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                              VK_IMAGE_LAYOUT_GENERAL};
inline constexpr ImageState kTransferRead{VK_PIPELINE_STAGE_2_COPY_BIT,
                                          VK_ACCESS_2_TRANSFER_READ_BIT,
                                          VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};

inline constexpr ImageState kCopyWrite{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
inline constexpr ImageState kBlitRead{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
inline constexpr ImageState kBlitWrite{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};

// Which mips and layers a barrier covers; a count of 0 means all from the base.
struct SubresourceRange {
    uint32_t baseLayer = 0, layerCount = 0;
    uint32_t baseMip = 0, mipCount = 0;
};

// The stages and accesses on one side of a buffer barrier.
struct BufferState {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
};

// Image and buffer barriers recorded together, in one vkCmdPipelineBarrier2.
class Barriers {
public:
    Barriers& image(const Image& image, const ImageState& from, const ImageState& to,
                    SubresourceRange range = {});
    Barriers& buffer(VkBuffer buffer, const BufferState& from, const BufferState& to);
    bool empty() const { return mImages.empty() && mBuffers.empty(); }
    void record(VkCommandBuffer cmd);

private:
    std::vector<VkImageMemoryBarrier2> mImages;
    std::vector<VkBufferMemoryBarrier2> mBuffers;
};

// One barrier: mip levels [baseMip, baseMip + mipCount) of every layer; mipCount 0: all from
// baseMip.
void imageBarrier(VkCommandBuffer cmd, const Image& image, const ImageState& from,
                  const ImageState& to, uint32_t baseMip = 0, uint32_t mipCount = 0);
// A barrier on the one colour subresource of an image Penumbra does not own (a swapchain's).
void colorImageBarrier(VkCommandBuffer cmd, VkImage image, const ImageState& from,
                       const ImageState& to);
void bufferBarrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 srcStage,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess);
// A global memory barrier: every resource's writes at `srcStage` before `dstStage`'s accesses.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Copies every layer of `image` (in kTransferRead) into `buffer`, tightly packed, layer-major.
void copyImageToBuffer(VkCommandBuffer cmd, const Image& image, VkBuffer buffer);

} // namespace penumbra::vk
