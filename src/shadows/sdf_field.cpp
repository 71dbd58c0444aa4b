#include "shadows/sdf_field.h"

#include "penumbra/error.h"
#include "sdf_math.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

namespace penumbra::shadows {
namespace {

// The most triangles alpha-tested casters are cut into, and the most brick-list entries: past
// them the field would take more memory than any scene Penumbra renders needs.
constexpr uint64_t kMaxCutTriangles = uint64_t{1} << 23;
constexpr uint64_t kMaxBrickEntries = uint64_t{1} << 28;

float maxExtent(const Bounds& b) {
    const glm::vec3 e = b.extent();
    return std::max({e.x, e.y, e.z, 0.0f});
}

struct Welder {
    double step;
    std::unordered_map<uint64_t, std::vector<std::pair<std::array<int64_t, 3>, uint32_t>>> cells;
    uint32_t next = 0;
    uint32_t id(const glm::vec3& p) {
        const std::array<int64_t, 3> key{std::llround(p.x / step), std::llround(p.y / step),
                                         std::llround(p.z / step)};
        const uint64_t hash = static_cast<uint64_t>(key[0]) * 73856093u ^
                              static_cast<uint64_t>(key[1]) * 19349663u ^
                              static_cast<uint64_t>(key[2]) * 83492791u;
        auto& bucket = cells[hash];
        for (const auto& [k, i] : bucket)
            if (k == key)
                return i;
        bucket.push_back({key, next});
        return next++;
    }
};

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t i) {
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

gpu::FieldTriangle fieldTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t flags) {
    float f;
    std::memcpy(&f, &flags, sizeof f);
    return {glm::vec4(a, f), glm::vec4(b, 0.0f), glm::vec4(c, 0.0f)};
}

uint32_t flagsOf(const gpu::FieldTriangle& t) {
    uint32_t flags;
    std::memcpy(&flags, &t.a.w, sizeof flags);
    return flags;
}

// An alpha-tested triangle cut into n x n pieces of at most half a voxel, keeping those whose
// centre the material covers (the test the shadow pass and the ground truth make).
void cutByCoverage(const Scene& scene, const std::array<const Vertex*, 3>& v, float voxel,
                   uint64_t& budget, std::vector<gpu::FieldTriangle>& out) {
    const glm::vec3 a = v[0]->position, b = v[1]->position, c = v[2]->position;
    const float edge = std::max({glm::distance(a, b), glm::distance(b, c), glm::distance(c, a)});
    auto n = static_cast<uint32_t>(std::clamp(std::ceil(edge / (0.5f * voxel)), 1.0f, 64.0f));
    while (n > 1 && uint64_t{n} * n > budget)
        --n;
    auto at = [&](float s, float t) { return a + s * (b - a) + t * (c - a); };
    const float step = 1.0f / static_cast<float>(n);
    auto covered = [&](glm::vec2 st0, glm::vec2 st1, glm::vec2 st2) {
        const glm::vec2 st = (st0 + st1 + st2) / 3.0f;
        const float w0 = 1.0f - st.x - st.y;
        const glm::vec2 uv = w0 * v[0]->uv + st.x * v[1]->uv + st.y * v[2]->uv;
        const float alpha = w0 * v[0]->color.w + st.x * v[1]->color.w + st.y * v[2]->color.w;
        return scene.covers(v[0]->material, uv, alpha);
    };
    // Piece (i, j) "up": corners P(i, j), P(i + 1, j), P(i, j + 1); "down": P(i + 1, j),
    // P(i + 1, j + 1), P(i, j + 1), for i + j + 2 <= n. Pieces outside the triangle count as
    // covered: its own edges continue into its neighbours.
    auto up = [&](int i, int j) {
        if (i < 0 || j < 0 || i + j >= int(n))
            return true;
        const glm::vec2 p(float(i) * step, float(j) * step);
        return covered(p, p + glm::vec2(step, 0), p + glm::vec2(0, step));
    };
    auto down = [&](int i, int j) {
        if (i < 0 || j < 0 || i + j + 2 > int(n))
            return true;
        const glm::vec2 p(float(i) * step, float(j) * step);
        return covered(p + glm::vec2(step, 0), p + glm::vec2(step, step), p + glm::vec2(0, step));
    };
    auto emit = [&](glm::vec2 st0, glm::vec2 st1, glm::vec2 st2, bool ab, bool bc, bool ca) {
        const uint32_t flags = FIELD_OPEN | (ab ? 0u : FIELD_OUTLINE_AB) |
                               (bc ? 0u : FIELD_OUTLINE_BC) | (ca ? 0u : FIELD_OUTLINE_CA);
        out.push_back(fieldTriangle(at(st0.x, st0.y), at(st1.x, st1.y), at(st2.x, st2.y), flags));
    };
    for (int i = 0; i < int(n); ++i)
        for (int j = 0; i + j < int(n); ++j) {
            const glm::vec2 p(float(i) * step, float(j) * step);
            // Each edge's neighbour: up's are the downs below, left and across its diagonal.
            if (up(i, j))
                emit(p, p + glm::vec2(step, 0), p + glm::vec2(0, step), down(i, j - 1), down(i, j),
                     down(i - 1, j));
            if (i + j + 2 <= int(n) && down(i, j))
                emit(p + glm::vec2(step, 0), p + glm::vec2(step, step), p + glm::vec2(0, step),
                     up(i + 1, j), up(i, j + 1), up(i, j));
        }
    budget -= std::min<uint64_t>(budget, uint64_t{n} * n);
}

} // namespace

