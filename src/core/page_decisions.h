#pragma once
// Virtual pages decided the way the device will decide them (docs/techniques.md, "Pages decided
// on the device"): the host cache's rules (PageCache::keyLight and update, withCoarserPages,
// dropMovedPages, pageTable) restated as passes over flat arrays. Each pass is one dispatch over
// the physical pages or the table's entries; an element's work reads the others only through a
// prefix sum or a flag any of them may set, so the result does not depend on the order the
// device runs them in. This is the reference the device's passes are to equal, and it is itself
// checked to equal the host cache decision for decision (tests/test_page_decisions.cpp).
#include "core/moved_casters.h"
#include "core/virtual_maps.h"

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

// A physical page's owner, kept on the device from frame to frame.
struct PageOwner {
    static constexpr uint32_t kFree = ~0u;
    uint32_t level = kFree; // packLevel(light, face, level); kFree: the page holds nothing
    glm::ivec2 page{0};     // absolute in the level's grid
    uint32_t lastUsed = 0;  // the last frame that asked for it
};

// A level's name in an owner: light, face and level in one word (light < 2^16, face < 6,
// level < 2^8).
constexpr uint32_t packLevel(uint32_t light, uint32_t face, uint32_t level) {
    return (light << 16) | (face << 8) | level;
}

struct PageDecisionInputs {
    const std::vector<VirtualLevel>* levels = nullptr; // this frame's, tables from tableOffset
    std::span<const uint32_t> requests;                // one word per entry, non-zero: asked for
    std::span<const uint32_t> lightsRekeyed; // lights whose contents changed: every page goes
    // Per level (or empty: nothing moved), the pages moved casters may draw into
    // (movedPageRects); when any moved, the pages of levels this frame lacks go too.
    std::span<const std::vector<PageRect>> moved;
    uint32_t frame = 0; // increases by one a frame
};

struct PageDecisions {
    std::vector<uint32_t> table;                      // 1 + physical page, or 0
    std::vector<std::pair<uint32_t, PageKey>> render; // physical page, what it must hold
    uint32_t requested = 0, cached = 0, evicted = 0, dropped = 0; // as PageCache::Update
};

// The levels (indices) in the order their missing pages are allocated: the coarsest first (a
// full pool keeps what every reader falls back on), then by light and face; within a level, by
// row and column.
std::vector<size_t> missingPageOrder(const std::vector<VirtualLevel>& levels);

// One frame's decisions; `owners` (one per physical page) carried from the frame before.
PageDecisions decidePages(std::vector<PageOwner>& owners, const PageDecisionInputs& in);

} // namespace penumbra
