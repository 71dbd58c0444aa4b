#include "display.h"

#include "vk/sync.h"

#include <cstring>

namespace penumbra::viewer {
namespace {

// A storage image read by a compute shader (the lit images, the overlay).
constexpr vk::ImageState kComputeLoad{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL};

uint32_t groups(uint32_t n) {
    return (n + GROUP_SIZE - 1) / GROUP_SIZE;
}

} // namespace

DisplayPass::DisplayPass(const vk::Context& ctx) : mCtx(ctx) {
    mLayout = vk::createPipelineLayout(
        ctx,
        {{DISPLAY_COLOR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
         {DISPLAY_COLOR_B, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
         {DISPLAY_VISIBILITY_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
         {DISPLAY_DEPTH_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
         {DISPLAY_GBUFFER_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
         {DISPLAY_OVERLAY_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
         {DISPLAY_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
         {DISPLAY_OUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
         {DISPLAY_INTERMEDIATES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
         {DISPLAY_LAYER_RESULTS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
        VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::DisplayPush));
    mPipeline = vk::createComputePipeline(ctx, mLayout, "viewer_display.comp");
    mNearest = vk::createSampler(ctx, {});
}

void DisplayPass::resize(uint32_t width, uint32_t height) {
    if (mOutput && mOutput.width == width && mOutput.height == height)
        return;
    const VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    mOutput = vk::createImage(mCtx, {.name = "viewer display",
                                     .format = VK_FORMAT_R8G8B8A8_UNORM,
                                     .width = width,
                                     .height = height,
                                     .usage = storage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    mOverlay = vk::createImage(mCtx, {.name = "viewer overlay",
                                      .format = VK_FORMAT_R8G8B8A8_UNORM,
                                      .width = width,
                                      .height = height,
                                      .usage = storage | VK_IMAGE_USAGE_TRANSFER_DST_BIT});
    mOverlayUpload =
        vk::createBuffer(mCtx, VkDeviceSize{width} * height * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         vk::MemoryUse::Upload, "viewer overlay upload");
    std::memset(mOverlayUpload.mapped, 0, mOverlayUpload.size);
    mOverlayPending = true; // a bound image must hold something: black until an overlay comes
}

void DisplayPass::setOverlay(std::span<const uint8_t> rgba) {
    std::memcpy(mOverlayUpload.mapped, rgba.data(),
                std::min<size_t>(rgba.size(), mOverlayUpload.size));
    mOverlayPending = true;
}

void DisplayPass::record(VkCommandBuffer cmd, const render::FrameOutputs& a,
                         const render::FrameOutputs* b, const gpu::DisplayPush& push) {
    if (mOverlayPending) {
        vk::imageBarrier(cmd, mOverlay, vk::kUndefined, vk::kCopyWrite);
        const VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                       .imageExtent = {mOverlay.width, mOverlay.height, 1}};
        vkCmdCopyBufferToImage(cmd, mOverlayUpload.get(), mOverlay.get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        vk::imageBarrier(cmd, mOverlay, vk::kCopyWrite, kComputeLoad);
        mOverlayPending = false;
    }
    vk::Barriers toRead;
    toRead.image(*a.color, vk::kComputeWrite, kComputeLoad);
    if (b)
        toRead.image(*b->color, vk::kComputeWrite, kComputeLoad);
    toRead.image(mOutput, vk::kUndefined, vk::kComputeWrite);
    toRead.record(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mPipeline.get());
    vk::PushDescriptors()
        .storageImage(DISPLAY_COLOR, a.color->view.get())
        .storageImage(DISPLAY_COLOR_B, (b ? b : &a)->color->view.get())
        .sampled(DISPLAY_VISIBILITY_MAP, a.visibility->view.get(), mNearest.get())
        .sampled(DISPLAY_DEPTH_MAP, a.depthMap->view.get(), mNearest.get())
        .sampled(DISPLAY_GBUFFER_DEPTH, a.gbufferDepth->view.get(), mNearest.get())
        .storageImage(DISPLAY_OVERLAY_IMAGE, mOverlay.view.get())
        .uniformBuffer(DISPLAY_FRAME, a.frame)
        .storageImage(DISPLAY_OUT, mOutput.view.get())
        .sampled(DISPLAY_INTERMEDIATES, a.intermediates->view.get(), mNearest.get())
        .sampled(DISPLAY_LAYER_RESULTS, a.layerResults->view.get(), mNearest.get())
        .push(mCtx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mLayout);
    vkCmdPushConstants(cmd, mLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, groups(mOutput.width), groups(mOutput.height), 1);
    vk::imageBarrier(cmd, mOutput, vk::kComputeWrite, vk::kBlitRead);
}

} // namespace penumbra::viewer
