#pragma once
// Virtual shadow maps on the host (docs/techniques.md, "Virtual shadow maps"): the levels of a
// light's virtual map and the page cache that decides which pages are resident in the physical
// pool. The page lookup's maths is shared with the shaders (shaders/include/virtual_pages.h).
//
// A sun's virtual map is a clipmap: orthographic levels of the same orientation and depth range,
// level l twice the extent of level l - 1, each centred on the camera and snapped to whole pages
// (a page keeps its place in the world while the camera moves: it stays valid); level
// `levels` - 1 covers the whole scene, and the levels above it are its mips (its window, half the
// pages a side each), down to one page. A spot's is its frustum at `size` texels and its mips down
// to one page; a point light's, six such cube faces. Pages are named by PageKey: a sun's by
// their absolute place in the level's page grid, so a moved window finds the pages it keeps.
#include "core/light_space.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

namespace penumbra {

// The `virtual` parameter family.
struct VirtualSettings {
    bool enabled = false;
    uint32_t size = 16384;      // virtual.size: a level's side in texels
    uint32_t pageSize = 128;    // virtual.pageSize: a page's side in texels
    uint32_t levels = 12;       // virtual.levels: a sun's clipmap levels up to the scene's extent
    uint32_t poolSize = 8192;   // virtual.poolSize: the physical pool's side in texels
    float lodBias = -0.5f;      // virtual.lodBias: levels coarser (+) or finer (-) than a pixel
    bool lodFromImage = true;   // virtual.lodFromImage: lodBias relative to a 1920x1080 image
    bool deviceDecides = false; // virtual.deviceDecides: pages decided in the frame, on the device
    bool staticLayer = false;   // virtual.staticLayer, on the host's decisions: a second pool

    static VirtualSettings of(const ParameterValues& p);
    // The level bias a width x height image reads with: lodBias, and with lodFromImage half a
    // level finer per halving of the pixel count below 1920x1080 (coarser above), within
    // kImageLevels: about the pages a 1080p image asks for, whatever the image.
    float levelBias(uint32_t width, uint32_t height) const;
    uint32_t pagesPerSide() const { return size / pageSize; }
    uint32_t poolPagesPerSide() const { return poolSize / pageSize; }
    uint32_t poolPages() const { return poolPagesPerSide() * poolPagesPerSide(); }
    // Levels of a spot's map or a cube face: the full size, then mips down to one page.
    uint32_t localLevels() const;
    // A sun's: `levels` up to the one over the whole scene, then that one's mips down to one
    // page (an image whose pixels are larger than the scene level's texels reads those).
    uint32_t sunLevels() const { return levels + localLevels() - 1; }
    // Warm-up frames a render runs before its timed ones: decided on the host, pages render a
    // frame after they are asked for (one frame asks, the next renders); else one.
    uint32_t warmUpFrames() const { return enabled && !deviceDecides ? 2 : 1; }
};

// A light's levels (0 without a shadow map) and their page-table entries.
uint32_t virtualViewCount(const Light& light, const VirtualSettings& settings);
uint64_t virtualTableEntries(const Light& light, const VirtualSettings& settings);

// One level of a light's virtual map: a shadow view over pagesPerSide^2 pages.
struct VirtualLevel {
    uint32_t light = 0;         // the scene light
    uint32_t face = 0;          // a point light's cube face; 0 otherwise
    uint32_t level = 0;         // 0 the finest
    LightProjection projection; // the level's whole window
    glm::ivec2 firstPage{0};    // the window's first page in the level's absolute page grid
    uint32_t pagesPerSide = 0;
    uint32_t tableOffset = 0; // its first page-table entry
    // A sun's clipmap level below the scene's mips: its pages are named in a grid anchored at
    // the light space's origin (firstPage moves with the camera); else by their place in the
    // level's fixed window.
    bool followsCamera = false;
    uint32_t tableEntries() const { return pagesPerSide * pagesPerSide; }
};

// What the levels are fitted to, made steady: the scene's bounds snapped outward to a grid
// (anchored at the world's origin) of the power of two at or above 1/64 of their largest side,
// and a light's nearest surface rounded down to a quarter of an octave. A caster that moves a
// little changes neither, so the lights keep their pages (docs/techniques.md, "Invalidation by
// what moved"); the same pose always gives the same levels, whatever the poses before it.
Bounds steadyBounds(const Bounds& scene);
float steadyNearestSurface(float distance);

// A light's levels, finest first (a point light's faces one after the other), their table
// entries from `tableOffset` on (advanced past them), fitted to steadyBounds(scene) and
// steadyNearestSurface. `camera`: the position a sun's clipmap centres on.
std::vector<VirtualLevel> virtualLevels(const Light& light, uint32_t lightIndex,
                                        const Bounds& scene, const glm::vec3& camera,
                                        const VirtualSettings& settings, const ViewFitting& fitting,
                                        uint32_t& tableOffset);

// The level's view-projection narrowed to its page `page` (the window's own page coordinates):
// what renders that page alone into a pageSize^2 viewport.
glm::mat4 pageViewProj(const VirtualLevel& level, glm::ivec2 page);

// What a light's pages hold depends on: its geometry, the virtual map's sizes and the casters'
// depth offsets. A change of any drops every page of the light.
uint64_t pageContentsKey(const Light& light, const std::vector<VirtualLevel>& levels,
                         const VirtualSettings& settings, glm::vec2 casterBias);

struct PageKey {
    uint32_t light = 0, face = 0, level = 0;
    glm::ivec2 page{0}; // absolute in the level's grid
    bool operator==(const PageKey&) const = default;
};

struct PageKeyHash {
    size_t operator()(const PageKey& k) const;
};

// The key of entry `entry` of a level's table.
PageKey pageKeyOf(const VirtualLevel& level, uint32_t entry);

// The level of `levels` that holds `key`'s light, face and level, if this frame has it.
const VirtualLevel* levelOf(const std::vector<VirtualLevel>& levels, const PageKey& key);
// The table entry (from the level's tableOffset) of absolute page `page`, if the level's window
// holds it: the inverse of pageKeyOf.
std::optional<uint32_t> entryOf(const VirtualLevel& level, glm::ivec2 page);

// The physical pool: which page holds which virtual page, least recently used first out.
class PageCache {
public:
    explicit PageCache(uint32_t capacity);

