#include "report/light_mask.h"

#include <cmath>

namespace penumbra {

std::vector<uint8_t> lightMask(const Light& light, const RenderResult& g) {
    const size_t pixels = size_t{g.width} * g.height;
    std::vector<uint8_t> mask(pixels, 0);
    const glm::vec3 axis = glm::normalize(light.direction);
    const float cosOuter = std::cos(light.outerConeAngle);
    for (size_t i = 0; i < pixels; ++i) {
        const glm::vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
        const glm::vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
        if (!std::isfinite(p.x) || !std::isfinite(n.x))
            continue;
        if (light.type == LightType::Directional) {
            mask[i] = glm::dot(n, -axis) > 0.0f;
            continue;
        }
        const glm::vec3 toLight = light.position - p;
        const float distance = glm::length(toLight);
        if (distance <= 0.0f || glm::dot(n, toLight) <= 0.0f)
            continue;
        if (light.range > 0.0f && distance > light.range)
            continue; // glTF's range: the light's contribution is zero beyond it
        // The composite's cone falls to zero at the outer angle.
        if (light.type == LightType::Spot && glm::dot(-toLight / distance, axis) <= cosOuter)
            continue;
        mask[i] = 1;
    }
    return mask;
}

std::vector<std::vector<uint8_t>> lightMasks(const Scene& lit, const RenderResult& r) {
    std::vector<std::vector<uint8_t>> masks(r.visibility.size());
    for (const LightShadow& s : r.lights)
        if (s.visibilityIndex >= 0)
            masks[static_cast<size_t>(s.visibilityIndex)] = lightMask(lit.lights[s.sceneLight], r);
    return masks;
}

} // namespace penumbra
