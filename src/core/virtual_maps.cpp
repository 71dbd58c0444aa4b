#include "core/virtual_maps.h"

#include "core/fnv1a.h"
#include "core/projection.h"
#include "penumbra/error.h"
#include "virtual_pages.h" // shaders/include: the shared lookup

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <unordered_set>

namespace penumbra {
namespace {

uint64_t mix(uint64_t h, uint64_t v) {
    return fnv1a(&v, sizeof v, h);
}
uint64_t mixFloats(uint64_t h, const float* v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        h = mix(h, std::bit_cast<uint32_t>(v[i]));
    return h;
}

// A sun's clipmap: the orientation and depth range of the map over the whole scene, and levels
// whose extents double up to one that holds the scene with two pages to spare on each side (the
// snap to whole pages moves a window by less than one), then on to one page over it.
std::vector<VirtualLevel> clipmapLevels(const Light& light, uint32_t lightIndex,
                                        const Bounds& scene, const glm::vec3& camera,
                                        const VirtualSettings& s, uint32_t& tableOffset) {
    const LightProjection whole = fitDirectional(light, scene, s.size);
    const uint32_t n = s.pagesPerSide();
    const glm::vec4 w = whole.window;
    const float top = std::max(w.y - w.x, w.w - w.z) * (1.0f + 4.0f / static_cast<float>(n));
    const glm::vec2 eye = glm::vec2(whole.view * glm::vec4(camera, 1.0f));
    std::vector<VirtualLevel> levels;
    for (uint32_t l = 0; l < s.levels; ++l) {
        const float extent = std::ldexp(top, static_cast<int>(l) - static_cast<int>(s.levels - 1));
        const float pageWorld = extent / static_cast<float>(n);
        // Centred on the camera, but kept over the scene (a camera outside it still sees it).
        glm::vec2 centre;
        for (int a = 0; a < 2; ++a) {
            const float lo = w[2 * a] + 0.5f * extent, hi = w[2 * a + 1] - 0.5f * extent;
            centre[a] = lo > hi ? 0.5f * (w[2 * a] + w[2 * a + 1]) : std::clamp(eye[a], lo, hi);
        }
        const glm::ivec2 first =
            glm::ivec2(glm::floor(centre / pageWorld)) - glm::ivec2(static_cast<int>(n / 2));
        VirtualLevel v{.light = lightIndex, .level = l, .projection = whole};
        LightProjection& p = v.projection;
        p.window = {static_cast<float>(first.x) * pageWorld,
                    static_cast<float>(first.x + static_cast<int>(n)) * pageWorld,
                    static_cast<float>(first.y) * pageWorld,
                    static_cast<float>(first.y + static_cast<int>(n)) * pageWorld};
        p.projection =
            orthographic(p.window.x, p.window.y, p.window.z, p.window.w, p.nearPlane, p.farPlane);
        p.viewProj = p.projection * p.view;
        p.texelWorldSize = pageWorld / static_cast<float>(s.pageSize);
        p.name = "level";
        v.firstPage = first;
        v.followsCamera = true;
        v.pagesPerSide = n;
        v.tableOffset = tableOffset;
        tableOffset += v.tableEntries();
        levels.push_back(v);
    }
    // Above the scene's level, its mips: the same window (fixed: it holds the whole scene), half
    // the pages a side each, down to one.
    for (uint32_t k = 1; k < s.localLevels(); ++k) {
        VirtualLevel v = levels[s.levels - 1];
        v.level = s.levels - 1 + k;
        v.followsCamera = false;
        v.projection.texelWorldSize = std::ldexp(v.projection.texelWorldSize, static_cast<int>(k));
        v.firstPage = glm::ivec2(0);
        v.pagesPerSide = n >> k;
        v.tableOffset = tableOffset;
        tableOffset += v.tableEntries();
        levels.push_back(v);
    }
    return levels;
}

} // namespace

Bounds steadyBounds(const Bounds& scene) {
    const glm::vec3 e = scene.extent();
    const float largest = std::max({e.x, e.y, e.z, 1e-6f});
    const float grid = std::exp2(std::ceil(std::log2(largest / 64.0f)));
    return {.min = glm::floor(scene.min / grid) * grid, .max = glm::ceil(scene.max / grid) * grid};
}

float steadyNearestSurface(float distance) {
    if (!std::isfinite(distance) || distance <= 0.0f)
        return distance;
    return std::exp2(std::floor(4.0f * std::log2(distance)) / 4.0f);
}

VirtualSettings VirtualSettings::of(const ParameterValues& p) {
    return {.enabled = p.number("virtual.enabled") != 0.0,
            .size = static_cast<uint32_t>(p.number("virtual.size")),
            .pageSize = static_cast<uint32_t>(p.number("virtual.pageSize")),
            .levels = static_cast<uint32_t>(p.number("virtual.levels")),
            .poolSize = static_cast<uint32_t>(p.number("virtual.poolSize")),
            .lodBias = static_cast<float>(p.number("virtual.lodBias")),
            .lodFromImage = p.number("virtual.lodFromImage") != 0.0,
            .deviceDecides = p.number("virtual.deviceDecides") != 0.0,
            // The device's decisions draw every caster into the pages they render.
            .staticLayer =
                p.number("virtual.staticLayer") != 0.0 && p.number("virtual.deviceDecides") == 0.0};
}

float VirtualSettings::levelBias(uint32_t width, uint32_t height) const {
    if (!lodFromImage || width == 0 || height == 0)
        return lodBias;
    constexpr double kReferencePixels = 1920.0 * 1080.0;
    // Two levels finer at most (a 480x270 image), one coarser (3840x2160).
    constexpr double kFinest = -2.0, kCoarsest = 1.0;
    const double pixels = double(width) * double(height);
    const double image = std::clamp(0.5 * std::log2(pixels / kReferencePixels), kFinest, kCoarsest);
    return static_cast<float>(lodBias + image);
}

uint32_t VirtualSettings::localLevels() const {
    return static_cast<uint32_t>(std::countr_zero(pagesPerSide())) + 1;
}

uint32_t virtualViewCount(const Light& light, const VirtualSettings& s) {
    if (!castsShadowMap(light))
        return 0;
    if (light.type == LightType::Directional)
        return s.sunLevels();
    return (light.type == LightType::Point ? kCubeFaces : 1u) * s.localLevels();
}

uint64_t virtualTableEntries(const Light& light, const VirtualSettings& s) {
    if (!castsShadowMap(light))
        return 0;
    const uint64_t n = s.pagesPerSide();
    uint64_t mips = 0;
    for (uint32_t l = 0; l < s.localLevels(); ++l)
        mips += (n >> l) * (n >> l);
    if (light.type == LightType::Directional)
        return uint64_t{s.levels - 1} * n * n + mips;
    return (light.type == LightType::Point ? kCubeFaces : 1u) * mips;
}

std::vector<VirtualLevel> virtualLevels(const Light& light, uint32_t lightIndex,
                                        const Bounds& scene, const glm::vec3& camera,
                                        const VirtualSettings& s, const ViewFitting& fitting,
                                        uint32_t& tableOffset) {
    PENUMBRA_CHECK(std::has_single_bit(s.size) && std::has_single_bit(s.pageSize) &&
                       s.pageSize <= s.size && s.levels >= 1 && s.levels <= VIRTUAL_MAX_LEVELS,
                   "virtual map sizes not checked");
    const Bounds steady = steadyBounds(scene);
    if (light.type == LightType::Directional)
        return clipmapLevels(light, lightIndex, steady, camera, s, tableOffset);
    ViewFitting local = fitting;
    local.camera = nullptr; // no cascades: one frustum, or six faces
    local.nearestSurface = steadyNearestSurface(fitting.nearestSurface);
    const std::vector<LightProjection> faces = fitLightViews(light, steady, s.size, local);
    std::vector<VirtualLevel> levels;
    for (uint32_t f = 0; f < faces.size(); ++f)
        for (uint32_t l = 0; l < s.localLevels(); ++l) {
            VirtualLevel v{.light = lightIndex, .face = f, .level = l, .projection = faces[f]};
            v.projection.texelWorldSize = std::ldexp(faces[f].texelWorldSize, static_cast<int>(l));
            v.pagesPerSide = s.pagesPerSide() >> l;
            v.tableOffset = tableOffset;
            tableOffset += v.tableEntries();
            levels.push_back(v);
        }
    return levels;
}

glm::mat4 pageViewProj(const VirtualLevel& level, glm::ivec2 page) {
    // NDC x in [2i/n - 1, 2(i+1)/n - 1] -> [-1, 1]: x' = n x - (2i + 1 - n); y alike.
    const auto n = static_cast<float>(level.pagesPerSide);
    glm::mat4 crop(1.0f);
    crop[0][0] = n;
    crop[1][1] = n;
    crop[3][0] = -(2.0f * static_cast<float>(page.x) + 1.0f - n);
    crop[3][1] = -(2.0f * static_cast<float>(page.y) + 1.0f - n);
    return crop * level.projection.viewProj;
}

uint64_t pageContentsKey(const Light& light, const std::vector<VirtualLevel>& levels,
                         const VirtualSettings& s, glm::vec2 casterBias) {
    uint64_t h = kFnv1aOffset;
    h = mix(h, static_cast<uint64_t>(light.type));
    h = mix(h, (uint64_t{s.size} << 32) | s.pageSize);
    h = mix(h, s.levels);
    h = mixFloats(h, &casterBias.x, 2);
    // A level's orientation, depth range and scale: what a page's texels mean (a sun's windows
    // move over the same grid; their origin is not part of it).
    for (const VirtualLevel& v : levels) {
        const glm::mat4& view = v.projection.view;
        h = mixFloats(h, &view[0][0], 16);
        const float depth[3] = {v.projection.nearPlane, v.projection.farPlane,
                                v.projection.texelWorldSize};
        h = mixFloats(h, depth, 3);
        if (v.projection.perspective)
            h = mixFloats(h, &v.projection.projection[0][0], 16);
    }
    return h;
}

PageKey pageKeyOf(const VirtualLevel& level, uint32_t entry) {
    const uint32_t local = entry - level.tableOffset;
    const glm::ivec2 page(static_cast<int>(local % level.pagesPerSide),
                          static_cast<int>(local / level.pagesPerSide));
    return {.light = level.light,
            .face = level.face,
            .level = level.level,
            .page = level.firstPage + page};
}

const VirtualLevel* levelOf(const std::vector<VirtualLevel>& levels, const PageKey& key) {
    for (const VirtualLevel& level : levels) // a frame has tens of levels: a short search
        if (level.light == key.light && level.face == key.face && level.level == key.level)
            return &level;
    return nullptr;
}

std::optional<uint32_t> entryOf(const VirtualLevel& level, glm::ivec2 page) {
    const glm::ivec2 local = page - level.firstPage;
    const auto n = static_cast<int>(level.pagesPerSide);
    if (local.x < 0 || local.y < 0 || local.x >= n || local.y >= n)
        return std::nullopt;
    return gpu::virtualEntryIndex(level.tableOffset, level.pagesPerSide, local);
}

size_t PageKeyHash::operator()(const PageKey& k) const {
    uint64_t h = kFnv1aOffset;
    h = mix(h, (uint64_t{k.light} << 32) | (k.face << 8) | k.level);
    h = mix(h, (uint64_t{std::bit_cast<uint32_t>(k.page.x)} << 32) |
                   std::bit_cast<uint32_t>(k.page.y));
    return static_cast<size_t>(h);
}

PageCache::PageCache(uint32_t capacity) : mPages(capacity) {}

uint32_t PageCache::keyLight(uint32_t light, uint64_t contentsKey) {
    auto it = std::find_if(mLightKeys.begin(), mLightKeys.end(),
                           [&](const auto& k) { return k.first == light; });
    if (it == mLightKeys.end()) {
        mLightKeys.emplace_back(light, contentsKey);
        return 0;
    }
    if (it->second == contentsKey)
        return 0;
    it->second = contentsKey;
    return dropIf([light](const PageKey& k) { return k.light == light; });
}

uint32_t PageCache::dropIf(const std::function<bool(const PageKey&)>& drop) {
    uint32_t dropped = 0;
    for (Physical& p : mPages)
        if (p.key && drop(*p.key)) {
            mWhere.erase(*p.key);
            p = {.lastUsed = p.lastUsed}; // free pages are taken least recently used first
            ++dropped;
        }
    return dropped;
}

uint32_t PageCache::staleIf(const std::function<bool(const PageKey&)>& stale, bool keepLayer) {
    uint32_t marked = 0;
    for (Physical& p : mPages)
        if (p.key && stale(*p.key)) {
            p.stale = true;
            p.staticHeld = p.staticHeld && keepLayer;
            ++marked;
        }
    return marked;
}

PageCache::Update PageCache::update(std::vector<PageKey> requests, uint64_t frame) {
    Update u;
    // Coarsest first; then a fixed order, so that a full pool always keeps the same pages.
    std::sort(requests.begin(), requests.end(), [](const PageKey& a, const PageKey& b) {
        if (a.level != b.level)
            return a.level > b.level;
        return std::tie(a.light, a.face, a.page.y, a.page.x) <
               std::tie(b.light, b.face, b.page.y, b.page.x);
    });
    requests.erase(std::unique(requests.begin(), requests.end()), requests.end());
    u.requested = static_cast<uint32_t>(requests.size());
    std::vector<PageKey> missing;
    for (const PageKey& key : requests) {
        auto it = mWhere.find(key);
        if (it == mWhere.end()) {
            missing.push_back(key);
            continue;
        }
        Physical& p = mPages[it->second];
        p.lastUsed = frame;
        if (!p.stale) {
            ++u.cached;
            continue;
        }
        // Rendered again in its place: the moving casters over its static layer, if it holds one.
        u.render.emplace_back(it->second, key);
        u.staticHeld.push_back(p.staticHeld);
        p.stale = false;
        p.staticHeld = true; // its render draws the layer if it lacked one
    }
    // Free pages first (a stale page not asked for is as good as free: no reader sees it), then
    // the least recently used of those not requested this frame.
    std::vector<uint32_t> candidates;
    for (uint32_t i = 0; i < mPages.size(); ++i)
        if (!mPages[i].key || mPages[i].lastUsed < frame)
            candidates.push_back(i);
    const auto isFree = [&](uint32_t i) { return !mPages[i].key || mPages[i].stale; };
    std::stable_sort(candidates.begin(), candidates.end(), [&](uint32_t a, uint32_t b) {
        const bool freeA = isFree(a), freeB = isFree(b);
        if (freeA != freeB)
            return freeA;
        return mPages[a].lastUsed < mPages[b].lastUsed;
    });
    size_t next = 0;
    for (const PageKey& key : missing) {
        if (next == candidates.size()) {
            ++u.dropped;
            continue;
        }
        Physical& p = mPages[candidates[next]];
        if (p.key) {
            mWhere.erase(*p.key);
            u.evicted += !p.stale;
        }
        p = {.key = key, .lastUsed = frame, .staticHeld = true}; // its render draws the layer
        mWhere[key] = candidates[next];
        u.render.emplace_back(candidates[next], key);
        u.staticHeld.push_back(0);
        ++next;
    }
    return u;
}

std::optional<uint32_t> PageCache::physicalOf(const PageKey& key) const {
    auto it = mWhere.find(key);
    return it == mWhere.end() ? std::nullopt : std::optional<uint32_t>(it->second);
}

std::optional<PageKey> PageCache::keyOf(uint32_t physical) const {
    return mPages.at(physical).key;
}

uint32_t PageCache::resident() const {
    return static_cast<uint32_t>(mWhere.size());
}

std::vector<uint32_t> pageTable(const std::vector<VirtualLevel>& levels, const PageCache& cache,
                                uint32_t entries) {
    // From the resident pages (a few thousand), not from every entry (hundreds of thousands).
    std::vector<uint32_t> table(entries, VIRTUAL_NOT_RESIDENT);
    for (uint32_t physical = 0; physical < cache.capacity(); ++physical) {
        const std::optional<PageKey> key = cache.keyOf(physical);
        const VirtualLevel* level = key && !cache.stale(physical) ? levelOf(levels, *key) : nullptr;
        if (const std::optional<uint32_t> e = level ? entryOf(*level, key->page) : std::nullopt)
            table.at(*e) = physical + 1u;
    }
    return table;
}

std::vector<PageKey> withCoarserPages(const std::vector<PageKey>& requests,
                                      const std::vector<VirtualLevel>& levels) {
    auto floorHalf = [](glm::ivec2 p) { return glm::ivec2(p.x >> 1, p.y >> 1); }; // floor(p / 2)
    std::vector<PageKey> out = requests;
    std::unordered_map<PageKey, bool, PageKeyHash> seen;
    for (const PageKey& k : requests)
        seen[k] = true;
    for (const PageKey& request : requests) {
        PageKey k = request;
        const VirtualLevel* child = levelOf(levels, k);
        while (child) {
            const VirtualLevel* parent =
                levelOf(levels, {.light = k.light, .face = k.face, .level = k.level + 1});
            if (!parent)
                break;
            // A clipmap's grids share their origin: page p's parent is p / 2; a fixed window's
            // pages count from its corner, which the scene level's window shares with its mips.
            k.page =
                parent->followsCamera ? floorHalf(k.page) : floorHalf(k.page - child->firstPage);
            k.level = parent->level;
            if (!entryOf(*parent, k.page))
                break;
            if (seen.emplace(k, true).second)
                out.push_back(k);
            child = parent;
        }
    }
    return out;
}

VirtualPages virtualPages(const std::vector<VirtualLevel>& levels, const PageCache& cache,
                          const std::vector<PageKey>& requested,
                          const std::vector<uint32_t>& rendered, uint32_t poolPagesPerSide) {
    VirtualPages out{.poolOwner = std::vector<int32_t>(cache.capacity(), -1),
                     .poolRendered = std::vector<uint8_t>(cache.capacity(), 0),
                     .poolPagesPerSide = poolPagesPerSide};
    for (const VirtualLevel& level : levels)
        out.levels.push_back({.light = level.light,
                              .face = level.face,
                              .level = level.level,
                              .pagesPerSide = level.pagesPerSide,
                              .pages = std::vector<PageState>(level.tableEntries())});
    // The level a key belongs to and its entry there, if this frame's window shows it.
    auto place = [&](const PageKey& key) -> std::optional<std::pair<size_t, uint32_t>> {
        const VirtualLevel* level = levelOf(levels, key);
        const std::optional<uint32_t> e = level ? entryOf(*level, key.page) : std::nullopt;
        if (!e)
            return std::nullopt;
        return std::pair{size_t(level - levels.data()), *e - level->tableOffset};
    };
    std::unordered_set<PageKey, PageKeyHash> asked(requested.begin(), requested.end());
    for (const PageKey& key : asked) // resident ones are overwritten below
        if (const auto at = place(key))
            out.levels[at->first].pages[at->second] = PageState::Dropped;
    for (uint32_t physical : rendered)
        out.poolRendered.at(physical) = 1;
    for (uint32_t physical = 0; physical < cache.capacity(); ++physical) {
        const std::optional<PageKey> key = cache.keyOf(physical);
        if (!key)
            continue;
        const auto at = place(*key);
        out.poolOwner[physical] = at ? static_cast<int32_t>(at->first) : -2;
        if (!at)
            continue;
        PageState& state = out.levels[at->first].pages[at->second];
        if (out.poolRendered[physical])
            state = PageState::Rendered;
        else
            state = asked.count(*key) ? PageState::Cached : PageState::Kept;
    }
    return out;
}

std::vector<PageKey> requestedPages(const std::vector<VirtualLevel>& levels,
                                    const uint32_t* requests) {
    std::vector<PageKey> out;
    for (const VirtualLevel& level : levels)
        for (uint32_t e = level.tableOffset; e < level.tableOffset + level.tableEntries(); ++e)
            if (requests[e] != 0u)
                out.push_back(pageKeyOf(level, e));
    return out;
}

} // namespace penumbra
