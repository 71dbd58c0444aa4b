#pragma once
// The `sdf` technique's signed distance field of a scene, built on the GPU in compute:
//   1. sdf_seed: each voxel's nearest triangle among its brick's list (src/shadows/sdf_field.h),
//   2. sdf_flood: voxels far from everything take the nearest of the triangles nearest to their
//      brick's and its neighbours' centres (jump flooded over the bricks on the CPU), each
//      candidate measured exactly,
//   3. sdf_resolve: the exact distance to the chosen triangle, negative inside closed surfaces
//      (the winding of the closed triangles a column crosses below the voxel).
// Each pass is submitted in slabs, so that a long build reports its progress.
// A SceneRenderer builds it once per scene and field setting (FieldSetting) for a technique that
// declares one (shadows::TechniqueModule::distanceField).
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "render/pipelines.h"
#include "shadows/sdf_field.h"
#include "vk/resources.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::render {

struct DistanceField {
    shadows::FieldLayout layout;
    float thickness = 0.0f;      // open geometry's half-thickness, world units
    vk::Image image;             // R32F, 3D, voxel centres at layout.voxelCentre
    uint32_t sceneTriangles = 0; // the scene's
    uint32_t triangles = 0, closedTriangles = 0, openTriangles = 0; // the field's
    uint32_t alphaTriangles = 0, alphaPieces = 0; // the scene's alpha-tested ones, their pieces
    std::vector<std::string> warnings;            // closed surfaces taken as shells
    double buildMs = 0.0;                         // GPU time of the three passes
    std::vector<PassTime> passMs;                 // each pass's (sdf_seed, sdf_flood, sdf_resolve)
    double cpuMs = 0.0;                           // CPU time of the triangle lists
    uint64_t bytes() const { return layout.voxels() * 4; }
};

// Device memory the build needs at its peak: the field and two id images.
uint64_t fieldBuildBytes(const shadows::FieldLayout& layout);

// The field a module declares (shadows::DistanceFieldDecl) at the parameters' values.
struct FieldSetting {
    uint32_t resolution = 0;        // voxels on the longest axis; 0: automatic
    float thicknessVoxels = 0.0f;   // open geometry's half-thickness
    std::string_view resolutionKey; // the parameter a refusal names
    static FieldSetting of(const shadows::DistanceFieldDecl& decl, const ParameterValues& params);
    auto operator<=>(const FieldSetting&) const = default;
};

// Throws InputError naming the resolution's key when the field of `scene` (invalid triangles
// dropped) does not fit this device: the voxel cap, its 3D image size limit, memory.
shadows::FieldLayout checkDistanceField(const vk::Context& ctx, const Scene& scene,
                                        const FieldSetting& setting);

// Checks as checkDistanceField, then builds. A build that runs past a second reports its
// progress and the time left through `progress`.
DistanceField buildDistanceField(const vk::Context& ctx, FramePipelines& pipelines,
                                 const Scene& scene, const FieldSetting& setting,
                                 const ProgressFn& progress = {});

// One submission of the build: a pass over a slab of the field, voxels [first, first + count)
// along z (along y for sdf_resolve, which walks columns along z). `cost`: its estimated work,
// for the progress's share done.
inline constexpr std::string_view kSeed = "sdf_seed", kFlood = "sdf_flood",
                                  kResolve = "sdf_resolve";
struct FieldSlab {
    std::string_view pass;
    uint32_t first = 0, count = 0;
    bool columns = false;
    double cost = 0.0;
};
// The build's submissions: each pass in `count` slabs of whole bricks (fewer on a thin axis).
std::vector<FieldSlab> fieldSlabs(const shadows::FieldLayout& layout,
                                  const std::vector<uint32_t>& brickStarts, uint32_t count);

// The time left when `fraction` of the work took `seconds`, at the same rate.
double fieldTimeLeft(double fraction, double seconds);
// "distance field 45% (sdf_flood), 12.3 s, about 15 s left": the share done, the time since the
// build began, the time left, what runs next.
std::string fieldProgressLine(double fraction, double elapsedSeconds, double leftSeconds,
                              std::string_view next);

// The field's voxels, x fastest then y then z (tests, the debug slice).
std::vector<float> readDistanceField(const vk::Context& ctx, const DistanceField& field);

} // namespace penumbra::render
