#include "reference/sampling.h"

#include "kernels.h"

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr double kPi = 3.14159265358979323846;

double radicalInverse2(uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    return static_cast<double>(i) * 0x1p-32;
}

} // namespace

uint32_t hashU32(uint32_t v) {
    return gpu::hashU32(v); // the shaders' own (kernels.h)
}

LightCone coneTowards(const Light& light, const glm::dvec3& p) {
    LightCone cone;
    if (light.type == LightType::Directional) {
        cone.axis = -glm::normalize(glm::dvec3(light.direction));
        const double half = 0.5 * glm::radians(static_cast<double>(light.angularDiameter));
        cone.oneMinusCosAlpha = 2.0 * std::sin(0.5 * half) * std::sin(0.5 * half);
        cone.single = !light.hasSize();
        return cone;
    }
    cone.toInfinity = false;
    cone.center = glm::dvec3(light.position);
    cone.radius = light.radius;
    const glm::dvec3 toCenter = cone.center - p;
    const double d = glm::length(toCenter);
    cone.axis = d > 0.0 ? toCenter / d : glm::dvec3(0, 1, 0);
    cone.inside = d <= cone.radius;
    cone.single = !light.hasSize() || cone.inside;
    if (!cone.single) {
        const double sinAlpha = cone.radius / d;
        // 1 - cos a = sin^2 a / (1 + cos a): no cancellation for small lights far away.
        cone.oneMinusCosAlpha = sinAlpha * sinAlpha / (1.0 + std::sqrt(1.0 - sinAlpha * sinAlpha));
    }
    return cone;
}

glm::dvec2 hammersley(uint32_t i, uint32_t n, const glm::dvec2& shift) {
    const glm::dvec2 u((static_cast<double>(i) + 0.5) / static_cast<double>(n), radicalInverse2(i));
    return glm::fract(u + shift);
}

glm::dvec2 pixelShift(uint32_t x, uint32_t y, uint32_t light) {
    const uint32_t h1 = hashU32(x * 0x9E3779B9u ^ hashU32(y ^ hashU32(light + 0x68E31DA4u)));
    const uint32_t h2 = hashU32(h1 ^ 0xB5297A4Du);
    return {static_cast<double>(h1) * 0x1p-32, static_cast<double>(h2) * 0x1p-32};
}

glm::dvec3 sampleDirection(const LightCone& cone, const glm::dvec2& u) {
    if (cone.single)
        return cone.axis;
    // cos(theta) uniform in [cos a, 1]: 1 - cos(theta) = u.x (1 - cos a).
    const double oneMinusCos = u.x * cone.oneMinusCosAlpha;
    const double cosTheta = 1.0 - oneMinusCos;
    const double sinTheta = std::sqrt(std::max(oneMinusCos * (2.0 - oneMinusCos), 0.0));
    const double phi = 2.0 * kPi * u.y;
    const glm::dvec3 a = cone.axis;
    const glm::dvec3 helper = std::abs(a.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t = glm::normalize(glm::cross(helper, a));
    const glm::dvec3 b = glm::cross(a, t);
    return glm::normalize(cosTheta * a + sinTheta * (std::cos(phi) * t + std::sin(phi) * b));
}

double distanceToLight(const LightCone& cone, const glm::dvec3& origin, const glm::dvec3& dir) {
    if (cone.toInfinity)
        return std::numeric_limits<double>::infinity();
    // Nearest intersection with the light sphere (radius 0: the centre itself).
    const glm::dvec3 oc = cone.center - origin;
    const double along = glm::dot(oc, dir);
    const double closest2 = glm::dot(oc, oc) - along * along;
    const double r2 = cone.radius * cone.radius;
    return along - std::sqrt(std::max(r2 - closest2, 0.0));
}

} // namespace penumbra
