#pragma once
// The CPU reference of the `sdf` technique's field (issue 13): the exact distance from a point to
// a scene's triangles, signed by the generalised winding number [Jacobson et al. 2013] where the
// geometry is closed. The GPU field builder is checked against it; it is a brute-force loop over
// every triangle, for tests and small scenes only.
#include "penumbra/scene.h"
#include "penumbra/settings.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace penumbra::shadows {
struct TechniqueModule;
}

namespace penumbra {

// The point of triangle (a, b, c) closest to p [Ericson, Real-Time Collision Detection, 5.1.5]:
// by the Voronoi region of p among the triangle's vertices, edges and face.
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c);

// The solid angle triangle (a, b, c) subtends at p over 4 pi [Van Oosterom and Strackee 1983],
// positive when p lies behind it (on the side its normal (b - a) x (c - a) points away from).
// Summed over a closed mesh wound counter-clockwise seen from outside: 1 inside, 0 outside.
double windingContribution(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                           const glm::dvec3& c);

struct FieldSample {
    double distance = 0; // to the nearest triangle, >= 0
    double winding = 0;  // generalised winding number of the whole scene at the point
    // Negative inside closed geometry (winding above one half), positive elsewhere.
    double signedDistance() const { return winding > 0.5 ? -distance : distance; }
};

FieldSample sampleDistanceField(const Scene& scene, const glm::dvec3& p);

// A field sampled on a grid (the GPU's, read back): voxel centres at origin + (i + 1/2) voxel,
// x fastest. sample() interpolates trilinearly, clamped at the outer voxel centres, as the
// tracer's sampler does.
struct FieldGrid {
    glm::vec3 origin{0.0f};
    float voxel = 1.0f;
    glm::uvec3 size{0u};
    std::vector<float> values;
    float sample(const glm::vec3& p) const;
    bool contains(const glm::vec3& p) const;
};

struct TraceSettings {
    uint32_t steps = 0;
    float startOffset = 0.0f; // voxels
    float k = 0.0f;           // 0: from the light's size
    float minStep = 0.0f;     // voxels
    float thickness = 0.0f;   // voxels: open geometry's half-thickness (gpu::ownSurface)
    bool horizon = true;
};
// What the visibility pass gets for `parameters`: the tracing module's own packing (sdf's,
// gpu::SdfParams) and its horizon constant, so the mirror cannot drift from the shader's settings.
TraceSettings traceSettingsOf(const shadows::TechniqueModule& tracer,
                              const ParameterValues& parameters);

// The CPU mirror of the sdf tracer (shaders/include/shadow_sdf.glsl, the same sdf_math.h
// steps): the visible fraction of `light` at receiver `world` with triangle normal `face`.
float traceFieldVisibility(const FieldGrid& field, const Light& light, const glm::vec3& world,
                           const glm::vec3& face, const TraceSettings& settings);

} // namespace penumbra
