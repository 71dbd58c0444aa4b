#pragma once
// Cascaded shadow maps for directional lights [Engel 2006, 'Cascaded shadow maps'; Zhang et al.
// 2006, 'Parallel-split shadow maps']: the camera's view distance is cut into slices by the
// practical split scheme, and each slice gets its own orthographic shadow view. Stabilised
// cascades [Valient 2008, 'Stable rendering of cascaded shadow maps'] are fitted to their slice's
// bounding sphere (a size that does not change as the camera turns) and snapped to whole texels
// (a grid that does not slide as it moves). docs/techniques.md, "Cascades".
#include "core/light_space.h"

#include <vector>

namespace penumbra {

// The split distances d_0 = near < d_1 < ... < d_count = far along the camera's view axis:
// d_i = lambda near (far/near)^(i/n) + (1 - lambda) (near + (far - near) i / n).
std::vector<float> cascadeSplits(float nearDistance, float farDistance, uint32_t count,
                                 float lambda);

// The camera's view distances that hold the scene: from max(znear, nearest bounds corner) to
// min(zfar, farthest bounds corner) along the view axis.
glm::vec2 cameraDepthRange(const Camera& camera, const Bounds& scene);
// Stabilised cascades' range, which must not change as the camera turns or moves a little:
// `range` rounded outwards to quarter powers of two, within [znear, zfar].
glm::vec2 stableDepthRange(glm::vec2 range, const Camera& camera);

// Every cascade of `sun` for `camera` (image aspect `aspect`), nearest first, splitting
// `visibleDepths` (visibleDepthRange(); when empty, cameraDepthRange()). Each view carries
// its slice (splitNear, splitFar, blendStart: camera view distances) and kernelScale = the
// first cascade's texel size over its own; `guard` is kept free around each slice
// (GuardBand::cascadeTexels). No cascade is wider than the scene's box seen from the sun.
std::vector<LightProjection> fitCascades(const Light& sun, const Bounds& scene,
                                         const Camera& camera, float aspect, uint32_t mapSize,
                                         const CascadeSettings& settings, const GuardBand& guard,
                                         glm::vec2 visibleDepths = {1.0f, 0.0f});

} // namespace penumbra