FieldLayout fieldLayout(const Bounds& bounds, uint32_t resolution) {
    PENUMBRA_CHECK(!bounds.empty() && resolution > 0, "fieldLayout: empty bounds");
    const float longest = maxExtent(bounds);
    FieldLayout layout;
    layout.voxel = longest > 0.0f ? longest / static_cast<float>(resolution) : 1.0f;
    const glm::vec3 extent = bounds.extent();
    for (int axis = 0; axis < 3; ++axis) {
        const double inner = std::ceil(static_cast<double>(extent[axis]) / layout.voxel);
        const double voxels = std::max(inner, 1.0) + 2.0 * kFieldPadding;
        const double bricks = std::ceil(voxels / FIELD_BRICK);
        layout.size[axis] = static_cast<uint32_t>(bricks) * FIELD_BRICK;
        // Centre the bounds in the box: the rounding's slack goes half to each side.
        layout.origin[axis] =
            bounds.min[axis] -
            0.5f * (static_cast<float>(layout.size[axis]) * layout.voxel - extent[axis]);
    }
    if (layout.voxels() > kMaxFieldVoxels)
        throw InputError("sdf.resolution",
                         fmt::format("{} voxels on the longest axis make a field of {}x{}x{} "
                                     "voxels, past the cap of {} (2^27); lower it",
                                     resolution, layout.size.x, layout.size.y, layout.size.z,
                                     kMaxFieldVoxels));
    return layout;
}

