#pragma once
// The Poisson disk that Poisson-disk PCF (and later PCSS) rotates per pixel: 64 points in the
// unit disk by Mitchell's best-candidate algorithm with a fixed seed. Best-candidate order is
// progressive, so the first k points are themselves well spread: pcf.samples = k uses them.
#include <glm/glm.hpp>

#include <array>

namespace penumbra {

inline constexpr size_t kPoissonPoints = 64;
const std::array<glm::vec2, kPoissonPoints>& poissonDisk();

} // namespace penumbra
