#include "scene/sanitize.h"

#include "penumbra/scene.h"

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

bool usable(const glm::vec3& p) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(p[i]) || std::abs(p[i]) > kMaxCoordinate)
            return false;
    return true;
}

glm::dvec3 areaNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    // In double: float cross products of large, nearly parallel edges round to zero.
    return glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
}

} // namespace

bool triangleIsUsable(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::dvec3 n = areaNormal(a, b, c);
    return usable(a) && usable(b) && usable(c) && glm::dot(n, n) > 0.0;
}

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
        if (!triangleIsUsable(a, b, c)) {
            ++dropped;
            continue;
        }
        const glm::dvec3 n = areaNormal(a, b, c);
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
    return light.castsShadow;
}

uint32_t shadowViewCount(const Light& light, uint32_t cascades) {
    if (!castsShadowMap(light))
        return 0;
    switch (light.type) {
    case LightType::Point:
        return 6;
    case LightType::Directional:
        return cascades;
    case LightType::Spot:
        break;
    }
    return 1;
}

namespace {

// Squared distance from p to triangle abc [Ericson 2005, 'Real-Time Collision Detection' 5.1.5:
// the closest point by Voronoi region].
double squaredDistanceToTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                 const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    auto at = [&](const glm::dvec3& q) { return glm::dot(p - q, p - q); };
    if (d1 <= 0 && d2 <= 0)
        return at(a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return at(b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return at(a + ab * (d1 / (d1 - d3)));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return at(c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return at(a + ac * (d2 / (d2 - d6)));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return at(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    const double denom = 1.0 / (va + vb + vc);
    return at(a + ab * (vb * denom) + ac * (vc * denom));
}

} // namespace

float nearestSurfaceDistance(const Scene& scene, const glm::vec3& point) {
    const glm::dvec3 p(point);
    double best = std::numeric_limits<double>::infinity();
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const glm::dvec3 a(scene.vertices[scene.indices[t]].position);
        const glm::dvec3 b(scene.vertices[scene.indices[t + 1]].position);
        const glm::dvec3 c(scene.vertices[scene.indices[t + 2]].position);
        // The triangle's box is nearer than the triangle: skip it when that is already too far.
        const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
        const glm::dvec3 outside = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
        if (glm::dot(outside, outside) >= best)
            continue;
        best = std::min(best, squaredDistanceToTriangle(p, a, b, c));
    }
    return static_cast<float>(std::sqrt(best));
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
