// Virtual pages decided on the device (page_decisions.comp; src/render/page_decision_passes.h):
// the records the host uploads each frame, the owners the device keeps from frame to frame, the
// counts it returns, the passes' bindings and specialization constant, compiled as GLSL and as
// C++ with static_asserts on their layout. The passes are those of the CPU reference,
// decidePages (src/core/page_decisions.h), which the device's results are checked against.
// clang-format off
#ifndef PENUMBRA_PAGE_PASSES_H
#define PENUMBRA_PAGE_PASSES_H
#include "shared_prelude.h"

#define PAGES_BLOCK 128u          // invocations per workgroup (Vulkan's least maximum); a scan block's slots
#define PAGES_FREE 0xffffffffu    // PageOwnerData::level of a page that holds nothing
#define PAGES_NONE 0xffffffffu    // no level, entry or rank
#define PAGES_MOST_ENTRIES (65535u * PAGES_BLOCK) // a frame's table entries: one dispatch's reach (every device
                                                  // dispatches at least 65535 workgroups along x)

// page_decisions.comp's bindings (set 0, push descriptors).
#define PAGES_LEVELS 0            // PageLevelData[], this frame's levels
#define PAGES_REQUESTS 1          // uint per table entry, non-zero: asked for (the marking's)
#define PAGES_OWNERS 2            // PageOwnerData per physical page, kept across frames
#define PAGES_MOVED 3             // PageRectData[]: each level's moved pages (movedFirst, count)
#define PAGES_REKEYED 4           // bits by light: its contents changed, every page goes
#define PAGES_WANTED 5            // per entry: bit 0 asked for (or a chain's), bit 1 resident
#define PAGES_MISSING 6           // per priority slot: 1 + the entry missing there, or 0
#define PAGES_SUMS 7              // the scan's per-block sums, then their exclusive prefix
#define PAGES_RANKED 8            // per rank: the missing entry
#define PAGES_CANDIDATES 9        // per rank: the physical page that takes it
#define PAGES_RENDER 10           // per rank: PageRenderData, what to render where
#define PAGES_TABLE 11            // the page table: 1 + physical page, or 0
#define PAGES_COUNTS 12           // PageCounts

// The specialization constant that picks the pass (PAGES_PASS_*), in the order they run.
#define SPEC_PAGE_PASS 27
#define PAGES_PASS_FREE 0u        // per physical page: re-keyed lights, moved casters, absent levels
#define PAGES_PASS_WANT 1u        // per entry: the requests and their coarser chains
#define PAGES_PASS_HOLD 2u        // per physical page: resident and asked for: kept, dated
#define PAGES_PASS_MISSING 3u     // per entry: the missing ones, in priority order
#define PAGES_PASS_SCAN_BLOCKS 4u // per block of slots: its count of missing entries
#define PAGES_PASS_SCAN_SUMS 5u   // one workgroup: the blocks' exclusive prefix
#define PAGES_PASS_RANK 6u        // per slot: a missing entry's rank
#define PAGES_PASS_CANDIDATES 7u  // per physical page: a candidate's rank
#define PAGES_PASS_ASSIGN 8u      // per rank: the candidate takes the missing page
#define PAGES_PASS_TABLE 9u       // per physical page: its entry in the table

// The page draws (page_draws.comp, page_*.vert; src/render/page_draw_passes.h): each page the
// decisions render, cleared and drawn into its square of the pool, one instance a page.
#define PAGE_DRAW_LEVELS 0        // PageLevelData[], the decisions' (where each table starts)
#define PAGE_DRAW_VIEWS 1         // PageViewData[], by level: its view-projection and kind
#define PAGE_DRAW_RENDER 2        // PageRenderData[], the decisions' pages to render, by rank
#define PAGE_DRAW_COUNTS 3        // PageCounts, the decisions'
#define PAGE_DRAW_LIST 4          // PageDrawData[2 * pool pages]: orthographic pages, then perspective ones
#define PAGE_DRAW_LIST_COUNTS 5   // uint[2]: how many of each
#define PAGE_DRAW_ORTHO 0u        // PageDrawPush::list: a sun's pages (drawn with depth clamp)
#define PAGE_DRAW_PERSPECTIVE 1u  // a spot's or a cube face's

