#pragma once
// CPU references of the shadow-map filters: shaders/include/shadow_pcf.glsl and shadow_hard.glsl
// transcribed operation for operation (float arithmetic, the same texel clamping as
// textureGather with clamp-to-edge), reading the same FrameData block the GPU reads. The parity
// tests compare them with Renderer::probeTechnique on synthetic shadow maps.
#include "light_geometry.h"
#include "frame_block.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

#include <span>

namespace penumbra {

struct ShadowMapView {
    std::span<const float> depth; // size x size, rows top to bottom
    uint32_t size = 0;
    float texel(int i, int j) const; // clamp-to-edge
};

float hardReference(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f);
float pcfReference(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f);
// x visibility; yzw as Renderer::probeTechnique (PCSS: blocker depth, blockers, radius; VSM: the
// filtered moments and the receiver's moment depth).
glm::vec4 techniqueReference(Technique technique, const ShadowMapView& map,
                             const FilterProbe& probe, const gpu::FrameData& f,
                             const gpu::ShadowViewData& view);

// The smallest |receiver depth + correction - stored depth| over every texel the filter reads:
// how close a probe comes to a comparison tie (tests skip probes a float rounding could flip).
float smallestComparisonMargin(Technique technique, const ShadowMapView& map,
                               const FilterProbe& probe, const gpu::FrameData& f,
                               const gpu::ShadowViewData& view);

} // namespace penumbra
