#include "core/moved_casters.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

namespace penumbra {
namespace {

// What the depth pass and its alpha test read of a vertex.
bool castsAlike(const Vertex& a, const Vertex& b) {
    return a.position == b.position && a.uv == b.uv && a.color.w == b.color.w &&
           a.material == b.material;
}

// How far the GPU's clip coordinates may be from these, in units of the sum of the products'
// magnitudes: a float dot product of four terms is within 5 u of it (u = 2^-24, Higham's bound
// (n + 1) u), the page's crop matrix times the level's within 2 u more, and 1 u for the float
// matrix's own entries.
constexpr double kRoundoff = 8.0 * 0x1p-24;
// Far past the window (a box beside a perspective eye), a page number no grid reaches.
constexpr double kFar = 1 << 30;

std::optional<PageRect> pagesUnder(const VirtualLevel& level, const Bounds& box,
                                   uint32_t pageSize) {
    const glm::dmat4 m(level.projection.viewProj);
    glm::dmat4 magnitude;
    for (int column = 0; column < 4; ++column)
        magnitude[column] = glm::abs(m[column]);
    const double pages = level.pagesPerSide;
    // Page i of the window holds NDC [2i/n - 1, 2(i+1)/n - 1] (pageViewProj): NDC x is page
    // (x + 1) n / 2. A texel is 1 / pageSize of a page: rasterization reaches a texel whose
    // centre the triangle covers, so a texel either side holds it.
    const double texel = 1.0 / static_cast<double>(pageSize);
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec4 p((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                           (c & 4) ? box.max.z : box.min.z, 1.0);
        const glm::dvec4 clip = m * p;
        if (level.projection.perspective && clip.w <= 0.0) {
            ++behind;
            continue;
        }
        const glm::dvec4 error = kRoundoff * (magnitude * glm::abs(p));
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        const glm::dvec2 slack =
            (glm::dvec2(error) + glm::abs(ndc) * error.w) / clip.w * (0.5 * pages) + texel;
        const glm::dvec2 page = (ndc + 1.0) * (0.5 * pages);
        lo = glm::min(lo, page - slack);
        hi = glm::max(hi, page + slack);
    }
    if (behind == 8) // wholly behind the eye: it draws nothing into this view
        return std::nullopt;
    const bool finite =
        std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y);
    if (behind > 0 || !finite) // its projection is unbounded
        return PageRect{.wholeLevel = true};
    auto page = [](double v) { return static_cast<int>(std::floor(std::clamp(v, -kFar, kFar))); };
    return PageRect{.lo = level.firstPage + glm::ivec2(page(lo.x), page(lo.y)),
                    .hi = level.firstPage + glm::ivec2(page(hi.x), page(hi.y))};
}

// The pages of `r` inside `region`, if any; a whole level stays whole.
std::optional<PageRect> clipped(const PageRect& r, const PageRect& region) {
    if (r.wholeLevel || region.wholeLevel)
        return r;
    const PageRect c{.lo = glm::max(r.lo, region.lo), .hi = glm::min(r.hi, region.hi)};
    if (c.lo.x > c.hi.x || c.lo.y > c.hi.y)
        return std::nullopt;
    return c;
}

} // namespace

MovedCasters movedCasters(const Scene& before, const Scene& after) {
    // Triangle t of one pose against triangle t of the other, corner by corner (the winding
    // kept): the same vertices under other indices are the same caster; a triangle past the
    // other pose's count was removed or added, and is bounded where it is.
    const size_t was = before.triangleCount(), is = after.triangleCount();
    const auto corner = [](const Scene& s, size_t t, int k) -> const Vertex& {
        return s.vertices[s.indices[3 * t + size_t(k)]];
    };
    // The common case, a pose of the same meshes: every vertex is compared once (a vertex is
    // shared by about six triangles), and a triangle moved if any of its corners did.
    const bool sameIndices =
        before.indices == after.indices && before.vertices.size() == after.vertices.size();
    std::vector<uint8_t> vertexMoved;
    if (sameIndices) {
        vertexMoved.resize(after.vertices.size());
        for (size_t v = 0; v < vertexMoved.size(); ++v)
            vertexMoved[v] = !castsAlike(before.vertices[v], after.vertices[v]);
    }
    const auto alike = [&](size_t t) {
        if (t >= was || t >= is)
            return false;
        for (int k = 0; k < 3; ++k) {
            const bool cornerAlike = sameIndices
                                         ? !vertexMoved[after.indices[3 * t + size_t(k)]]
                                         : castsAlike(corner(before, t, k), corner(after, t, k));
            if (!cornerAlike)
                return false;
        }
        return true;
    };
    // Each moved triangle where it was and where it is, apart: a page only the old pose drew into
    // loses it, one only the new pose draws into gains it, a page between them (the sweep) holds
    // neither. One box when the corners stayed (a texture coordinate, alpha or material moved).
    MovedCasters moved;
    const auto boundsOf = [&](const Scene& s, size_t t) {
        Bounds b;
        for (int k = 0; k < 3; ++k)
            b.grow(corner(s, t, k).position);
        return b;
    };
    for (size_t t = 0; t < std::max(was, is); ++t) {
        if (alike(t))
            continue;
        if (t < was)
            moved.boxes.push_back(boundsOf(before, t));
        if (t < is) {
            const Bounds now = boundsOf(after, t);
            if (t >= was || now.min != moved.boxes.back().min || now.max != moved.boxes.back().max)
                moved.boxes.push_back(now);
        }
    }
    return moved;
}

