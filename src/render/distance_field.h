#pragma once
// The `sdf` technique's signed distance field of a scene, built on the GPU in compute:
//   1. sdf_seed: each voxel's nearest triangle among its brick's list (src/shadows/sdf_field.h),
//   2. sdf_flood: jump flooding spreads the nearest-triangle ids to voxels far from everything,
//      each candidate measured exactly,
//   3. sdf_resolve: the exact distance to the chosen triangle, negative inside closed surfaces
//      (the winding of the closed triangles a column crosses below the voxel).
// A SceneRenderer builds it once per scene and field setting (sdf.resolution, sdf.thickness).
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "render/pipelines.h"
#include "shadows/sdf_field.h"
#include "vk/resources.h"

#include <cstdint>
#include <vector>

namespace penumbra::render {

struct DistanceField {
    shadows::FieldLayout layout;
    float thickness = 0.0f; // open geometry's half-thickness, world units
    vk::Image image;        // R32F, 3D, voxel centres at layout.voxelCentre
    uint32_t triangles = 0, closedTriangles = 0, openTriangles = 0, alphaTriangles = 0;
    double buildMs = 0.0;         // GPU time of the three passes
    std::vector<PassTime> passMs; // each pass's (sdf_seed, sdf_flood, sdf_resolve)
    double cpuMs = 0.0;           // CPU time of the triangle lists
    uint64_t bytes() const { return layout.voxels() * 4; }
};

// Device memory the build needs at its peak: the field and two id images.
uint64_t fieldBuildBytes(const shadows::FieldLayout& layout);

// Throws InputError naming sdf.resolution when the field of `scene` (invalid triangles dropped)
// does not fit this device: the voxel cap, its 3D image size limit, memory.
shadows::FieldLayout checkDistanceField(const vk::Context& ctx, const Scene& scene,
                                        const ParameterValues& parameters);

// Checks as checkDistanceField, then builds. `thicknessVoxels`: sdf.thickness.
DistanceField buildDistanceField(const vk::Context& ctx, FramePipelines& pipelines,
                                 const Scene& scene, uint32_t resolution, float thicknessVoxels);

// The field's voxels, x fastest then y then z (tests, the debug slice).
std::vector<float> readDistanceField(const vk::Context& ctx, const DistanceField& field);

} // namespace penumbra::render
