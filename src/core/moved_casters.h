#pragma once
// Invalidation by caster (docs/techniques.md, "Virtual shadow maps", "Invalidation by what
// moved"): between two poses of a scene, what moved, as world boxes that hold each moved
// triangle where it was and where it is (apart); and the resident pages those boxes may draw
// into, in each level's projection. A virtual map keeps every other page across a new pose.
#include "core/virtual_maps.h"
#include "penumbra/scene.h"

#include <array>
#include <span>
#include <vector>

namespace penumbra {

// A moved triangle's corners, where it was or where it is.
struct MovedTriangle {
    std::array<glm::vec3, 3> corners;
};

struct MovedCasters {
    // Each moved triangle's bounds where it was, then where it is (one box when its corners
    // stayed), in triangle order. Triangle t moved when a corner of it differs between the poses
    // in what the depth pass and its alpha test read (position, texture coordinate, alpha,
    // material; corners in order, so the winding too), or when only one pose has a triangle t
    // (a caster added or removed: bounded where it is).
    std::vector<Bounds> boxes;
    // boxes[i]'s triangle: the pages it may draw into are those of the triangle itself, fewer
    // than its box's where it lies long and thin across a level (a swinging rod, a limb).
    std::vector<MovedTriangle> triangles;
    // Each moved triangle's index (in the pose that has it), once, in order.
    std::vector<uint32_t> indices;

    void append(const MovedCasters& more);
    void clear() { boxes.clear(), triangles.clear(), indices.clear(); }
};

MovedCasters movedCasters(const Scene& before, const Scene& after);

// Pages of a level (absolute, in its page grid), inclusive; or the whole level.
struct PageRect {
    bool wholeLevel = false;
    glm::ivec2 lo{0}, hi{-1};
    bool holds(glm::ivec2 p) const {
        return wholeLevel || (p.x >= lo.x && p.y >= lo.y && p.x <= hi.x && p.y <= hi.y);
    }
};

// For each of `levels`, the pages each of `moved` may draw into: the box's projection into the
// level, widened by a texel and the GPU's roundoff; the whole level for a box partly behind a
// perspective view's eye; none for one wholly behind it. With `triangles` (moved[i]'s triangle
// each), a box's pages are its triangle's: the triangle of its projected corners, widened so,
// page row by page row. Only pages that may hold anything are listed: those of a window that
// does not move (a fixed window's level holds no other), and, when `held` is given (one
// rectangle per level, empty: nothing held), those inside it.
std::vector<std::vector<PageRect>> movedPageRects(const std::vector<VirtualLevel>& levels,
                                                  std::span<const Bounds> moved, uint32_t pageSize,
                                                  std::span<const PageRect> held = {},
                                                  std::span<const MovedTriangle> triangles = {});

// What becomes of a resident page that something moved over.
enum class MovedPage {
    Dropped,        // freed: another may take its place (the device's decisions' rule)
    Stale,          // kept in its place with its static layer, to be drawn again before it is read
    StaleLayerLost, // kept in its place, its static layer forgotten: drawn whole again
};

// Drops from `cache` every resident page that one of `moved` may draw into: the box's projection
// into the page's level (its triangle's, with `triangles`), widened by a texel, overlaps the page.
// A box partly behind a perspective view's eye drops the level's pages. `fate`: what becomes of
// those pages (PageCache::staleIf); a page of a level not in `levels` is dropped whatever it
// says. Returns how many pages were dropped or marked.
uint32_t dropMovedPages(PageCache& cache, const std::vector<VirtualLevel>& levels,
                        std::span<const Bounds> moved, uint32_t pageSize,
                        std::span<const MovedTriangle> triangles = {},
                        MovedPage fate = MovedPage::Dropped);

} // namespace penumbra
