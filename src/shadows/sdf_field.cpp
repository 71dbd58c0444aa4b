#include "shadows/sdf_field.h"

#include "penumbra/error.h"
#include "sdf_math.h"
#include "shadows/sdf_cut.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <thread>

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

// Each brick's nearest triangle to its centre: exact where its list has one within a brick of the
// centre (the list holds every triangle that close), then carried to the other bricks by
// jump flooding over the bricks [Rong and Tan 2006]: steps n/2, ..., 1, then 1 again, each
// candidate measured exactly from the brick's centre.
std::vector<uint32_t> brickNearest(const FieldGeometry& g, const FieldLayout& layout,
                                   float thickness) {
    const glm::ivec3 bricks(layout.bricks());
    const size_t count = size_t(bricks.x) * size_t(bricks.y) * size_t(bricks.z);
    const float side = FIELD_BRICK * layout.voxel;
    auto index = [&](glm::ivec3 b) {
        return (size_t(b.z) * size_t(bricks.y) + size_t(b.y)) * size_t(bricks.x) + size_t(b.x);
    };
    auto distance = [&](uint32_t id, glm::vec3 p) {
        const gpu::FieldTriangle& t = g.triangles[id];
        return gpu::fieldTriangleDistance(p, glm::vec3(t.a), glm::vec3(t.b), glm::vec3(t.c),
                                          flagsOf(t), thickness);
    };
    std::vector<uint32_t> ids(count, FIELD_NO_TRIANGLE);
    std::vector<float> best(count, std::numeric_limits<float>::infinity());
    std::vector<uint8_t> exact(count, 0);
    // Every brick, its layers of z shared out among the CPU's threads (each writes its own).
    auto each = [&](auto&& f) {
        auto layers = [&](int first, int step) {
            for (int z = first; z < bricks.z; z += step)
                for (int y = 0; y < bricks.y; ++y)
                    for (int x = 0; x < bricks.x; ++x) {
                        const glm::ivec3 b(x, y, z);
                        f(b, index(b), layout.origin + (glm::vec3(b) + 0.5f) * side);
                    }
        };
        const int threads = static_cast<int>(
            std::clamp(std::thread::hardware_concurrency(), 1u, static_cast<unsigned>(bricks.z)));
        std::vector<std::jthread> workers;
        for (int t = 1; t < threads; ++t)
            workers.emplace_back(layers, t, threads);
        layers(0, threads);
    };
    each([&](glm::ivec3, size_t b, glm::vec3 centre) {
        for (uint32_t i = g.brickStarts[b]; i < g.brickStarts[b + 1]; ++i) {
            const float d = distance(g.brickList[i], centre);
            if (d < best[b]) {
                best[b] = d;
                ids[b] = g.brickList[i];
            }
        }
        exact[b] = best[b] <= side - thickness; // (a slab is at most its thickness nearer)
    });
    int step = 1;
    while (2 * step < std::max({bricks.x, bricks.y, bricks.z}))
        step *= 2;
    std::vector<int> steps;
    for (; step >= 1; step /= 2)
        steps.push_back(step);
    steps.push_back(1);
    std::vector<uint32_t> nextIds;
    std::vector<float> nextBest;
    for (const int s : steps) {
        nextIds = ids;
        nextBest = best;
        each([&](glm::ivec3 b, size_t i, glm::vec3 centre) {
            if (exact[i])
                return;
            uint32_t tried = ids[i];
            for (int dz = -s; dz <= s; dz += s)
                for (int dy = -s; dy <= s; dy += s)
                    for (int dx = -s; dx <= s; dx += s) {
                        const glm::ivec3 q = b + glm::ivec3(dx, dy, dz);
                        if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
                            glm::any(glm::greaterThanEqual(q, bricks)))
                            continue;
                        const uint32_t id = ids[index(q)];
                        if (id == FIELD_NO_TRIANGLE || id == tried)
                            continue;
                        tried = id;
                        const float d = distance(id, centre);
                        if (d < nextBest[i]) {
                            nextBest[i] = d;
                            nextIds[i] = id;
                        }
                    }
        });
        ids.swap(nextIds);
        best.swap(nextBest);
    }
    return ids;
}

