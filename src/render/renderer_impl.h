#pragma once
// Renderer's private state, shared by the files that implement its methods.
#include "penumbra/renderer.h"
#include "render/frame.h"
#include "render/pipelines.h"
#include "vk/context.h"

namespace penumbra {

struct Renderer::Impl {
    explicit Impl(const DeviceOptions& options) : ctx(options), pipelines(ctx) {}
    vk::Context ctx;
    render::FramePipelines pipelines;
};

// The viewer's way in (apps/viewer): the device, and SceneRenderer's frame recorded into the
// caller's command buffer, so that the caller submits it with its own synchronisation (frames in
// flight, presentation).
struct RendererAccess {
    static const vk::Context& context(const Renderer& renderer);
    static render::FramePipelines& pipelines(Renderer& renderer);
    struct LiveFrame {
        RenderResult result; // lights, views and distance field; no pixels, no times
        const render::FrameTargets* targets; // colour left in vk::kComputeWrite
    };
    // Records one frame of `scene` into `cmd` with ring slot `slot` (the caller must know the
    // frame that used that slot before has completed) and `timer` (read after the frame's
    // fence). Remaking targets or the distance field waits for the device to go idle.
    // `intermediates`: the visibility pass also writes the technique's intermediate results
    // (targets->intermediates: evaluateTechnique's vector, x visibility).
    static LiveFrame recordFrame(SceneRenderer& scene, VkCommandBuffer cmd,
                                 const RenderOptions& options,
                                 const SceneRenderer::FrameState& state, size_t slot,
                                 vk::GpuTimer& timer, bool intermediates,
                                 const ProgressFn& progress = {});
};

} // namespace penumbra
