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

} // namespace penumbra
