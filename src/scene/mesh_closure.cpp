#include "scene/mesh_closure.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace penumbra {
namespace {

struct EdgeUse {
    uint32_t forward = 0, backward = 0; // from the lower welded vertex id to the higher, or back
};

} // namespace

MeshClosure meshClosure(const Scene& scene) {
    MeshClosure out{.triangles = scene.triangleCount()};
    const Bounds b = scene.bounds();
    if (b.empty())
        return out;
    const float cell = std::max(glm::length(b.extent()) * 1e-6f, 1e-30f);
    // Weld: vertices in the same cell are one.
    std::unordered_map<uint64_t, uint32_t> cellId;
    std::vector<uint32_t> welded(scene.vertices.size());
    for (size_t v = 0; v < scene.vertices.size(); ++v) {
        const glm::vec3 q = glm::floor((scene.vertices[v].position - b.min) / cell);
        const auto key = (static_cast<uint64_t>(std::clamp(q.x, 0.0f, 2097151.0f)) << 42) |
                         (static_cast<uint64_t>(std::clamp(q.y, 0.0f, 2097151.0f)) << 21) |
                         static_cast<uint64_t>(std::clamp(q.z, 0.0f, 2097151.0f));
        welded[v] = cellId.emplace(key, static_cast<uint32_t>(cellId.size())).first->second;
    }
    const auto edgeKey = [](uint32_t a, uint32_t c) {
        return (static_cast<uint64_t>(std::min(a, c)) << 32) | std::max(a, c);
    };
    std::unordered_map<uint64_t, EdgeUse> edges;
    edges.reserve(scene.indices.size());
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = welded[scene.indices[t + k]];
            const uint32_t c = welded[scene.indices[t + (k + 1) % 3]];
            EdgeUse& e = edges[edgeKey(a, c)];
            (a < c ? e.forward : e.backward) += 1;
        }
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        bool open = false, misWound = false;
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = welded[scene.indices[t + k]];
            const uint32_t c = welded[scene.indices[t + (k + 1) % 3]];
            const EdgeUse& e = edges[edgeKey(a, c)];
            open |= e.forward + e.backward == 1;
            misWound |= e.forward + e.backward > 1 && (e.forward != 1 || e.backward != 1);
        }
        out.open += open;
        out.misWound += misWound && !open;
    }
    return out;
}

} // namespace penumbra
