#include "shadows/sdf_field.h"

#include "sdf_math.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>

namespace penumbra::shadows {
namespace {

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

struct Shell {
    uint32_t root;
    std::string warning;
};

// The closed surfaces that hold a light or a camera inside them: a room drawn as one closed box,
// a sky box, a building's closed envelope seen from inside. Signed as a solid, every receiver the
// camera sees or the light reaches in there would read as inside it and shadow itself. They are
// taken as shells, open geometry. (A closed surface around other geometry alone stays a solid: a
// tower's envelope around its floors, seen and lit from outside, shadows as a whole.) A point
// decides only when it is clear of the surface by a millionth of the scene's size.
std::vector<Shell> holdingShells(const Scene& scene, const std::vector<uint32_t>& rootOf,
                                 const std::vector<bool>& open, const std::vector<double>& volume) {
    const size_t count = rootOf.size();
    auto corner = [&](size_t t, int k) {
        return scene.vertices[scene.indices[3 * t + k]].position;
    };
    std::unordered_map<uint32_t, std::vector<uint32_t>> closedTriangles; // per closed root
    std::unordered_map<uint32_t, Bounds> bounds;
    for (size_t t = 0; t < count; ++t) {
        const uint32_t r = rootOf[t];
        if (open[r])
            continue;
        closedTriangles[r].push_back(static_cast<uint32_t>(t));
        for (int k = 0; k < 3; ++k)
            bounds[r].grow(corner(t, k));
    }
    struct Probe {
        glm::vec3 p;
        std::string what;
    };
    std::vector<Probe> probes;
    for (const Light& light : scene.lights)
        if (light.type != LightType::Directional)
            probes.push_back({light.position, fmt::format("light '{}'", light.name)});
    for (const Camera& camera : scene.cameras)
        probes.push_back({camera.position, fmt::format("camera '{}'", camera.name)});
    const float clear = static_cast<float>(std::max(1e-6 * maxExtent(scene.bounds()), 1e-12));
    std::vector<Shell> shells;
    for (const auto& [r, triangles] : closedTriangles) {
        const Bounds& b = bounds[r];
        for (const Probe& probe : probes) {
            if (glm::any(glm::lessThan(probe.p, b.min)) ||
                glm::any(glm::greaterThan(probe.p, b.max)))
                continue;
            // The winding along the column from below (sdf_resolve's rule), and the distance.
            int winding = 0;
            float nearest = std::numeric_limits<float>::infinity();
            for (const uint32_t t : triangles) {
                const glm::vec3 a = corner(t, 0), bb = corner(t, 1), c = corner(t, 2);
                nearest = std::min(
                    nearest, glm::distance(probe.p, gpu::nearestOnTriangle(probe.p, a, bb, c)));
                float z = 0.0f;
                const int crossing = gpu::columnCrossing(glm::vec2(probe.p), a, bb, c, z);
                if (crossing != 0 && z < probe.p.z)
                    winding += crossing;
            }
            if (volume[r] < 0.0)
                winding = -winding;
            if (winding <= 0 || nearest <= clear)
                continue;
            const uint32_t material = scene.vertices[scene.indices[3 * triangles[0]]].material;
            const std::string name =
                material < scene.materials.size()
                    ? fmt::format("material '{}'", scene.materials[material].name)
                    : std::string("no material");
            shells.push_back(
                {r, fmt::format("sdf: a closed surface of {} triangles ({}) holds {} inside it: "
                                "taken as a thin shell, not a solid",
                                triangles.size(), name, probe.what)});
            break;
        }
    }
    std::sort(shells.begin(), shells.end(),
              [](const Shell& x, const Shell& y) { return x.root < y.root; });
    return shells;
}

} // namespace

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
    std::vector<bool> open(welder.next, false), edgeOpen(welder.next, false), alpha(count);
    std::vector<double> volume(welder.next, 0.0);
    for (size_t t = 0; t < count; ++t) {
        const auto& w = welded[t];
        const uint32_t root = findRoot(parent, w[0]);
        const Material* m =
            scene.materials.empty()
                ? nullptr
                : &scene.materials[std::min<size_t>(scene.vertices[scene.indices[3 * t]].material,
                                                    scene.materials.size() - 1)];
        alpha[t] = m && m->alphaTested();
        if (alpha[t])
            open[root] = true;
        for (int k = 0; k < 3; ++k) {
            const uint32_t u = w[k], v = w[(k + 1) % 3];
            auto back = directedEdges.find(edgeKey(v, u));
            if (directedEdges[edgeKey(u, v)] != 1 || back == directedEdges.end() ||
                back->second != 1)
                open[root] = edgeOpen[root] = true;
        }
        const glm::dvec3 a(scene.vertices[scene.indices[3 * t]].position);
        const glm::dvec3 b(scene.vertices[scene.indices[3 * t + 1]].position);
        const glm::dvec3 c(scene.vertices[scene.indices[3 * t + 2]].position);
        volume[root] += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    std::vector<uint32_t> rootOf(count);
    for (size_t t = 0; t < count; ++t) {
        rootOf[t] = findRoot(parent, welded[t][0]);
        out.openEdged += edgeOpen[rootOf[t]] && !alpha[t];
    }
    for (const Shell& shell : holdingShells(scene, rootOf, open, volume)) {
        open[shell.root] = true;
        out.shells.push_back(shell.warning);
    }
    for (size_t t = 0; t < count; ++t) {
        out.closed[t] = !open[rootOf[t]];
        out.flipped[t] = !open[rootOf[t]] && volume[rootOf[t]] < 0.0;
    }
    return out;
}

} // namespace penumbra::shadows
