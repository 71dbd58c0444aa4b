#include "scene/interior.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr float kInteriorFovDegrees = 70.0f;

glm::vec3 centreOf(const Scene& scene) {
    return scene.bounds().center();
}

} // namespace

Light defaultSun() {
    return {.name = "default sun",
            .type = LightType::Directional,
            .direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f)),
            .intensity = 2.0f};
}

std::optional<RayHit> firstHit(const Scene& scene, const glm::vec3& origin, const glm::vec3& dir) {
    std::optional<RayHit> best;
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const Vertex& a = scene.vertices[scene.indices[t]];
        const glm::vec3 e1 = scene.vertices[scene.indices[t + 1]].position - a.position;
        const glm::vec3 e2 = scene.vertices[scene.indices[t + 2]].position - a.position;
        // Moller-Trumbore.
        const glm::vec3 p = glm::cross(dir, e2);
        const float det = glm::dot(e1, p);
        if (std::abs(det) < 1e-20f)
            continue;
        const glm::vec3 s = origin - a.position;
        // Edges inclusive (with round-off): a ray through the diagonal of a quad hits it.
        constexpr float kEdge = 1e-5f;
        const float u = glm::dot(s, p) / det;
        if (u < -kEdge || u > 1.0f + kEdge)
            continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(dir, q) / det;
        if (v < -kEdge || u + v > 1.0f + kEdge)
            continue;
        const float distance = glm::dot(e2, q) / det;
        if (distance <= 0.0f || (best && distance >= best->distance))
            continue;
        // Counter-clockwise is the front (glTF): the ray meets the front when it runs against
        // the normal n = cross(e1, e2), and det = dot(e1, cross(dir, e2)) = -dot(dir, n). By
        // winding only, even for double-sided materials: exporters mark closed models
        // double-sided as often as not.
        best = RayHit{.distance = distance, .front = det > 0.0f};
    }
    return best;
}

bool isInterior(const Scene& scene) {
    if (scene.triangleCount() == 0)
        return false;
    const glm::vec3 centre = centreOf(scene);
    for (const glm::vec3 dir : {glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0),
                                glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)}) {
        const auto hit = firstHit(scene, centre, dir);
        if (!hit || !hit->front)
            return false;
    }
    return true;
}

Camera interiorCamera(const Scene& scene) {
    const Bounds b = scene.bounds();
    const glm::vec3 centre = b.center();
    const glm::vec3 extent = b.extent();
    const glm::vec3 along = extent.x >= extent.z ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, -1);
    const float size = std::max(glm::length(extent), 1e-3f);
    return {.name = "auto (interior)",
            .position = centre,
            .target = centre + along * (0.25f * size),
            .yfov = glm::radians(kInteriorFovDegrees),
            .znear = size * 1e-4f,
            .zfar = size * 1.5f};
}

Light defaultLightFor(const Scene& scene) {
    const Light sun = defaultSun();
    if (!isInterior(scene))
        return sun;
    const glm::vec3 centre = centreOf(scene);
    if (!firstHit(scene, centre, -sun.direction))
        return sun; // the sun reaches the middle of the room (an open roof)
    const Bounds b = scene.bounds();
    const auto ceiling = firstHit(scene, centre, glm::vec3(0, 1, 0));
    const float up = ceiling ? ceiling->distance : b.max.y - centre.y;
    const glm::vec3 position = centre + glm::vec3(0.0f, 0.5f * up, 0.0f);
    const auto floor = firstHit(scene, position, glm::vec3(0, -1, 0));
    const float height = floor ? floor->distance : position.y - b.min.y;
    // A point light's irradiance at distance d is I / d^2: the sun's irradiance on that floor.
    return {.name = "default light (interior)",
            .type = LightType::Point,
            .position = position,
            .intensity = sun.intensity * std::max(height * height, 1e-6f)};
}

} // namespace penumbra
