#include "core/moved_casters.h"

#include "penumbra/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
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

// A corner projected into a level's window, in pages (page i holds [i, i + 1)), with how far
// the GPU's projection of it may lie from there, a texel included.
struct Projected {
    bool behind = false; // before a perspective eye's plane: its projection is unbounded
    glm::dvec2 page{0.0}, slack{0.0};
};

class LevelProjection {
public:
    LevelProjection(const VirtualLevel& level, uint32_t pageSize)
        : mLevel(level), m(level.projection.viewProj), mPages(level.pagesPerSide),
          mTexel(1.0 / static_cast<double>(pageSize)) {
        for (int column = 0; column < 4; ++column)
            mMagnitude[column] = glm::abs(m[column]);
    }

    // Page i of the window holds NDC [2i/n - 1, 2(i+1)/n - 1] (pageViewProj): NDC x is page
    // (x + 1) n / 2. A texel is 1 / pageSize of a page: rasterization reaches a texel whose
    // centre the triangle covers, so a texel either side holds it.
    Projected operator()(const glm::dvec3& corner) const {
        const glm::dvec4 p(corner, 1.0);
        const glm::dvec4 clip = m * p;
        if (mLevel.projection.perspective && clip.w <= 0.0)
            return {.behind = true};
        const glm::dvec4 error = kRoundoff * (mMagnitude * glm::abs(p));
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        return {.page = (ndc + 1.0) * (0.5 * mPages),
                .slack = (glm::dvec2(error) + glm::abs(ndc) * error.w) / clip.w * (0.5 * mPages) +
                         mTexel};
    }

    // The level's page under window coordinate v (in pages), as far out as a grid can be.
    int page(double v) const { return static_cast<int>(std::floor(std::clamp(v, -kFar, kFar))); }
    // The window's page under v (in pages), not moved by firstPage.
    glm::ivec2 page(glm::dvec2 v) const { return {page(v.x), page(v.y)}; }
    const VirtualLevel& level() const { return mLevel; }

private:
    const VirtualLevel& mLevel;
    glm::dmat4 m, mMagnitude;
    double mPages, mTexel;
};

std::optional<PageRect> pagesUnder(const LevelProjection& project, const Bounds& box) {
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
        const Projected p =
            project(glm::dvec3((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                               (c & 4) ? box.max.z : box.min.z));
        if (p.behind) {
            ++behind;
            continue;
        }
        lo = glm::min(lo, p.page - p.slack);
        hi = glm::max(hi, p.page + p.slack);
    }
    if (behind == 8) // wholly behind the eye: it draws nothing into this view
        return std::nullopt;
    const bool finite =
        std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y);
    if (behind > 0 || !finite) // its projection is unbounded
        return PageRect{.wholeLevel = true};
    const glm::ivec2 first = project.level().firstPage;
    return PageRect{.lo = first + project.page(lo), .hi = first + project.page(hi)};
}

