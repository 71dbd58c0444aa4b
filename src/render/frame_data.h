#pragma once
// Fills the FrameData uniform block: the camera, the composite knobs, and the settings every
// technique reads (shadows::setSharedSettings; the technique's own go in its parameter block).
#include "frame_block.h"
#include "light_geometry.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "vk/context.h"

#include <algorithm>

namespace penumbra::render {

gpu::FrameData frameData(const Camera& camera, const RenderOptions& options, uint32_t lightCount,
                         const vk::Context& ctx);

// How many records of `bytes` each the lights' or the views' uniform buffer holds on this device
// (the shaders declare `declared`, MAX_UNIFORM_LIGHTS or MAX_UNIFORM_VIEWS).
inline size_t uniformCapacity(const vk::Context& ctx, size_t bytes, size_t declared) {
    return std::min<size_t>(declared, ctx.limits().maxUniformBufferRange / bytes);
}

// ShadowViewData::cascade's distances for a view that is not a cascade: it serves them all.
inline constexpr float kNotACascade = 3.0e38f;

// The shadow view of a probed shadow map (only what the filters read is filled; layer 0).
gpu::ShadowViewData probeViewData(const ProbeLight& light);

} // namespace penumbra::render
