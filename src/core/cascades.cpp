#include "core/cascades.h"

#include "core/projection.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {
namespace {

std::array<glm::vec3, 8> sliceCorners(const ViewFrustum& f, float a, float b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i) {
        const float d = i & 4 ? b : a;
        const glm::vec2 h = f.halfExtentAt(d);
        c[i] = f.position + f.forward * d + f.right * (i & 1 ? h.x : -h.x) +
               f.up * (i & 2 ? h.y : -h.y);
    }
    return c;
}

// The smallest sphere around the slice [a, b]: its centre lies on the view axis, where the near
// and far corners are equally far (or at the far face's centre when that is nearer).
std::pair<glm::vec3, float> sliceSphere(const ViewFrustum& f, float a, float b) {
    const float rNear = glm::length(f.halfExtentAt(a)), rFar = glm::length(f.halfExtentAt(b));
    float t = (b * b - a * a + rFar * rFar - rNear * rNear) / (2.0f * (b - a));
    t = std::clamp(t, a, b);
    const float radius = std::max(std::hypot(t - a, rNear), std::hypot(b - t, rFar));
    return {f.position + f.forward * t, radius};
}

} // namespace

std::vector<float> cascadeSplits(float n, float f, uint32_t count, float lambda) {
    std::vector<float> d(count + 1);
    for (uint32_t i = 0; i <= count; ++i) {
        const float s = static_cast<float>(i) / static_cast<float>(count);
        d[i] = lambda * n * std::pow(f / n, s) + (1.0f - lambda) * (n + (f - n) * s);
    }
    d.front() = n, d.back() = f; // exact ends despite rounding
    return d;
}

glm::vec2 cameraDepthRange(const Camera& camera, const Bounds& scene) {
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c{i & 1 ? scene.max.x : scene.min.x, i & 2 ? scene.max.y : scene.min.y,
                          i & 4 ? scene.max.z : scene.min.z};
        const float d = glm::dot(c - camera.position, forward);
        lo = std::min(lo, d), hi = std::max(hi, d);
    }
    const float nearDistance = std::max(camera.znear, lo);
    const float farDistance = std::min(camera.zfar, hi);
    return {nearDistance, std::max(farDistance, nearDistance * 1.01f + 1e-4f)};
}

glm::vec2 stableDepthRange(glm::vec2 range, const Camera& camera) {
    auto steps = [](float x) { return 4.0f * std::log2(x); }; // quarter powers of two
    const float nearDistance =
        range.x > camera.znear
            ? std::max(camera.znear, std::exp2(std::floor(steps(range.x)) / 4.0f))
            : camera.znear;
    const float farDistance = std::min(camera.zfar, std::exp2(std::ceil(steps(range.y)) / 4.0f));
    return {nearDistance, std::max(farDistance, nearDistance * 1.01f + 1e-4f)};
}

