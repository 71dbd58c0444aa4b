#include "penumbra/scene.h"

#include <cmath>

namespace penumbra {
namespace {

bool usable(const glm::vec3& p) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(p[i]) || std::abs(p[i]) > kMaxCoordinate)
            return false;
    return true;
}

} // namespace

size_t dropInvalidTriangles(Scene& scene) {
    const size_t vertexCount = scene.vertices.size();
    std::vector<uint32_t> kept;
    kept.reserve(scene.indices.size());
    size_t dropped = 0;
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const uint32_t i[3] = {scene.indices[t], scene.indices[t + 1], scene.indices[t + 2]};
        if (i[0] >= vertexCount || i[1] >= vertexCount || i[2] >= vertexCount) {
            ++dropped;
            continue;
        }
        const glm::vec3& a = scene.vertices[i[0]].position;
        const glm::vec3& b = scene.vertices[i[1]].position;
        const glm::vec3& c = scene.vertices[i[2]].position;
        // Area in double: float cross products of large, nearly parallel edges round to zero.
        const glm::dvec3 n = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
        if (!usable(a) || !usable(b) || !usable(c) || glm::dot(n, n) <= 0.0) {
            ++dropped;
            continue;
        }
        kept.insert(kept.end(), i, i + 3);
        const glm::vec3 face = glm::vec3(glm::normalize(n));
        for (uint32_t v : i) {
            glm::vec3& normal = scene.vertices[v].normal;
            if (!std::isfinite(normal.x) || !std::isfinite(normal.y) || !std::isfinite(normal.z) ||
                glm::dot(normal, normal) < 1e-12f)
                normal = face;
        }
    }
    dropped += (scene.indices.size() % 3 != 0);
    scene.indices = std::move(kept);
    return dropped;
}

bool castsShadowMap(const Light& light) {
    return light.castsShadow && light.type != LightType::Point;
}

void applyLightSizeOverrides(Scene& scene, float radius, float angleDegrees) {
    for (Light& light : scene.lights) {
        if (radius >= 0.0f && light.type != LightType::Directional)
            light.radius = radius;
        if (angleDegrees >= 0.0f && light.type == LightType::Directional)
            light.angularDiameter = angleDegrees;
    }
}

} // namespace penumbra
