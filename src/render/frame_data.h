#pragma once
// Fills the FrameData uniform block: the camera, the composite knobs, and every technique
// setting the visibility pass reads (the same block feeds the filter probe of the tests).
#include "gpu_types.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "vk/context.h"

namespace penumbra::render {

gpu::FrameData frameData(const Camera& camera, const RenderOptions& options, uint32_t lightCount,
                         const vk::Context& ctx);
// The technique part alone: pcf.*, bias.receiver*, the Poisson disk, and whether the device
// filters depth comparisons in hardware (with how many sub-texel bits).
void setTechniqueSettings(gpu::FrameData& frame, const ParameterValues& params,
                          bool hardwareDepthFilter, uint32_t subTexelBits);

// ShadowViewData::cascade's distances for a view that is not a cascade: it serves them all.
inline constexpr float kNotACascade = 3.0e38f;

// The shadow view of a probed shadow map (only what the filters read is filled; layer 0).
gpu::ShadowViewData probeViewData(const ProbeLight& light);

} // namespace penumbra::render