std::vector<std::vector<PageRect>> movedPageRects(const std::vector<VirtualLevel>& levels,
                                                  std::span<const Bounds> moved, uint32_t pageSize,
                                                  std::span<const PageRect> held) {
    // Boxes in runs of kRun (a mesh's consecutive triangles lie close): a run's bounds that miss
    // the pages a level may hold spare projecting its boxes, and when they reach one page
    // alone, so does each box of the run (a box inside the run's bounds has its corners inside
    // them, and pages are monotone in them); wholly behind the eye, each box is. A walking figure's
    // thousands of triangles cost a few hundred projections a level.
    constexpr size_t kRun = 32;
    std::vector<std::vector<PageRect>> rects(levels.size());
    for (size_t i = 0; i < levels.size(); ++i) {
        const VirtualLevel& level = levels[i];
        PageRect region{.wholeLevel = true};
        if (!level.followsCamera)
            region = {.lo = level.firstPage,
                      .hi = level.firstPage + glm::ivec2(int(level.pagesPerSide) - 1)};
        if (!held.empty()) {
            const std::optional<PageRect> c = clipped(held[i], region);
            if (!c)
                continue;
            region = *c;
        }
        for (size_t first = 0; first < moved.size(); first += kRun) {
            const std::span<const Bounds> run =
                moved.subspan(first, std::min(kRun, moved.size() - first));
            Bounds all;
            for (const Bounds& box : run) {
                all.grow(box.min);
                all.grow(box.max);
            }
            const std::optional<PageRect> under = pagesUnder(level, all, pageSize);
            const std::optional<PageRect> seen = under ? clipped(*under, region) : std::nullopt;
            if (!seen)
                continue;
            if (!under->wholeLevel && under->lo == under->hi) { // not seen's: a box may miss it
                rects[i].push_back(*seen);
                continue;
            }
            for (const Bounds& box : run)
                if (const std::optional<PageRect> r = pagesUnder(level, box, pageSize))
                    if (const std::optional<PageRect> c = clipped(*r, region))
                        rects[i].push_back(*c);
        }
    }
    return rects;
}

uint32_t dropMovedPages(PageCache& cache, const std::vector<VirtualLevel>& levels,
                        std::span<const Bounds> moved, uint32_t pageSize) {
    if (moved.empty())
        return 0;
    // Per level, the pages under the boxes: small rectangles' pages in a set (a skinned figure
    // moves thousands of triangles, each under a page or two), larger ones kept as rectangles.
    constexpr int64_t kListedPages = 64;
    struct Under {
        std::unordered_set<uint64_t> pages;
        std::vector<PageRect> rects;
    };
    const auto packed = [](glm::ivec2 p) {
        return (uint64_t(uint32_t(p.x)) << 32) | uint64_t(uint32_t(p.y));
    };
    // Per level, the bounds of its resident pages: boxes elsewhere need not be projected.
    std::vector<PageRect> held(levels.size());
    for (uint32_t physical = 0; physical < cache.capacity(); ++physical) {
        const std::optional<PageKey> key = cache.keyOf(physical);
        const VirtualLevel* level = key ? levelOf(levels, *key) : nullptr;
        if (!level)
            continue;
        PageRect& h = held[size_t(level - levels.data())];
        const bool first = h.lo.x > h.hi.x;
        h.lo = first ? key->page : glm::min(h.lo, key->page);
        h.hi = first ? key->page : glm::max(h.hi, key->page);
    }
    std::vector<Under> under(levels.size());
    const std::vector<std::vector<PageRect>> rects = movedPageRects(levels, moved, pageSize, held);
    for (size_t i = 0; i < levels.size(); ++i)
        for (const PageRect& r : rects[i]) {
            const int64_t area = int64_t(r.hi.x - r.lo.x + 1) * int64_t(r.hi.y - r.lo.y + 1);
            if (r.wholeLevel || area > kListedPages) {
                under[i].rects.push_back(r);
                continue;
            }
            for (int y = r.lo.y; y <= r.hi.y; ++y)
                for (int x = r.lo.x; x <= r.hi.x; ++x)
                    under[i].pages.insert(packed({x, y}));
        }
    return cache.dropIf([&](const PageKey& k) {
        const VirtualLevel* level = levelOf(levels, k);
        if (!level)
            return true; // a level this frame does not have: nothing says what it holds
        const Under& u = under[size_t(level - levels.data())];
        return u.pages.contains(packed(k.page)) ||
               std::any_of(u.rects.begin(), u.rects.end(),
                           [&](const PageRect& r) { return r.holds(k.page); });
    });
}

} // namespace penumbra
