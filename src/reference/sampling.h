#pragma once
// Light sampling for the ground truth. Directions are uniform in solid angle over the cone a
// light subtends (a sphere light, or a directional light's angular diameter), drawn from a
// Hammersley set with a per-pixel Cranley-Patterson rotation: stratified within a pixel,
// decorrelated between pixels (noise rather than banding).
#include "penumbra/scene.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace penumbra {

// The cone of directions from a receiver towards one light.
struct LightCone {
    glm::dvec3 axis{0.0};        // unit, towards the light
    double oneMinusCosAlpha = 0; // 1 - cos(half-angle), kept exact for tiny angles
    bool single = true;          // a point or parallel light: one exact ray
    bool toInfinity = true;      // directional: rays never end
    glm::dvec3 center{0.0};      // sphere lights: centre and radius
    double radius = 0;
    bool inside = false; // the receiver is inside the light sphere: fully lit
};

LightCone coneTowards(const Light& light, const glm::dvec3& receiver);

// An integer hash with good avalanche (lowbias32); shaders/include/shadow_pcf.glsl has its twin.
uint32_t hashU32(uint32_t v);

// The i-th of n points of the unit square, rotated by `shift` (each coordinate mod 1).
glm::dvec2 hammersley(uint32_t i, uint32_t n, const glm::dvec2& shift);
// A per-pixel, per-light shift, from an integer hash: deterministic across runs and threads.
glm::dvec2 pixelShift(uint32_t x, uint32_t y, uint32_t light);

// Direction of sample `u` in `cone` (uniform in solid angle).
glm::dvec3 sampleDirection(const LightCone& cone, const glm::dvec2& u);
// Distance along `dir` from `origin` to where the ray reaches the light (inf: directional).
double distanceToLight(const LightCone& cone, const glm::dvec3& origin, const glm::dvec3& dir);

} // namespace penumbra