std::vector<LightProjection> fitCascades(const Light& sun, const Bounds& scene,
                                         const Camera& camera, float aspect, uint32_t mapSize,
                                         const CascadeSettings& s, const GuardBand& guardBand,
                                         glm::vec2 visibleDepths) {
    const ViewFrustum frame = viewFrustum(camera, aspect);
    glm::vec2 range =
        visibleDepths.x <= visibleDepths.y ? visibleDepths : cameraDepthRange(camera, scene);
    range.y = std::max(range.y, range.x * 1.01f + 1e-4f);
    if (s.stabilize)
        range = stableDepthRange(range, camera);
    const std::vector<float> d = cascadeSplits(range.x, range.y, s.count, s.lambda);
    const glm::vec3 dir = glm::normalize(sun.direction);
    // One orientation for every cascade and every frame: only the window moves.
    const glm::mat4 rotation = lookAt(
        glm::vec3(0.0f), dir, std::abs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    // Depth: every caster of the scene, whichever slice it shadows. Across: the scene's box.
    glm::vec3 sceneLo(std::numeric_limits<float>::max()), sceneHi(-sceneLo);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c{i & 1 ? scene.max.x : scene.min.x, i & 2 ? scene.max.y : scene.min.y,
                          i & 4 ? scene.max.z : scene.min.z};
        const glm::vec3 v(rotation * glm::vec4(c, 1.0f));
        sceneLo = glm::min(sceneLo, v), sceneHi = glm::max(sceneHi, v);
    }
    const float zLo = sceneLo.z, zHi = sceneHi.z;
    const glm::vec2 sceneCentre = 0.5f * (glm::vec2(sceneLo) + glm::vec2(sceneHi));
    const glm::vec2 sceneHalf = 0.5f * (glm::vec2(sceneHi) - glm::vec2(sceneLo)) + 1e-4f;
    const float pad = 1e-4f * std::max(zHi - zLo, 1e-3f);
    const float n = static_cast<float>(mapSize);
    const float sceneDepth = zHi - zLo + 2.0f * pad; // along the light

    std::vector<LightProjection> cascades;
    for (uint32_t i = 0; i < s.count; ++i) {
        const float a = i == 0 ? d[0] : d[i] - s.blend * (d[i] - d[i - 1]);
        const float b = d[i + 1];
        glm::vec2 centre, half;
        float guard = 0.0f; // texels
        if (s.stabilize) {
            const auto [sphereCentre, radius] = sliceSphere(frame, a, b);
            guard = guardBand.cascadeTexels(radius, sceneDepth, n);
            half = glm::vec2(radius * n / (n - 2.0f * guard)); // the band around the slice
            const float texel = 2.0f * half.x / n;
            centre = glm::vec2(rotation * glm::vec4(sphereCentre, 1.0f));
            centre = glm::floor(centre / texel) * texel; // whole texels: the grid does not slide
        } else {
            glm::vec2 lo(std::numeric_limits<float>::max()), hi(-lo);
            for (const glm::vec3& c : sliceCorners(frame, a, b)) {
                const glm::vec2 p(rotation * glm::vec4(c, 1.0f));
                lo = glm::min(lo, p), hi = glm::max(hi, p);
            }
            centre = 0.5f * (lo + hi);
            const float inner = 0.5f * std::max(hi.x - lo.x, hi.y - lo.y);
            guard = guardBand.cascadeTexels(inner, sceneDepth, n);
            half = glm::vec2(inner * n / (n - 2.0f * guard));
        }
        // Never coarser than one map over the whole scene: past the scene's box there is
        // nothing to shadow, so along an axis where a cascade is wider than the scene it takes
        // the scene's own extent (a fixed one, as stable as the scene). A low sun sees a scene
        // thin along one axis: that axis keeps the finer texels that then resist acne.
        for (int k = 0; k < 2; ++k)
            if (half[k] >= sceneHalf[k])
                centre[k] = sceneCentre[k], half[k] = sceneHalf[k];
        LightProjection p;
        p.name = "cascade";
        p.view = rotation;
        p.window = {centre.x - half.x, centre.x + half.x, centre.y - half.y, centre.y + half.y};
        p.nearPlane = -zHi - pad, p.farPlane = -zLo + pad; // the view looks down -z
        p.projection =
            orthographic(p.window.x, p.window.y, p.window.z, p.window.w, p.nearPlane, p.farPlane);
        p.viewProj = p.projection * p.view;
        p.texelWorldSize = 2.0f * std::max(half.x, half.y) / n;
        p.splitNear = a, p.splitFar = b;
        // The slice's corners bound every receiver it serves; the normal offset and a filter's
        // guard band reach a little past them.
        float lo = std::numeric_limits<float>::max(), hi = -lo;
        for (const glm::vec3& c : sliceCorners(frame, a, b)) {
            const float depth =
                (-(rotation * glm::vec4(c, 1.0f)).z - p.nearPlane) / (p.farPlane - p.nearPlane);
            lo = std::min(lo, depth), hi = std::max(hi, depth);
        }
        const float margin = (guard + 2.0f) * p.texelWorldSize / (p.farPlane - p.nearPlane);
        lo = std::clamp(lo - margin, 0.0f, 1.0f), hi = std::clamp(hi + margin, 0.0f, 1.0f);
        if (hi - lo > 1e-3f)
            p.receiverDepths = {lo, hi};
        p.blendStart = i + 1 < s.count ? b - s.blend * (b - d[i]) : b;
        cascades.push_back(p);
    }
    for (LightProjection& p : cascades)
        p.kernelScale = cascades.front().texelWorldSize / p.texelWorldSize;
    return cascades;
}

} // namespace penumbra