// Per brick, the far voxels' candidates: the distinct nearest triangles of the brick and its 26
// neighbours, less those that cannot be nearest anywhere in the brick (measured from its centre,
// more than the brick's diagonal farther than the nearest of them: distances change by at most
// the distance moved). Packed: bricks + 1 offsets into the array, then the lists. A brick whose
// every voxel has its nearest triangle within a brick (sdf_seed's exact answer) lists none.
std::vector<uint32_t> farCandidates(const FieldGeometry& g, const FieldLayout& layout,
                                    float thickness) {
    const glm::ivec3 bricks(layout.bricks());
    const size_t count = g.brickNearest.size();
    const float side = FIELD_BRICK * layout.voxel;
    const float halfDiagonal = 0.5f * std::sqrt(3.0f) * side;
    std::vector<uint32_t> packed(count + 1, 0);
    std::vector<std::pair<float, uint32_t>> found;
    size_t b = 0;
    for (int z = 0; z < bricks.z; ++z)
        for (int y = 0; y < bricks.y; ++y)
            for (int x = 0; x < bricks.x; ++x, ++b) {
                packed[b] = static_cast<uint32_t>(packed.size());
                const glm::vec3 centre = layout.origin + (glm::vec3(x, y, z) + 0.5f) * side;
                found.clear();
                for (int dz = -1; dz <= 1; ++dz)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const glm::ivec3 q(x + dx, y + dy, z + dz);
                            if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
                                glm::any(glm::greaterThanEqual(q, bricks)))
                                continue;
                            const uint32_t id =
                                g.brickNearest[(size_t(q.z) * size_t(bricks.y) + size_t(q.y)) *
                                                   size_t(bricks.x) +
                                               size_t(q.x)];
                            if (id == FIELD_NO_TRIANGLE ||
                                std::any_of(found.begin(), found.end(),
                                            [&](const auto& f) { return f.second == id; }))
                                continue;
                            const gpu::FieldTriangle& t = g.triangles[id];
                            found.push_back(
                                {gpu::fieldTriangleDistance(centre, glm::vec3(t.a), glm::vec3(t.b),
                                                            glm::vec3(t.c), flagsOf(t), thickness),
                                 id});
                        }
                if (found.empty())
                    continue;
                std::sort(found.begin(), found.end());
                if (found[0].first + halfDiagonal <= side - thickness)
                    continue; // every voxel's seed is exact
                for (const auto& [d, id] : found)
                    if (d <= found[0].first + 2.0f * halfDiagonal)
                        packed.push_back(id);
            }
    packed[count] = static_cast<uint32_t>(packed.size());
    return packed;
}

} // namespace

uint32_t fieldResolution(const Bounds& bounds, uint32_t requested) {
    if (requested > 0 && requested < 16)
        throw InputError("sdf.resolution",
                         fmt::format("{} is too coarse: 0 (automatic) or 16 to 1024", requested));
    if (requested > 0 || bounds.empty())
        return requested > 0 ? requested : kAutoFieldResolutionMin;
    const glm::dvec3 extent = glm::dvec3(bounds.extent());
    const double longest = std::max({extent.x, extent.y, extent.z});
    if (!(longest > 0.0))
        return kAutoFieldResolutionMin;
    // Whole voxels per axis (at least one, as fieldLayout counts them), padding left out: the
    // budget is the scene's, not the margin's. Steps of 16 from the finest down.
    for (uint32_t n = kAutoFieldResolutionMax; n > kAutoFieldResolutionMin; n -= 16) {
        const double voxel = longest / n;
        double count = 1.0;
        for (int axis = 0; axis < 3; ++axis)
            count *= std::max(std::ceil(extent[axis] / voxel), 1.0);
        if (count <= static_cast<double>(kAutoFieldVoxels))
            return n;
    }
    return kAutoFieldResolutionMin;
}

FieldLayout fieldLayout(const Bounds& bounds, uint32_t requested) {
    PENUMBRA_CHECK(!bounds.empty(), "fieldLayout: empty bounds");
    const uint32_t resolution = fieldResolution(bounds, requested);
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

FieldGeometry fieldGeometry(const Scene& scene, const FieldLayout& layout, float thickness) {
    FieldGeometry g;
    g.sceneTriangles = static_cast<uint32_t>(scene.triangleCount());
    const Closure closure = closedSurfaces(scene);
    g.warnings = closure.shells;
    uint64_t budget = kMaxCutTriangles;
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const std::array<const Vertex*, 3> v{&scene.vertices[scene.indices[3 * t]],
                                             &scene.vertices[scene.indices[3 * t + 1]],
                                             &scene.vertices[scene.indices[3 * t + 2]]};
        const uint32_t material = v[0]->material;
        if (material < scene.materials.size() && scene.materials[material].alphaTested()) {
            ++g.alphaTriangles;
            const size_t before = g.triangles.size();
            cutByCoverage(scene, v, layout.voxel, budget, g.triangles);
            g.alphaPieces += static_cast<uint32_t>(g.triangles.size() - before);
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

    g.brickNearest = brickNearest(g, layout, thickness);
    g.farCandidates = farCandidates(g, layout, thickness);
    return g;
}

} // namespace penumbra::shadows
