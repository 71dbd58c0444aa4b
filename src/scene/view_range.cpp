// The camera's view volume and the depth range of what lies inside it (cascade splits).
#include "penumbra/scene.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {

ViewFrustum viewFrustum(const Camera& c, float aspect) {
    ViewFrustum f{.position = c.position, .forward = glm::normalize(c.target - c.position)};
    f.right = glm::normalize(glm::cross(f.forward, c.up));
    f.up = glm::cross(f.right, f.forward);
    if (c.orthographic)
        f.halfExtent = {aspect * c.ymag, c.ymag};
    else
        f.halfExtentPerDistance = glm::vec2(aspect, 1.0f) * std::tan(0.5f * c.yfov);
    return f;
}

namespace {

// A point in the camera's frame: x right, y up, z the distance along the view axis.
using ViewPoint = glm::vec3;
constexpr int kPlanes = 6;

// The six half-spaces of the view volume as signed functions of a view point (>= 0: inside).
std::array<float, kPlanes> planeValues(const ViewFrustum& f, const Camera& c, ViewPoint p) {
    const glm::vec2 h = f.halfExtentAt(p.z);
    return {h.x - p.x, h.x + p.x, h.y - p.y, h.y + p.y, p.z - c.znear, c.zfar - p.z};
}

// Sutherland-Hodgman: the part of a convex polygon inside one half-space (the plane values are
// linear along each edge, so the crossing is where they interpolate to zero).
template <size_t N>
size_t clipPolygon(const std::array<ViewPoint, N>& in, size_t count, const ViewFrustum& f,
                   const Camera& c, int plane, std::array<ViewPoint, N>& out) {
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        const ViewPoint a = in[i], b = in[(i + 1) % count];
        const float va = planeValues(f, c, a)[plane], vb = planeValues(f, c, b)[plane];
        if (va >= 0.0f)
            out[n++] = a;
        if ((va >= 0.0f) != (vb >= 0.0f))
            out[n++] = a + (b - a) * (va / (va - vb));
    }
    return n;
}

} // namespace

glm::vec2 visibleDepthRange(const Scene& scene, const Camera& camera, float aspect) {
    const ViewFrustum f = viewFrustum(camera, aspect);
    std::vector<ViewPoint> local(scene.vertices.size());
    for (size_t i = 0; i < local.size(); ++i) {
        const glm::vec3 d = scene.vertices[i].position - f.position;
        local[i] = {glm::dot(d, f.right), glm::dot(d, f.up), glm::dot(d, f.forward)};
    }
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const std::array<ViewPoint, 3> v{local[scene.indices[t]], local[scene.indices[t + 1]],
                                         local[scene.indices[t + 2]]};
        // Nothing to learn from a triangle within the range found so far.
        const float zMin = std::min({v[0].z, v[1].z, v[2].z});
        const float zMax = std::max({v[0].z, v[1].z, v[2].z});
        if (zMin >= lo && zMax <= hi)
            continue;
        std::array<ViewPoint, 9> polygon{v[0], v[1], v[2]}, clipped{};
        size_t count = 3;
        for (int plane = 0; plane < kPlanes && count > 0; ++plane) {
            count = clipPolygon(polygon, count, f, camera, plane, clipped);
            std::swap(polygon, clipped);
        }
        for (size_t i = 0; i < count; ++i)
            lo = std::min(lo, polygon[i].z), hi = std::max(hi, polygon[i].z);
    }
    // Clipping puts points on the near and far planes up to rounding: keep them within.
    if (lo <= hi)
        lo = std::max(lo, camera.znear), hi = std::min(hi, camera.zfar);
    return {lo, hi};
}

} // namespace penumbra
