#include "scene/ray_cast.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {
namespace {

constexpr uint32_t kLeafSize = 4;
constexpr size_t kBruteForceRays = 16; // fewer rays than this: no hierarchy
// |det| / (|e1| |e2|): the cosine of the ray to the normal times the sine between the edges.
constexpr float kParallel = 1e-9f;

glm::vec3 corner(const Scene& scene, uint32_t t, int k) {
    return scene.vertices[scene.indices[3 * size_t{t} + static_cast<size_t>(k)]].position;
}

// The slab test: the distance at which the ray enters `box`, or nullopt when it misses it or
// enters beyond `limit` (which may be infinite: a miss must not compare equal to it).
std::optional<float> entry(const Bounds& box, const glm::vec3& origin, const glm::vec3& inverse,
                           float limit) {
    const glm::vec3 a = (box.min - origin) * inverse, b = (box.max - origin) * inverse;
    const glm::vec3 lo = glm::min(a, b), hi = glm::max(a, b);
    const float enter = std::max({lo.x, lo.y, lo.z, 0.0f});
    const float leave = std::min({hi.x, hi.y, hi.z, limit});
    if (enter <= leave)
        return enter;
    return std::nullopt;
}

bool closer(const RayHit& a, const std::optional<RayHit>& best) {
    return !best || a.distance < best->distance ||
           (a.distance == best->distance && a.triangle < best->triangle);
}

} // namespace

std::optional<RayHit> hitTriangle(const Scene& scene, uint32_t t, const Ray& ray) {
    const glm::vec3 a = corner(scene, t, 0);
    const glm::vec3 e1 = corner(scene, t, 1) - a, e2 = corner(scene, t, 2) - a;
    const glm::vec3& dir = ray.direction;
    const glm::vec3 p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    // Parallel to the plane, or a triangle without area: relative to the edges, so that a world
    // a billionth the size is hit as the same world.
    if (!(std::abs(det) > kParallel * glm::length(e1) * glm::length(e2)))
        return std::nullopt;
    const glm::vec3 s = ray.origin - a;
    constexpr float kEdge = 1e-5f;
    const float u = glm::dot(s, p) / det;
    if (u < -kEdge || u > 1.0f + kEdge)
        return std::nullopt;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) / det;
    if (v < -kEdge || u + v > 1.0f + kEdge)
        return std::nullopt;
    const float distance = glm::dot(e2, q) / det;
    if (!(distance > 0.0f))
        return std::nullopt;
    // The front is counter-clockwise (glTF): the ray meets it when it runs against
    // n = cross(e1, e2), and det = dot(e1, cross(dir, e2)) = -dot(dir, n).
    return RayHit{.distance = distance, .front = det > 0.0f, .triangle = t};
}

TriangleBvh::TriangleBvh(const Scene& scene) : mScene(scene) {
    const auto triangles = static_cast<uint32_t>(scene.triangleCount());
    if (triangles == 0)
        return;
    // Each triangle's box, grown by the edge tolerance of hitTriangle so that no hit it accepts
    // lies outside its leaf.
    std::vector<Bounds> boxes(triangles);
    std::vector<glm::vec3> centres(triangles);
    for (uint32_t t = 0; t < triangles; ++t) {
        for (int k = 0; k < 3; ++k)
            boxes[t].grow(corner(scene, t, k));
        const float pad = 2e-5f * glm::length(boxes[t].extent()) + 1e-30f;
        boxes[t].min -= pad, boxes[t].max += pad;
        centres[t] = boxes[t].center();
    }
    mOrder.resize(triangles);
    for (uint32_t t = 0; t < triangles; ++t)
        mOrder[t] = t;
    mNodes.reserve(2 * (triangles / kLeafSize + 1));
    struct Task {
        uint32_t node, begin, end;
    };
    std::vector<Task> tasks;
    mNodes.push_back({});
    tasks.push_back({0, 0, triangles});
    while (!tasks.empty()) {
        const Task task = tasks.back();
        tasks.pop_back();
        Bounds box, spread;
        for (uint32_t i = task.begin; i < task.end; ++i) {
            box.grow(boxes[mOrder[i]].min);
            box.grow(boxes[mOrder[i]].max);
            spread.grow(centres[mOrder[i]]);
        }
        mNodes[task.node].box = box;
        const glm::vec3 extent = spread.extent();
        if (task.end - task.begin <= kLeafSize || glm::length(extent) == 0.0f) {
            mNodes[task.node].first = task.begin;
            mNodes[task.node].count = task.end - task.begin;
            continue;
        }
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const uint32_t middle = task.begin + (task.end - task.begin) / 2;
        std::nth_element(
            mOrder.begin() + task.begin, mOrder.begin() + middle, mOrder.begin() + task.end,
            [&](uint32_t a, uint32_t b) { return centres[a][axis] < centres[b][axis]; });
        const auto left = static_cast<uint32_t>(mNodes.size());
        mNodes.push_back({});
        const auto right = static_cast<uint32_t>(mNodes.size());
        mNodes.push_back({});
        mNodes[task.node].first = right; // left == right - 1
        tasks.push_back({right, middle, task.end});
        tasks.push_back({left, task.begin, middle});
    }
}

