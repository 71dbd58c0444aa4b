#pragma once
// Culling on the CPU: the index buffer is cut into clusters of a few hundred triangles with their
// world bounds, and each pass draws only the clusters its view's frustum may hold, contiguous
// ones merged into one draw. Lavapipe shades, clips and sets up every triangle of a draw on one
// thread, so what a view cannot see costs it as much as what it can; a sun's cascades each see a
// part of the scene. Conservative: a cluster is dropped only when its box lies wholly outside one
// plane of the frustum, so the images are those of drawing everything.
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::render {

struct Cluster {
    uint32_t firstIndex, indexCount;
    glm::vec3 lo, hi;     // world bounds of its triangles
    bool dynamic = false; // a triangle of it has moved (markDynamicClusters)
};

// Which clusters a pass draws: all; those no pose has moved (a virtual map's static layer,
// virtual.staticLayer); or those one has (drawn over it).
enum class CasterSet { All, Static, Dynamic };

// Triangles per cluster: small enough that a cascade's slice drops most of a large scene, large
// enough that the per-cluster test and the merged draws cost nothing next to the triangles.
inline constexpr uint32_t kClusterTriangles = 256;

// Clusters over `indices` (triangle lists into `positions`), never straddling a boundary in
// `boundaries` (each a first index: the batches'), in index order.
std::vector<Cluster> makeClusters(std::span<const glm::vec3> positions,
                                  std::span<const uint32_t> indices,
                                  std::span<const uint32_t> boundaries);

struct IndexRange {
    uint32_t first, count;
};

// The parts of [first, first + count) (whole clusters) that the frustum of `viewProj` (clip
// space: |x|, |y| <= w, 0 <= z <= w) may show, merged; `depthClamped`: the near and far planes
// do not cull (a sun's casters before its near plane still cast, clamped).
std::vector<IndexRange> visibleRanges(std::span<const Cluster> clusters, uint32_t first,
                                      uint32_t count, const glm::mat4& viewProj, bool depthClamped,
                                      CasterSet set = CasterSet::All);

// Marks dynamic each cluster that holds a triangle of `moved` (a flag per scene triangle;
// `triangleOf`: the scene triangle of each of the index buffer's).
void markDynamicClusters(std::span<Cluster> clusters, std::span<const uint32_t> triangleOf,
                         std::span<const uint8_t> moved);

} // namespace penumbra::render
