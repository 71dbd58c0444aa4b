#pragma once
// The blurred-moment members' maps on the CPU (vsm, esm, evsm, msm): the two blur passes' result
// at a texel, the bilinear read of it, and vsm.filter=mip's chain and footprint read.
#include "shadows/technique.h"

#include <glm/glm.hpp>

#include <vector>

namespace penumbra::shadows {

// What texel (i, j) of the blurred map holds after the row and column passes: warpedMoments of
// momentDepth (MOMENTS_* `kind`, `exponents` for esm and evsm) blurred by a normalised Gaussian
// of `taps` (scaled in a cascade), clamp-to-edge.
glm::vec4 blurredMoments(const ShadowMapView& map, uint32_t kind, uint32_t taps,
                         glm::vec2 exponents, const gpu::ShadowViewData& view, int i, int j);
// The blurred map at uv, bilinear over the four texels around it; `stored` maps what a texel's
// format keeps of its moments (msm.precision=16), if set.
glm::vec4 momentsAt(const ShadowMapView& map, uint32_t kind, uint32_t taps, glm::vec2 exponents,
                    const gpu::ShadowViewData& view, glm::vec2 uv,
                    glm::vec4 (*stored)(glm::vec4) = nullptr);
// vsm.filter=mip: the blurred moments' mip chain, level by level (vsm_mip.comp) ...
std::vector<std::vector<glm::vec2>> vsmMipChain(const ShadowMapView& map, uint32_t taps,
                                                const gpu::ShadowViewData& view);
// ... and its read over the probe's footprint (momentsMip).
glm::vec2 vsmMomentsMip(const std::vector<std::vector<glm::vec2>>& chain, uint32_t mapSize,
                        const FilterProbe& probe, float maxTaps);

} // namespace penumbra::shadows
