#pragma once
// Which pixels the error metrics count for one light: those that face it (N.L > 0) and lie
// inside its shadow frustum, where a shadow map can say anything at all.
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// `shadow` is one entry of RenderResult::lights with visibilityIndex >= 0; the scene is the
// rendered one (lights in the same order). 1 = counted.
std::vector<uint8_t> lightMask(const Scene& scene, const RenderResult& gbuffer,
                               const LightShadow& shadow);

} // namespace penumbra
