#pragma once
// Fills the FrameData uniform block: the camera, the composite knobs, and every technique
// setting the visibility pass reads (the same block feeds the filter probe of the tests).
#include "light_geometry.h"
#include "frame_block.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "vk/context.h"

#include <algorithm>

namespace penumbra::render {

gpu::FrameData frameData(const Camera& camera, const RenderOptions& options, uint32_t lightCount,
                         const vk::Context& ctx);
// The technique part alone: pcf.*, bias.receiver*, the Poisson disk, and whether the device
// filters depth comparisons in hardware (with how many sub-texel bits).
void setTechniqueSettings(gpu::FrameData& frame, const ParameterValues& params,
                          bool hardwareDepthFilter, uint32_t subTexelBits);

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
