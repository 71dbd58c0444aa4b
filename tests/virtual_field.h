#pragma once
// The virtual-map tests' shared setting (tests/test_virtual_maps.cpp,
// tests/test_moved_casters.cpp): an 800 x 30 x 800 field, a sun, a spot and a point light over it,
// and a small virtual map (4096 texels, 32 pages a side, 10 clipmap levels) whose levels they
// check.
#include "core/virtual_maps.h"

#include <vector>

namespace penumbra::virtual_field {

inline const Bounds kField{.min = {-400, 0, -400}, .max = {400, 30, 400}};
inline const Light kSun{.type = LightType::Directional,
                        .direction = glm::normalize(glm::vec3(0.55f, -0.45f, -0.35f))};
inline const Light kSpot{.type = LightType::Spot,
                         .position = {3, 40, 2},
                         .direction = glm::normalize(glm::vec3(-0.1f, -1.0f, 0.05f)),
                         .outerConeAngle = 0.6f};
inline const Light kPoint{.type = LightType::Point, .position = {1, 12, -3}};

inline VirtualSettings small() {
    return {.enabled = true, .size = 4096, .pageSize = 128, .levels = 10, .poolSize = 2048};
}

// `light`'s levels over the field (the nearest surface 5 away), its table from entry 0.
inline std::vector<VirtualLevel> levelsOf(const Light& light, glm::vec3 camera,
                                          const VirtualSettings& s = small()) {
    uint32_t offset = 0;
    return virtualLevels(light, 0, kField, camera, s, {.nearestSurface = 5.0f}, offset);
}

} // namespace penumbra::virtual_field
