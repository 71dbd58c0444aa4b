#pragma once
// The viewer's display pass (shaders/viewer_display.comp): from the frame's targets to the image
// the window shows: the lit image (split between techniques A and B), one light's visibility, a
// layer of the depth map, the cascade each pixel reads, or an image the host made (the error heat
// map). Its output is left ready to blit into the swapchain image.
#include "render/frame.h"
#include "viewer_types.h"
#include "vk/pipelines.h"
#include "vk/resources.h"

#include <span>

namespace penumbra::viewer {

class DisplayPass {
public:
    explicit DisplayPass(const vk::Context& ctx);
    // Makes the output and overlay images for this size when it changes (the device must be
    // idle then).
    void resize(uint32_t width, uint32_t height);
    // The overlay (RGBA8, the output's size, rows top to bottom), copied in by the next record.
    // The device must be idle.
    void setOverlay(std::span<const uint8_t> rgba);
    // `b`: technique B's frame, or null. Leaves the output in vk::kBlitRead.
    void record(VkCommandBuffer cmd, const render::FrameOutputs& a, const render::FrameOutputs* b,
                const gpu::DisplayPush& push);
    const vk::Image& output() const { return mOutput; }

private:
    const vk::Context& mCtx;
    vk::PipelineLayout mLayout;
    vk::PipelineHandle mPipeline;
    vk::SamplerHandle mNearest;
    vk::Image mOutput, mOverlay;
    vk::Buffer mOverlayUpload;
    bool mOverlayPending = false;
};

} // namespace penumbra::viewer