// The convex hull of a triangle's corner squares, counter-clockwise (Andrew's monotone chain).
using CornerSquares = std::array<glm::dvec2, 12>;
struct Hull {
    std::array<glm::dvec2, 2 * 12> points;
    size_t size = 0;
    std::span<const glm::dvec2> span() const { return {points.data(), size}; }
};
Hull hullOf(CornerSquares points) {
    std::sort(points.begin(), points.end(),
              [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    const auto turn = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    Hull out;
    auto& hull = out.points;
    size_t n = 0;
    for (size_t i = 0; i < points.size(); ++i) { // the lower chain
        while (n >= 2 && turn(hull[n - 2], hull[n - 1], points[i]) <= 0.0)
            --n;
        hull[n++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = n + 1; i-- > 0;) { // the upper chain
        while (n >= lower && turn(hull[n - 2], hull[n - 1], points[i]) <= 0.0)
            --n;
        hull[n++] = points[i];
    }
    out.size = n > 1 ? n - 1 : n; // the last point is the first
    return out;
}

// The x extent of convex polygon `p` between heights a and b (a <= b), if it reaches them: of
// its corners inside the band and its edges' crossings of the band's two lines (the extent of a
// convex polygon cut to a band lies at those points).
std::optional<glm::dvec2> xExtentInBand(std::span<const glm::dvec2> p, double a, double b) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    const auto take = [&](double x) { lo = std::min(lo, x), hi = std::max(hi, x); };
    for (size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2 u = p[i], v = p[(i + 1) % p.size()];
        if (u.y >= a && u.y <= b)
            take(u.x);
        for (const double h : {a, b})
            if ((u.y - h) * (v.y - h) < 0.0)
                take(u.x + (v.x - u.x) * ((h - u.y) / (v.y - u.y)));
    }
    if (lo > hi)
        return std::nullopt;
    return glm::dvec2(lo, hi);
}

// The pages triangle `t` (bounded by `box`) may draw into in `level`, each row's run of them.
// Its projection is the triangle of its corners' (all before a perspective eye); the GPU's may
// lie anywhere in the hull of a square round each corner, as wide as that corner's slack. Those
// runs are cut to the box's pages, which hold it too; a corner behind the eye leaves the box's.
void pagesUnder(const LevelProjection& project, const MovedTriangle& t, const Bounds& box,
                const PageRect& region, std::vector<PageRect>& out) {
    const VirtualLevel& level = project.level();
    const std::optional<PageRect> boxPages = pagesUnder(project, box);
    if (!boxPages)
        return;
    // Row by row only where the box is bounded and its rows are few: a box across a perspective
    // eye's plane (the whole level) or past 64 rows (a large caster in a fine level) keeps its
    // rectangle, one entry where its rows would be many for the device's decisions to test.
    constexpr int kMostRows = 64;
    if (boxPages->wholeLevel || int64_t(boxPages->hi.y) - boxPages->lo.y >= kMostRows) {
        out.push_back(*boxPages);
        return;
    }
    CornerSquares squares;
    size_t filled = 0;
    glm::dvec2 least(std::numeric_limits<double>::infinity()), most(-least);
    for (const glm::vec3& corner : t.corners) {
        const Projected p = project(glm::dvec3(corner));
        if (p.behind || !std::isfinite(p.page.x) || !std::isfinite(p.page.y) ||
            !std::isfinite(p.slack.x) || !std::isfinite(p.slack.y)) {
            out.push_back(*boxPages);
            return;
        }
        least = glm::min(least, p.page - p.slack);
        most = glm::max(most, p.page + p.slack);
        for (const glm::dvec2 side :
             {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)})
            squares[filled++] = p.page + side * p.slack;
    }
    // Rows and columns in the window's pages (the level's grid moved by firstPage), within the
    // box's and the corner squares' rectangles and the region that may hold pages.
    const glm::ivec2 squaresLo = project.page(least), squaresHi = project.page(most);
    glm::ivec2 lo = glm::max(boxPages->lo - level.firstPage, squaresLo);
    glm::ivec2 hi = glm::min(boxPages->hi - level.firstPage, squaresHi);
    if (!region.wholeLevel) {
        lo = glm::max(lo, region.lo - level.firstPage);
        hi = glm::min(hi, region.hi - level.firstPage);
    }
    if (lo.x > hi.x || lo.y > hi.y)
        return;
    if (squaresLo.x == squaresHi.x || squaresLo.y == squaresHi.y) { // one row or column: the
        out.push_back({.lo = level.firstPage + lo, .hi = level.firstPage + hi}); // rectangle's
        return;
    }
    const Hull hull = hullOf(squares);
    for (int row = lo.y; row <= hi.y; ++row) {
        const std::optional<glm::dvec2> x =
            xExtentInBand(hull.span(), double(row), double(row) + 1.0);
        if (!x)
            continue;
        const int first = std::max(project.page(x->x), lo.x),
                  end = std::min(project.page(x->y), hi.x);
        if (first <= end)
            out.push_back({.lo = level.firstPage + glm::ivec2(first, row),
                           .hi = level.firstPage + glm::ivec2(end, row)});
    }
}

// The pages of `rects` (one level's) in fewer rectangles, for the device's decisions, which test
// every resident page against every rectangle of its level: a whole level is all; small
// rectangles (neighbouring triangles share their pages) become their pages, then each row's
// runs of them, then runs of the same columns on consecutive rows one rectangle; large ones
// stay.
std::vector<PageRect> compacted(std::vector<PageRect> rects) {
    if (std::any_of(rects.begin(), rects.end(), [](const PageRect& r) { return r.wholeLevel; }))
        return {PageRect{.wholeLevel = true}};
    constexpr int64_t kSmall = 64;
    std::vector<glm::ivec2> pages; // (row, column), to sort by row
    std::vector<PageRect> out;
    for (const PageRect& r : rects) {
        if (int64_t(r.hi.x - r.lo.x + 1) * int64_t(r.hi.y - r.lo.y + 1) > kSmall) {
            out.push_back(r);
            continue;
        }
        for (int y = r.lo.y; y <= r.hi.y; ++y)
            for (int x = r.lo.x; x <= r.hi.x; ++x)
                pages.push_back({y, x});
    }
    const auto rowFirst = [](glm::ivec2 a, glm::ivec2 b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    };
    std::sort(pages.begin(), pages.end(), rowFirst);
    pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
    std::vector<PageRect> runs;
    for (size_t p = 0; p < pages.size();) {
        size_t q = p + 1;
        while (q < pages.size() && pages[q].x == pages[p].x && pages[q].y == pages[q - 1].y + 1)
            ++q;
        runs.push_back({.lo = {pages[p].y, pages[p].x}, .hi = {pages[q - 1].y, pages[p].x}});
        p = q;
    }
    // Runs of the same columns, row after row: one rectangle.
    std::sort(runs.begin(), runs.end(), [](const PageRect& a, const PageRect& b) {
        return std::tie(a.lo.x, a.hi.x, a.lo.y) < std::tie(b.lo.x, b.hi.x, b.lo.y);
    });
    for (const PageRect& r : runs) {
        PageRect* last = out.empty() ? nullptr : &out.back();
        if (last && last->lo.x == r.lo.x && last->hi.x == r.hi.x && last->hi.y + 1 == r.lo.y)
            last->hi.y = r.hi.y;
        else
            out.push_back(r);
    }
    return out;
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
    const auto cornersOf = [&](const Scene& s, size_t t) {
        return MovedTriangle{.corners = {corner(s, t, 0).position, corner(s, t, 1).position,
                                         corner(s, t, 2).position}};
    };
    for (size_t t = 0; t < std::max(was, is); ++t) {
        if (alike(t))
            continue;
        moved.indices.push_back(static_cast<uint32_t>(t));
        if (t < was) {
            moved.boxes.push_back(boundsOf(before, t));
            moved.triangles.push_back(cornersOf(before, t));
        }
        if (t < is) {
            const Bounds now = boundsOf(after, t);
            if (t >= was || now.min != moved.boxes.back().min ||
                now.max != moved.boxes.back().max) {
                moved.boxes.push_back(now);
                moved.triangles.push_back(cornersOf(after, t));
            }
        }
    }
    return moved;
}

void MovedCasters::append(const MovedCasters& more) {
    boxes.insert(boxes.end(), more.boxes.begin(), more.boxes.end());
    triangles.insert(triangles.end(), more.triangles.begin(), more.triangles.end());
    indices.insert(indices.end(), more.indices.begin(), more.indices.end());
}

std::vector<std::vector<PageRect>> movedPageRects(const std::vector<VirtualLevel>& levels,
                                                  std::span<const Bounds> moved, uint32_t pageSize,
                                                  std::span<const PageRect> held,
                                                  std::span<const MovedTriangle> triangles) {
    PENUMBRA_CHECK(triangles.empty() || triangles.size() == moved.size(),
                   "movedPageRects: a triangle for each box, or none");
    // Boxes in runs of kRun (a mesh's consecutive triangles lie close): a run's bounds that miss
    // the pages a level may hold spare projecting its boxes, and when they reach one page
    // alone, so does each box of the run (a box inside the run's bounds has its corners inside
    // them, and pages are monotone in them); wholly behind the eye, each box is. A walking figure's
    // thousands of triangles cost a few hundred projections a level.
    constexpr size_t kRun = 32;
    std::vector<std::vector<PageRect>> rects(levels.size());
    for (size_t i = 0; i < levels.size(); ++i) {
        const VirtualLevel& level = levels[i];
        const LevelProjection project(level, pageSize);
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
            const std::optional<PageRect> under = pagesUnder(project, all);
            const std::optional<PageRect> seen = under ? clipped(*under, region) : std::nullopt;
            if (!seen)
                continue;
            if (!under->wholeLevel && under->lo == under->hi) { // not seen's: a box may miss it
                rects[i].push_back(*seen);
                continue;
            }
            std::vector<PageRect> each;
            for (size_t b = first; b < first + run.size(); ++b)
                if (triangles.empty()) {
                    if (const std::optional<PageRect> r = pagesUnder(project, moved[b]))
                        each.push_back(*r);
                } else {
                    pagesUnder(project, triangles[b], moved[b], region, each);
                }
            for (const PageRect& r : each)
                if (const std::optional<PageRect> c = clipped(r, region))
                    rects[i].push_back(*c);
        }
        rects[i] = compacted(std::move(rects[i]));
    }
    return rects;
}

uint32_t dropMovedPages(PageCache& cache, const std::vector<VirtualLevel>& levels,
                        std::span<const Bounds> moved, uint32_t pageSize,
                        std::span<const MovedTriangle> triangles, MovedPage fate) {
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
    const std::vector<std::vector<PageRect>> rects =
        movedPageRects(levels, moved, pageSize, held, triangles);
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
    // A level this frame does not have: nothing says what its pages hold.
    uint32_t touched =
        cache.dropIf([&](const PageKey& k) { return levelOf(levels, k) == nullptr; });
    const auto isUnder = [&](const PageKey& k) {
        const Under& u = under[size_t(levelOf(levels, k) - levels.data())];
        return u.pages.contains(packed(k.page)) ||
               std::any_of(u.rects.begin(), u.rects.end(),
                           [&](const PageRect& r) { return r.holds(k.page); });
    };
    return touched + (fate == MovedPage::Dropped
                          ? cache.dropIf(isUnder)
                          : cache.staleIf(isUnder, fate == MovedPage::Stale));
}

} // namespace penumbra
