#pragma once
// What the `sdf` technique's field is built from, prepared on the CPU once per scene and
// resolution: the field's box and voxels, the triangles (closed surfaces signed by their winding,
// open ones given a thickness, alpha-tested ones cut down to their covered parts), a coarse
// grid of bricks listing the triangles near each, and each brick's nearest triangle. The GPU passes
// (src/render/distance_field.h) compute the distances from these.
#include "pass_types.h"
#include "penumbra/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::shadows {

// The most voxels a field may have (R32F: 512 MiB; the build holds two R32UI id images more).
inline constexpr uint64_t kMaxFieldVoxels = uint64_t{1} << 27;
// Voxels of free space around the scene's bounds on each side.
inline constexpr uint32_t kFieldPadding = 2;

struct FieldLayout {
    glm::vec3 origin{0.0f}; // the box's lowest corner
    float voxel = 1.0f;     // a voxel's side, world units
    glm::uvec3 size{0u};    // voxels per axis, each a multiple of FIELD_BRICK
    uint64_t voxels() const { return uint64_t{size.x} * size.y * size.z; }
    glm::uvec3 bricks() const { return size / FIELD_BRICK; }
    glm::vec3 voxelCentre(glm::uvec3 v) const { return origin + (glm::vec3(v) + 0.5f) * voxel; }
};

// sdf.resolution 0 (automatic): the finest resolution, from kAutoFieldResolutionMin to
// kAutoFieldResolutionMax voxels on the longest axis, whose bounds hold at most
// kAutoFieldVoxels voxels. A fixed resolution gives a flat scene (a wide ground and small
// casters) voxels as large as its casters; a voxel budget gives it as many voxels as a cube.
inline constexpr uint64_t kAutoFieldVoxels = uint64_t{1} << 23;
inline constexpr uint32_t kAutoFieldResolutionMin = 256, kAutoFieldResolutionMax = 1024;
// The resolution `requested` (sdf.resolution) stands for on `bounds`: itself, or for 0 the
// automatic one. Throws InputError("sdf.resolution", ...) for 1 to 15.
uint32_t fieldResolution(const Bounds& bounds, uint32_t requested);

// fieldResolution(bounds, resolution) voxels on the bounds' longest axis, cubic voxels,
// kFieldPadding around, each axis rounded up to whole bricks. Throws
// InputError("sdf.resolution", ...) past kMaxFieldVoxels.
FieldLayout fieldLayout(const Bounds& bounds, uint32_t resolution);

struct FieldGeometry {
    std::vector<gpu::FieldTriangle> triangles;
    // Brick b lists triangles[brickList[brickStarts[b]] .. brickList[brickStarts[b + 1] - 1]]:
    // every triangle within one brick of the brick's box (so a voxel's nearest triangle is in its
    // brick's list whenever it is that close, and every triangle crossing the brick is).
    std::vector<uint32_t> brickStarts, brickList;
    // Per brick, the triangle nearest to its centre (jump flooding over the bricks from those
    // with a list): the far voxels' candidates, those of their brick and its 26 neighbours.
    std::vector<uint32_t> brickNearest;
    // Per brick, the candidates sdf_flood measures for its far voxels (farCandidates): bricks + 1
    // offsets into this array, then the lists.
    std::vector<uint32_t> farCandidates;
    uint32_t sceneTriangles = 0;                     // the scene's, as given
    uint32_t closedTriangles = 0, openTriangles = 0; // of `triangles`
    uint32_t alphaTriangles = 0;       // the scene's alpha-tested triangles, before they were cut
    uint32_t alphaPieces = 0;          // what those were cut into (part of `triangles`)
    std::vector<std::string> warnings; // closed surfaces taken as shells (Closure::shells)
};

// Which of the scene's triangles belong to closed surfaces: welded by position (to a millionth of
// the scene's size), a connected set of triangles is closed when each of its edges is shared by
// exactly two of them, wound in opposite directions. Alpha-tested materials are never closed, nor
// are surfaces that hold a point or spot light or a camera inside (a room, a sky box: signed as
// solids, every receiver inside would shadow itself); `shells` has a warning for each.
// Also returns, per triangle, whether its closed surface is wound inside out (negative volume).
// (src/shadows/sdf_closure.cpp)
struct Closure {
    std::vector<bool> closed, flipped;
    std::vector<std::string> shells;
    // Triangles on connected surfaces left open by an edge (not alpha-tested ones, nor closed
    // shells): what a warning about open geometry counts.
    uint64_t openEdged = 0;
};
Closure closedSurfaces(const Scene& scene);

// `thickness`: open geometry's half-thickness, world units (the distance jump flooding measures).
FieldGeometry fieldGeometry(const Scene& scene, const FieldLayout& layout, float thickness);

} // namespace penumbra::shadows
