#pragma once
// Fits each light's shadow projection to the scene: a directional light gets the seeds'
// orthographic box fitted tightly around the scene bounds in light space; a spot light gets a
// perspective frustum around its cone, with near and far planes hugging the scene.
#include "penumbra/scene.h"

#include <glm/glm.hpp>

#include <cstdint>

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
};

LightProjection fitDirectional(const Light& light, const Bounds& scene, uint32_t mapSize);
LightProjection fitSpot(const Light& light, const Bounds& scene, uint32_t mapSize);
// Dispatches on light.type; point lights have no single projection (programmer error).
LightProjection fitLight(const Light& light, const Bounds& scene, uint32_t mapSize);

} // namespace penumbra
