#pragma once
// Alpha-tested casters for the `sdf` technique's field (src/shadows/sdf_field.h): a triangle cut
// down to the parts its material covers, as open field triangles whose edges facing a hole are
// marked as outlines (FIELD_OUTLINE_*).
#include "pass_types.h"
#include "penumbra/scene.h"

#include <array>
#include <cstdint>
#include <vector>

namespace penumbra::shadows {

gpu::FieldTriangle fieldTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t flags);
uint32_t flagsOf(const gpu::FieldTriangle& t);

// The triangle's n x n grid of pieces (n a power of two, 64 at most, pieces at most 1.5 x `voxel`
// across, fewer while n^2 is past `budget`) is sampled at the pieces' centres, the test the
// shadow pass and the ground truth make. The covered pieces are then merged back up the midpoint
// subdivision that makes the grid: a sub-triangle whose pieces are all covered is kept whole, so
// only the outline stays fine. Appends them to `out`; takes n^2 from `budget`.
void cutByCoverage(const Scene& scene, const std::array<const Vertex*, 3>& v, float voxel,
                   uint64_t& budget, std::vector<gpu::FieldTriangle>& out);

} // namespace penumbra::shadows
