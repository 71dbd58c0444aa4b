#pragma once
// Which pixels the error metrics count for one light: those the light itself reaches, judged from
// the light and not from any shadow projection: they face it (N.L > 0), lie inside a spot's
// outer cone, and within the light's range when it has one. Whatever a technique's views miss
// inside that region counts against the technique.
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// One value per pixel of `gbuffer` (its position and normal), 1 = counted; background pixels
// are 0.
std::vector<uint8_t> lightMask(const Light& light, const RenderResult& gbuffer);
// The mask of every visibility layer of `r`, in its order, for the lights of `lit`.
std::vector<std::vector<uint8_t>> lightMasks(const Scene& lit, const RenderResult& r);

} // namespace penumbra
