#pragma once
// Invalidation by caster (docs/techniques.md, "Virtual shadow maps", "Invalidation by what
// moved"): between two poses of a scene, what moved, as world boxes that hold each moved run of
// triangles where it was and where it is; and the resident pages those boxes may draw into, in
// each level's projection. A virtual map keeps every other page across a new pose.
#include "core/virtual_maps.h"
#include "penumbra/scene.h"

#include <span>
#include <vector>

namespace penumbra {

struct MovedCasters {
    // The triangles themselves changed (another count, other indices): no page can be kept.
    bool everything = false;
    // Each a run of at most kMovedRunTriangles consecutive moved triangles: the bounds of their
    // vertices before and after (a triangle moved when a vertex's position, texture coordinate,
    // alpha or material changed: what the depth pass and the alpha test read).
    std::vector<Bounds> boxes;
};

inline constexpr uint32_t kMovedRunTriangles = 32;

MovedCasters movedCasters(const Scene& before, const Scene& after);

// Drops from `cache` every resident page that one of `moved` may draw into: the box's projection
// into the page's level, widened by a texel, overlaps the page. A box partly behind a
// perspective view's eye drops the level's pages; a page of a level not in `levels` is dropped.
// Returns how many pages were dropped.
uint32_t dropMovedPages(PageCache& cache, const std::vector<VirtualLevel>& levels,
                        std::span<const Bounds> moved, uint32_t pageSize);

} // namespace penumbra
