#include "core/light_space.h"

#include "core/cascades.h"

#include "core/projection.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {
namespace {

std::array<glm::vec3, 8> corners(const Bounds& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[i] = {i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
    return c;
}

// Any vector not parallel to `dir`, preferring world up so shadow maps stay upright.
glm::vec3 upFor(const glm::vec3& dir) {
    return std::abs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

} // namespace

LightProjection fitDirectional(const Light& light, const Bounds& scene, uint32_t mapSize) {
    const glm::vec3 dir = glm::normalize(light.direction);
    const glm::vec3 center = scene.center();
    const float radius = std::max(0.5f * glm::length(scene.extent()), 1e-3f);
    LightProjection p;
    p.view = lookAt(center - dir * (2.0f * radius), center, upFor(dir));
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& c : corners(scene)) {
        const glm::vec3 v = glm::vec3(p.view * glm::vec4(c, 1.0f));
        lo = glm::min(lo, v), hi = glm::max(hi, v);
    }
    // A sliver of padding keeps surfaces on the bounds inside the box after rounding.
    const float pad = 1e-4f * radius;
    p.window = {lo.x - pad, hi.x + pad, lo.y - pad, hi.y + pad};
    p.nearPlane = -hi.z - pad; // view looks down -z: distance = -z
    p.farPlane = -lo.z + pad;
    p.projection =
        orthographic(p.window.x, p.window.y, p.window.z, p.window.w, p.nearPlane, p.farPlane);
    p.viewProj = p.projection * p.view;
    p.texelWorldSize =
        std::max(p.window.y - p.window.x, p.window.w - p.window.z) / static_cast<float>(mapSize);
    return p;
}

float GuardBand::widest(float n) const {
    return std::min(static_cast<float>(texels), 0.25f * n);
}

float GuardBand::cascadeTexels(float halfWindow, float depth, float n) const {
    if (lightSize < 0.0f)
        return widest(n);
    // The light's cone from a receiver reaches `reach` world units across before the near plane.
    // c texels hold it once the band (c + f texels, f the fixed ones) widens the window to
    // n / (n - 2 (c + f)) of itself: c >= reach (n - 2 c - 2 f) / (2 halfWindow), least at
    // c = reach (n - 2 f) / (2 halfWindow + 2 reach).
    const auto f = static_cast<float>(fixedTexels);
    const float reach = depth * lightSize;
    const float cone = std::ceil(reach * (n - 2.0f * f) / (2.0f * halfWindow + 2.0f * reach));
    return std::min(widest(n), cone + f);
}

float GuardBand::cubeFaceTexels(float n) const {
    // With size, the cone from a receiver near the light spans most of a face: the widest band.
    return lightSize == 0.0f ? std::min(widest(n), static_cast<float>(fixedTexels)) : widest(n);
}

LightProjection fitSpot(const Light& light, const Bounds& scene, uint32_t mapSize,
                        float nearestSurface) {
    const glm::vec3 dir = glm::normalize(light.direction);
    LightProjection p;
    p.perspective = true;
    p.view = lookAt(light.position, light.position + dir, upFor(dir));
    // The square frustum's half-angle covers the cone; past ~80 degrees one perspective map
    // degenerates, so wider cones are clamped (their rim then falls outside the map: lit).
    const float half = std::clamp(light.outerConeAngle, 0.01f, glm::radians(80.0f));
    p.yfov = 2.0f * half;
    float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
    for (const glm::vec3& c : corners(scene)) {
        const float depth = -(p.view * glm::vec4(c, 1.0f)).z;
        nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
    }
    if (light.range > 0.0f)
        farthest = std::min(farthest, light.range);
    p.farPlane = std::max(farthest * 1.001f, 1e-3f);
    // A light inside the scene bounds has bounds corners behind it; the nearest surface then
    // places the near plane (a surface at that distance lies at least that times the cosine of
    // the frustum's corner ray along the axis). Without either, keep depth precision bounded
    // (far/near <= 1e4) rather than put the near plane at zero.
    if (nearest <= 0.0f && std::isfinite(nearestSurface)) {
        const float t = std::tan(half);
        nearest = std::max(nearest, 0.99f * nearestSurface / std::sqrt(1.0f + 2.0f * t * t));
    }
    p.nearPlane = std::clamp(nearest * 0.999f, p.farPlane * 1e-4f, p.farPlane * 0.5f);
    p.projection = perspectiveLight(p.yfov, 1.0f, p.nearPlane, p.farPlane);
    p.viewProj = p.projection * p.view;
    p.texelWorldSize = 2.0f * std::tan(half) / static_cast<float>(mapSize);
    return p;
}

LightProjection fitCubeFace(const Light& light, const Bounds& scene, uint32_t mapSize,
                            uint32_t face, const ViewFitting& fitting) {
    static constexpr const char* kNames[kCubeFaces] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    glm::vec3 axis(0.0f);
    axis[static_cast<int>(face / 2)] = face % 2 == 0 ? 1.0f : -1.0f;
    LightProjection p;
    p.perspective = true;
    p.name = kNames[face];
    p.view = lookAt(light.position, light.position + axis, upFor(axis));
    // The inner mapSize - 2 guard texels span the 90-degree face (tangent -1..1); the guard band
    // widens it to tangent +-t.
    const float n = static_cast<float>(mapSize);
    const float guard = fitting.guard.cubeFaceTexels(n);
    const float tanHalf = n / (n - 2.0f * guard);
    p.yfov = 2.0f * std::atan(tanHalf);
    float farthest = 0.0f;
    for (const glm::vec3& c : corners(scene))
        farthest = std::max(farthest, glm::dot(c - light.position, axis));
    if (light.range > 0.0f)
        farthest = std::min(farthest, light.range); // nothing beyond the range is lit
    p.farPlane = std::max(farthest * 1.001f, 1e-3f);
    // A point at distance d inside the face's frustum lies at least d / sqrt(1 + 2 t^2) along
    // its axis (at a corner of the face): a near plane there clips no surface. Depth precision
    // stays bounded (far/near <= 1e4).
    const float cornerCos = 1.0f / std::sqrt(1.0f + 2.0f * tanHalf * tanHalf);
    const float nearest = std::isfinite(fitting.nearestSurface)
                              ? 0.99f * fitting.nearestSurface * cornerCos
                              : p.farPlane * 1e-4f;
    p.nearPlane = std::clamp(nearest, p.farPlane * 1e-4f, p.farPlane * 0.5f);
    p.projection = perspectiveLight(p.yfov, 1.0f, p.nearPlane, p.farPlane);
    p.viewProj = p.projection * p.view;
    p.texelWorldSize = 2.0f * tanHalf / n;
    return p;
}

std::vector<LightProjection> fitLightViews(const Light& light, const Bounds& scene,
                                           uint32_t mapSize, const ViewFitting& fitting) {
    if (light.type == LightType::Directional)
        return fitting.camera && fitting.cascades.count > 1
                   ? fitCascades(light, scene, *fitting.camera, fitting.aspect, mapSize,
                                 fitting.cascades, fitting.guard, fitting.visibleDepths)
                   : std::vector<LightProjection>{fitDirectional(light, scene, mapSize)};
    if (light.type == LightType::Spot)
        return {fitSpot(light, scene, mapSize, fitting.nearestSurface)};
    std::vector<LightProjection> faces;
    for (uint32_t face = 0; face < kCubeFaces; ++face)
        faces.push_back(fitCubeFace(light, scene, mapSize, face, fitting));
    return faces;
}

} // namespace penumbra
