#pragma once
// Fits each light's shadow projections to the scene: a directional light gets the seeds'
// orthographic box fitted tightly around the scene bounds in light space; a spot light gets a
// perspective frustum around its cone, with near and far planes hugging the scene; a point light
// gets six perspective cube faces with a guard band (docs/techniques.md, "Point lights").
#include "penumbra/scene.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace penumbra {

struct LightProjection {
    bool perspective = false;
    glm::mat4 view{1.0f};       // world -> light view space
    glm::mat4 projection{1.0f}; // light view -> clip
    glm::mat4 viewProj{1.0f};   // world -> clip
    float nearPlane = 0.0f, farPlane = 0.0f;
    glm::vec4 window{0.0f}; // orthographic l, r, b, t (view units)
    float yfov = 0.0f;      // perspective
    // World size of one shadow-map texel: constant for orthographic; for perspective, the size
    // at unit distance along the light axis (multiply by the distance).
    float texelWorldSize = 0.0f;
    const char* name = ""; // "" for a light's only view; "+x", "-x", ... for cube faces;
                           // "cascade" for a sun's cascades
    // Cascades: the slice of the camera's view distance this view serves, where it starts
    // blending into the next, and the first cascade's texel size over this one's (kernels keep
    // their world size). A view that is not a cascade serves every distance.
    float splitNear = 0.0f, splitFar = std::numeric_limits<float>::max();
    float blendStart = std::numeric_limits<float>::max();
    float kernelScale = 1.0f;
    // The depths (linear, [0, 1] over near..far) the view's receivers can have: what the moment
    // techniques spread their precision over (gpu::ShadowViewData::moments). A cascade's slice
    // of the camera's view is a small part of a depth range that spans the whole scene.
    glm::vec2 receiverDepths{0.0f, 1.0f};
};

// A point light's cube: face i looks down axis i / 2 (x, y, z), towards + when i is even; the
// shaders pick a face with cubeFace() (shaders/include/light_geometry.h), which uses this order.
inline constexpr uint32_t kCubeFaces = 6;

// csm.* (src/core/cascades.h).
struct CascadeSettings {
    uint32_t count = 1;    // csm.cascades, 1..8 (1: one map over the whole scene)
    float lambda = 0.9f;   // csm.lambda: 0 uniform, 1 logarithmic
    float blend = 0.1f;    // csm.blend: fraction of a cascade blended into the next
    bool stabilize = true; // csm.stabilize
};
inline constexpr uint32_t kMaxCascades = 8; // MAX_CASCADES in shaders/include/light_geometry.h

// Texels of each view kept free at its border for filter kernels: a cube face's beyond its 90
// degrees (a kernel centred in the face reads the geometry across the edge from the same map), a
// cascade's around its slice (at most mapSize / 4 either way).
struct GuardBand {
    uint32_t texels = 0; // the most a technique's kernels reach (its widest footprint)
    // When >= 0, its kernels reach no further than the light seen from the receiver (the cone of
    // rays towards it, cut at the near plane), plus fixedTexels: lightSize is the light's size as
    // the views record it (tan of a sun's half angle, a radius). A cascade then keeps the texels
    // that cone spans over the scene's depth, a cube face fixedTexels under a light without
    // size; never more than `texels`. Finer texels where the light is small.
    float lightSize = -1.0f;
    uint32_t fixedTexels = 0;
    GuardBand() = default;
    GuardBand(uint32_t widest) : texels(widest) {} // NOLINT: a plain guard converts
    GuardBand(uint32_t widest, float size, uint32_t fixed)
        : texels(widest), lightSize(size), fixedTexels(fixed) {}
    // A cascade's band, in texels of n: its window 2 halfWindow world units across before the
    // band widens it, the scene `depth` world units deep along the light.
    float cascadeTexels(float halfWindow, float depth, float n) const;
    // A cube face's band, in texels of n.
    float cubeFaceTexels(float n) const;

private:
    float widest(float n) const; // `texels`, at most a quarter of the map
};

// What a light's views need beyond the scene bounds.
struct ViewFitting {
    GuardBand guard;
    // The distance from the light to the nearest surface: the near plane is placed just inside
    // it (infinity when unknown: the near plane then follows the scene bounds).
    float nearestSurface = 0.0f;
    // Cascades of a directional light follow the camera (image aspect `aspect`); without a
    // camera, or with one cascade, a sun gets one map over the whole scene.
    const Camera* camera = nullptr;
    float aspect = 1.0f;
    // visibleDepthRange() of the scene for that camera; empty (x > y): from the bounds.
    glm::vec2 visibleDepths{1.0f, 0.0f};
    CascadeSettings cascades;
};

LightProjection fitDirectional(const Light& light, const Bounds& scene, uint32_t mapSize);
// `nearestSurface`: the distance from the light to the nearest surface, when known (see
// ViewFitting); it keeps the near plane off zero when bounds corners lie behind the light.
LightProjection fitSpot(const Light& light, const Bounds& scene, uint32_t mapSize,
                        float nearestSurface = std::numeric_limits<float>::infinity());
// Face `face` (0..5) of a point light's cube.
LightProjection fitCubeFace(const Light& light, const Bounds& scene, uint32_t mapSize,
                            uint32_t face, const ViewFitting& fitting);
// Every shadow view of a light, in layer order: a sun's cascades (one without them), a spot's
// frustum, a point light's six faces.
std::vector<LightProjection> fitLightViews(const Light& light, const Bounds& scene,
                                           uint32_t mapSize, const ViewFitting& fitting);

} // namespace penumbra