template <typename Visit>
void TriangleBvh::traverse(const Ray& ray, float& limit, Visit&& visit) const {
    if (mNodes.empty())
        return;
    glm::vec3 inverse;
    for (int k = 0; k < 3; ++k) // a zero component: a huge slope of its sign, never NaN
        inverse[k] = 1.0f / (ray.direction[k] == 0.0f ? 1e-30f : ray.direction[k]);
    std::array<uint32_t, 128> stack{};
    size_t size = 0;
    if (entry(mNodes[0].box, ray.origin, inverse, limit))
        stack[size++] = 0;
    while (size > 0) {
        const Node& node = mNodes[stack[--size]];
        if (node.count > 0) {
            mTested += node.count;
            for (uint32_t i = node.first; i < node.first + node.count; ++i)
                if (!visit(mOrder[i]))
                    return;
            continue;
        }
        const uint32_t children[2] = {node.first - 1, node.first};
        std::optional<float> near[2];
        for (int c = 0; c < 2; ++c)
            near[c] = entry(mNodes[children[c]].box, ray.origin, inverse, limit);
        const int first = near[1] && (!near[0] || *near[1] < *near[0]); // the nearer goes first
        for (int c : {1 - first, first})
            if (near[c] && size < stack.size())
                stack[size++] = children[c];
    }
}

std::optional<RayHit> TriangleBvh::firstHit(const Ray& ray, float maxDistance) const {
    std::optional<RayHit> best;
    float limit = maxDistance;
    traverse(ray, limit, [&](uint32_t t) {
        const auto hit = hitTriangle(mScene, t, ray);
        if (hit && hit->distance < maxDistance && closer(*hit, best)) {
            best = hit;
            limit = hit->distance; // equal distances stay in reach: the lower index wins
        }
        return true;
    });
    return best;
}

bool TriangleBvh::occluded(const Ray& ray, float maxDistance) const {
    bool blocked = false;
    float limit = maxDistance;
    traverse(ray, limit, [&](uint32_t t) {
        const auto hit = hitTriangle(mScene, t, ray);
        blocked = hit && hit->distance < maxDistance;
        return !blocked;
    });
    return blocked;
}

std::vector<std::optional<RayHit>> firstHitsBruteForce(const Scene& scene,
                                                       std::span<const Ray> rays) {
    std::vector<std::optional<RayHit>> best(rays.size());
    const auto triangles = static_cast<uint32_t>(scene.triangleCount());
    for (uint32_t t = 0; t < triangles; ++t)
        for (size_t r = 0; r < rays.size(); ++r)
            if (const auto hit = hitTriangle(scene, t, rays[r]); hit && closer(*hit, best[r]))
                best[r] = hit;
    return best;
}

std::vector<std::optional<RayHit>> firstHits(const Scene& scene, std::span<const Ray> rays) {
    if (rays.size() < kBruteForceRays)
        return firstHitsBruteForce(scene, rays);
    const TriangleBvh bvh(scene);
    std::vector<std::optional<RayHit>> hits(rays.size());
    for (size_t r = 0; r < rays.size(); ++r)
        hits[r] = bvh.firstHit(rays[r]);
    return hits;
}

std::optional<RayHit> firstHit(const Scene& scene, const glm::vec3& origin, const glm::vec3& dir) {
    const Ray ray{.origin = origin, .direction = dir};
    return firstHitsBruteForce(scene, std::span(&ray, 1)).front();
}

} // namespace penumbra
