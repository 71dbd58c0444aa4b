#include "render/culling.h"

#include <algorithm>
#include <limits>

namespace penumbra::render {

std::vector<Cluster> makeClusters(std::span<const glm::vec3> positions,
                                  std::span<const uint32_t> indices,
                                  std::span<const uint32_t> boundaries) {
    std::vector<Cluster> clusters;
    const auto triangles = static_cast<uint32_t>(indices.size() / 3);
    uint32_t t = 0;
    while (t < triangles) {
        // Up to kClusterTriangles, stopping at the next batch boundary.
        uint32_t end = std::min(triangles, t + kClusterTriangles);
        for (const uint32_t b : boundaries)
            if (b > 3 * t && b < 3 * end)
                end = b / 3;
        Cluster c{.firstIndex = 3 * t,
                  .indexCount = 3 * (end - t),
                  .lo = glm::vec3(std::numeric_limits<float>::max()),
                  .hi = glm::vec3(-std::numeric_limits<float>::max())};
        for (uint32_t i = c.firstIndex; i < c.firstIndex + c.indexCount; ++i) {
            const glm::vec3& p = positions[indices[i]];
            c.lo = glm::min(c.lo, p), c.hi = glm::max(c.hi, p);
        }
        clusters.push_back(c);
        t = end;
    }
    return clusters;
}

namespace {

// Whether the box lies wholly on the negative side of the plane a.x + b.y + c.z + d = 0.
bool outside(const glm::vec4& plane, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 far{plane.x >= 0 ? hi.x : lo.x, plane.y >= 0 ? hi.y : lo.y,
                        plane.z >= 0 ? hi.z : lo.z};
    return glm::dot(glm::vec3(plane), far) + plane.w < 0.0f;
}

} // namespace

std::vector<IndexRange> visibleRanges(std::span<const Cluster> clusters, uint32_t first,
                                      uint32_t count, const glm::mat4& viewProj, bool depthClamped,
                                      CasterSet set) {
    // The frustum's planes from the rows of the matrix [Gribb and Hartmann 2001]: w + x >= 0,
    // w - x >= 0, likewise y, then z >= 0 and w - z >= 0.
    const glm::mat4 m = glm::transpose(viewProj);
    std::vector<glm::vec4> planes{m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1]};
    if (!depthClamped)
        planes.insert(planes.end(), {m[2], m[3] - m[2]});
    std::vector<IndexRange> ranges;
    const auto begin =
        std::lower_bound(clusters.begin(), clusters.end(), first,
                         [](const Cluster& c, uint32_t index) { return c.firstIndex < index; });
    for (auto c = begin; c != clusters.end() && c->firstIndex < first + count; ++c) {
        if (set != CasterSet::All && c->dynamic != (set == CasterSet::Dynamic))
            continue;
        const bool culled = std::any_of(planes.begin(), planes.end(), [&](const glm::vec4& p) {
            return outside(p, c->lo, c->hi);
        });
        if (culled)
            continue;
        if (!ranges.empty() && ranges.back().first + ranges.back().count == c->firstIndex)
            ranges.back().count += c->indexCount;
        else
            ranges.push_back({c->firstIndex, c->indexCount});
    }
    return ranges;
}

void markDynamicClusters(std::span<Cluster> clusters, std::span<const uint32_t> triangleOf,
                         std::span<const uint8_t> moved) {
    for (Cluster& c : clusters) {
        c.dynamic = false;
        for (uint32_t t = c.firstIndex / 3; t < (c.firstIndex + c.indexCount) / 3; ++t)
            if (triangleOf[t] < moved.size() && moved[triangleOf[t]]) {
                c.dynamic = true;
                break;
            }
    }
}

} // namespace penumbra::render