Closure closedSurfaces(const Scene& scene) {
    const size_t count = scene.triangleCount();
    Closure out{.closed = std::vector<bool>(count, false),
                .flipped = std::vector<bool>(count, false)};
    Welder welder{.step = std::max(1e-6 * maxExtent(scene.bounds()), 1e-12)};
    std::vector<std::array<uint32_t, 3>> welded(count);
    for (size_t t = 0; t < count; ++t)
        for (int k = 0; k < 3; ++k)
            welded[t][k] = welder.id(scene.vertices[scene.indices[3 * t + k]].position);
    std::vector<uint32_t> parent(welder.next);
    std::iota(parent.begin(), parent.end(), 0u);
    std::unordered_map<uint64_t, uint32_t> directedEdges;
    auto edgeKey = [](uint32_t u, uint32_t v) { return (uint64_t{u} << 32) | v; };
    for (const auto& w : welded) {
        parent[findRoot(parent, w[1])] = findRoot(parent, w[0]);
        parent[findRoot(parent, w[2])] = findRoot(parent, w[0]);
        for (int k = 0; k < 3; ++k)
            ++directedEdges[edgeKey(w[k], w[(k + 1) % 3])];
    }
    std::vector<bool> open(welder.next, false);
    std::vector<double> volume(welder.next, 0.0);
    for (size_t t = 0; t < count; ++t) {
        const auto& w = welded[t];
        const uint32_t root = findRoot(parent, w[0]);
        const Material* m =
            scene.materials.empty()
                ? nullptr
                : &scene.materials[std::min<size_t>(scene.vertices[scene.indices[3 * t]].material,
                                                    scene.materials.size() - 1)];
        if (m && m->alphaTested())
            open[root] = true;
        for (int k = 0; k < 3; ++k) {
            const uint32_t u = w[k], v = w[(k + 1) % 3];
            auto back = directedEdges.find(edgeKey(v, u));
            if (directedEdges[edgeKey(u, v)] != 1 || back == directedEdges.end() ||
                back->second != 1)
                open[root] = true;
        }
        const glm::dvec3 a(scene.vertices[scene.indices[3 * t]].position);
        const glm::dvec3 b(scene.vertices[scene.indices[3 * t + 1]].position);
        const glm::dvec3 c(scene.vertices[scene.indices[3 * t + 2]].position);
        volume[root] += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    for (size_t t = 0; t < count; ++t) {
        const uint32_t root = findRoot(parent, welded[t][0]);
        out.closed[t] = !open[root];
        out.flipped[t] = !open[root] && volume[root] < 0.0;
    }
    return out;
}

FieldGeometry fieldGeometry(const Scene& scene, const FieldLayout& layout) {
    FieldGeometry g;
    const Closure closure = closedSurfaces(scene);
    uint64_t budget = kMaxCutTriangles;
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const std::array<const Vertex*, 3> v{&scene.vertices[scene.indices[3 * t]],
                                             &scene.vertices[scene.indices[3 * t + 1]],
                                             &scene.vertices[scene.indices[3 * t + 2]]};
        const uint32_t material = v[0]->material;
        if (material < scene.materials.size() && scene.materials[material].alphaTested()) {
            ++g.alphaTriangles;
            cutByCoverage(scene, v, layout.voxel, budget, g.triangles);
            continue;
        }
        const uint32_t flags =
            closure.closed[t] ? (closure.flipped[t] ? FIELD_FLIPPED : 0u) : FIELD_OPEN;
        g.triangles.push_back(fieldTriangle(v[0]->position, v[1]->position, v[2]->position, flags));
    }
    for (const gpu::FieldTriangle& t : g.triangles)
        ++((flagsOf(t) & FIELD_OPEN) ? g.openTriangles : g.closedTriangles);

    // Brick lists: every triangle within `band` of a brick's box. The test is conservative: the
    // distance from the brick's centre within the band plus its half diagonal.
    const glm::uvec3 bricks = layout.bricks();
    const float brickSide = FIELD_BRICK * layout.voxel;
    const float band = brickSide;
    const float reach = band + 0.5f * std::sqrt(3.0f) * brickSide;
    const uint64_t brickCount = uint64_t{bricks.x} * bricks.y * bricks.z;
    std::vector<uint32_t> counts(brickCount + 1, 0);
    auto visit = [&](const gpu::FieldTriangle& t, auto&& onBrick) {
        const glm::vec3 a(t.a), b(t.b), c(t.c);
        const glm::vec3 lo = (glm::min(a, glm::min(b, c)) - band - layout.origin) / brickSide;
        const glm::vec3 hi = (glm::max(a, glm::max(b, c)) + band - layout.origin) / brickSide;
        glm::uvec3 first, last;
        for (int axis = 0; axis < 3; ++axis) {
            first[axis] = static_cast<uint32_t>(
                std::clamp(std::floor(lo[axis]), 0.0f, static_cast<float>(bricks[axis] - 1)));
            last[axis] = static_cast<uint32_t>(
                std::clamp(std::floor(hi[axis]), 0.0f, static_cast<float>(bricks[axis] - 1)));
        }
        for (uint32_t z = first.z; z <= last.z; ++z)
            for (uint32_t y = first.y; y <= last.y; ++y)
                for (uint32_t x = first.x; x <= last.x; ++x) {
                    const glm::vec3 centre =
                        layout.origin + (glm::vec3(x, y, z) + 0.5f) * brickSide;
                    if (glm::distance(centre, gpu::nearestOnTriangle(centre, a, b, c)) <= reach)
                        onBrick((uint64_t{z} * bricks.y + y) * bricks.x + x);
                }
    };
    uint64_t entries = 0;
    for (const gpu::FieldTriangle& t : g.triangles)
        visit(t, [&](uint64_t brick) {
            ++counts[brick];
            ++entries;
        });
    if (entries > kMaxBrickEntries)
        throw InputError("sdf.resolution",
                         fmt::format("the field's brick lists would hold {} entries, past the cap "
                                     "of {}; lower it",
                                     entries, kMaxBrickEntries));
    g.brickStarts.assign(brickCount + 1, 0);
    for (uint64_t b = 0; b < brickCount; ++b)
        g.brickStarts[b + 1] = g.brickStarts[b] + counts[b];
    g.brickList.resize(entries);
    std::vector<uint32_t> cursor(g.brickStarts.begin(), g.brickStarts.end() - 1);
    for (uint32_t i = 0; i < g.triangles.size(); ++i)
        visit(g.triangles[i], [&](uint64_t brick) { g.brickList[cursor[brick]++] = i; });

    // Breadth-first over the bricks from those with a list, to their 26 neighbours.
    std::vector<uint32_t> hops(brickCount, UINT32_MAX);
    std::vector<uint64_t> frontier;
    for (uint64_t b = 0; b < brickCount; ++b)
        if (counts[b] > 0) {
            hops[b] = 0;
            frontier.push_back(b);
        }
    uint32_t farthest = 0;
    while (!frontier.empty()) {
        std::vector<uint64_t> next;
        for (const uint64_t b : frontier) {
            const glm::ivec3 c(static_cast<int>(b % bricks.x),
                               static_cast<int>(b / bricks.x % bricks.y),
                               static_cast<int>(b / (uint64_t{bricks.x} * bricks.y)));
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const glm::ivec3 n = c + glm::ivec3(dx, dy, dz);
                        if (glm::any(glm::lessThan(n, glm::ivec3(0))) ||
                            glm::any(glm::greaterThanEqual(n, glm::ivec3(bricks))))
                            continue;
                        const uint64_t nb =
                            (uint64_t(n.z) * bricks.y + uint64_t(n.y)) * bricks.x + uint64_t(n.x);
                        if (hops[nb] != UINT32_MAX)
                            continue;
                        hops[nb] = hops[b] + 1;
                        farthest = std::max(farthest, hops[nb]);
                        next.push_back(nb);
                    }
        }
        frontier.swap(next);
    }
    g.seedGap = (farthest + 1) * FIELD_BRICK;
    return g;
}

} // namespace penumbra::shadows
