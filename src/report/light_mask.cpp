#include "report/light_mask.h"

#include <cmath>

namespace penumbra {

std::vector<uint8_t> lightMask(const Scene& scene, const RenderResult& g,
                               const LightShadow& shadow) {
    const Light& light = scene.lights[shadow.sceneLight];
    const size_t pixels = size_t{g.width} * g.height;
    std::vector<uint8_t> mask(pixels, 0);
    for (size_t i = 0; i < pixels; ++i) {
        const glm::vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
        const glm::vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
        if (!std::isfinite(p.x) || !std::isfinite(n.x))
            continue;
        const glm::vec3 toLight = light.type == LightType::Directional
                                      ? -glm::normalize(light.direction)
                                      : glm::normalize(light.position - p);
        if (glm::dot(n, toLight) <= 0.0f)
            continue;
        const glm::vec4 s = shadow.worldToShadow * glm::vec4(p, 1.0f);
        if (s.w <= 0.0f)
            continue;
        const glm::vec3 uvz = glm::vec3(s) / s.w;
        mask[i] = uvz.x >= 0.0f && uvz.x <= 1.0f && uvz.y >= 0.0f && uvz.y <= 1.0f &&
                  uvz.z >= 0.0f && uvz.z <= 1.0f;
    }
    return mask;
}

} // namespace penumbra