PENUMBRA_GPU_BEGIN

struct PageLevelData {
    ivec2 firstPage;      // the window's first page in the level's absolute grid
    uint name;            // packLevel(light, face, level)
    uint pagesPerSide;
    uint tableOffset;     // its first entry
    uint parent;          // the next coarser level of its light and face, or PAGES_NONE
    uint priorityStart;   // its first slot in the missing pages' priority order
    uint movedFirst;      // its moved pages' rectangles in PAGES_MOVED
    uint movedCount;
    uint followsCamera;   // 1: a sun's clipmap level (its grid is anchored at the origin)
    uint pad0, pad1;
};

struct PageOwnerData {
    ivec2 page;           // absolute in its level's grid
    uint level;           // packLevel(light, face, level), or PAGES_FREE
    uint lastUsed;        // the last frame that asked for it
};

struct PageRectData {     // pages lo..hi of a level, inclusive (a whole level: the ints' range)
    ivec2 lo;
    ivec2 hi;
};

struct PageRenderData {
    uint physical;        // the pool's page
    uint entry;           // the table entry it now holds
};

struct PageCounts {
    uint requested;       // entries asked for, chains included
    uint cached;          // of them, resident already
    uint missing;         // the others
    uint candidates;      // pages free or not asked for this frame
    uint rendered;        // min(missing, candidates)
    uint evicted;         // of those, pages that held another
    uint dropped;         // missing pages the pool had no room for
    uint tilesRead;       // the candidates pass's work: tiles of the pool its workgroups read
    uint resident;        // pages holding a level's page after the frame's decisions
    uint pad0, pad1, pad2;
};

struct PagePush {
    uint frame;           // increases by one a frame
    uint entries;         // the table's
    uint pages;           // the pool's
    uint levelCount;
    uint anyMoved;        // 1: a caster moved (absent levels' pages go)
    uint rekeyedWords;    // PAGES_REKEYED's length
    uint scanBlocks;      // ceil(entries / PAGES_BLOCK)
    uint pad0;
};

struct PageViewData {
    mat4 viewProj;        // the level's world -> clip
    uvec4 kind;           // x: PAGE_DRAW_ORTHO or PAGE_DRAW_PERSPECTIVE
};

struct PageDrawData {
    mat4 poolFromWorld;   // world -> the pool's clip space (the page's crop, placed in its square)
    vec4 square;          // the square in the pool's NDC: lo.xy, hi.xy (clip distances keep to it)
};

struct PageSetupPush {    // page_draws.comp
    uint pages;           // the pool's
    uint poolPagesPerSide;
    uint levelCount;
    uint pad0;
};

struct PageDrawPush {     // page_*.vert; the size of ShadowPush, so shadow_mask.frag's material follows
    vec4 bias;            // x: the constant depth offset, as ShadowPush::bias
    uvec4 list;           // x: PAGE_DRAW_ORTHO or PAGE_DRAW_PERSPECTIVE, y: the pool's pages, z: its pages a side
    vec4 pad[3];
};

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(PageLevelData) == 48 && offsetof(PageLevelData, name) == 8 &&
              offsetof(PageLevelData, parent) == 20 && offsetof(PageLevelData, followsCamera) == 36);
static_assert(sizeof(PageOwnerData) == 16 && offsetof(PageOwnerData, level) == 8);
static_assert(sizeof(PageRectData) == 16 && offsetof(PageRectData, hi) == 8);
static_assert(sizeof(PageRenderData) == 8);
static_assert(sizeof(PageCounts) == 48 && offsetof(PageCounts, dropped) == 24 &&
              offsetof(PageCounts, resident) == 32);
static_assert(sizeof(PagePush) == 32 && offsetof(PagePush, scanBlocks) == 24);
static_assert(sizeof(PageViewData) == 80 && offsetof(PageViewData, kind) == 64);
static_assert(sizeof(PageDrawData) == 80 && offsetof(PageDrawData, square) == 64);
static_assert(sizeof(PageSetupPush) == 16);
static_assert(sizeof(PageDrawPush) == 80 && offsetof(PageDrawPush, list) == 16);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