    // A light's contents key: when it differs from the last one given, its pages are dropped.
    // Returns how many were.
    uint32_t keyLight(uint32_t light, uint64_t contentsKey);
    // Drops every resident page for which `drop` holds; returns how many.
    uint32_t dropIf(const std::function<bool(const PageKey&)>& drop);
    // Marks stale every resident page for which `stale` holds: it keeps its place, and its static
    // layer (virtual.staticLayer: what the casters that never moved drew into it) when
    // `keepLayer`, but readers do not see it (pageTable) until an update renders it again.
    // Returns how many.
    uint32_t staleIf(const std::function<bool(const PageKey&)>& stale, bool keepLayer);

    struct Update {
        std::vector<std::pair<uint32_t, PageKey>> render; // physical page, what it must hold
        uint32_t requested = 0;                           // distinct pages asked for
        uint32_t cached = 0;                              // of them, resident already
        uint32_t evicted = 0; // resident pages given to others (least recently used first)
        uint32_t dropped = 0; // asked for but the pool was full: readers fall back coarser
        // render[i]'s static layer is held: a stale page only the moving casters redraw.
        std::vector<uint8_t> staticHeld;
    };
    // This frame's requests: the resident ones are kept (the stale ones rendered again in their
    // places), the others allocated (the coarsest levels first, so that a full pool keeps the
    // coarse pages every reader can fall back on), from free pages, then stale ones not asked for
    // (no reader sees them), then pages not requested this frame, least recently used first.
    Update update(std::vector<PageKey> requests, uint64_t frame);

    std::optional<uint32_t> physicalOf(const PageKey& key) const;
    uint32_t capacity() const { return static_cast<uint32_t>(mPages.size()); }
    uint32_t resident() const;
    // What physical page `physical` holds (nothing when free).
    std::optional<PageKey> keyOf(uint32_t physical) const;
    bool stale(uint32_t physical) const { return mPages.at(physical).stale; }

private:
    struct Physical {
        std::optional<PageKey> key;
        uint64_t lastUsed = 0;
        bool stale = false;      // to be rendered again before it is read
        bool staticHeld = false; // the static pool's page holds this key's static layer
    };
    std::vector<Physical> mPages;
    std::vector<std::pair<uint32_t, uint64_t>> mLightKeys;
    std::unordered_map<PageKey, uint32_t, PageKeyHash> mWhere;
};

// The page table of `levels`' entries: 1 + the physical page of each resident page that is not
// stale, else VIRTUAL_NOT_RESIDENT. `entries`: the table's size (the last level's end at least).
std::vector<uint32_t> pageTable(const std::vector<VirtualLevel>& levels, const PageCache& cache,
                                uint32_t entries);

// `requests` and, for each, the page that holds it in every coarser level of its light (and
// face), once each: the chain a reader falls back on when the pool cannot hold its own level's
// page (PageCache::update allocates the coarsest first). Pages outside a level's window are
// left out.
std::vector<PageKey> withCoarserPages(const std::vector<PageKey>& requests,
                                      const std::vector<VirtualLevel>& levels);

// The debug views' picture after an update: every level's pages and the pool's owners.
// `requested`: the update's requests (the coarser chains included); `rendered`: the physical
// pages it rendered.
VirtualPages virtualPages(const std::vector<VirtualLevel>& levels, const PageCache& cache,
                          const std::vector<PageKey>& requested,
                          const std::vector<uint32_t>& rendered, uint32_t poolPagesPerSide);

// The pages a request buffer (one word per table entry, non-zero: requested) asks for.
std::vector<PageKey> requestedPages(const std::vector<VirtualLevel>& levels,
                                    const uint32_t* requests);

} // namespace penumbra
