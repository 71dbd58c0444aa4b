#include "scene/framing.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr float kLowPercentile = 0.05f, kHighPercentile = 0.95f;
constexpr float kSubjectMargin = 0.25f; // of the core's diagonal
constexpr float kAzimuthDegrees = 30.0f;
constexpr float kLowestElevation = 20.0f, kElevationRange = 30.0f;
constexpr float kFrameMargin = 1.05f; // the subject's extent over what the view must hold
// The image shape the framing assumes: the default 1280 x 720. Narrower images cut the sides.
constexpr float kAssumedAspect = 16.0f / 9.0f;

float percentile(std::vector<float>& values, float fraction) {
    const size_t k = static_cast<size_t>(fraction * static_cast<float>(values.size() - 1) + 0.5f);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

bool overlaps(const Bounds& a, const Bounds& b) {
    return glm::all(glm::lessThanEqual(a.min, b.max)) && glm::all(glm::lessThanEqual(b.min, a.max));
}

} // namespace

Bounds subjectBounds(const Scene& scene) {
    const Bounds all = scene.bounds();
    if (all.empty())
        return all;
    Bounds core;
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<float> values; // the triangles' corners
        values.reserve(scene.indices.size());
        for (uint32_t i : scene.indices)
            values.push_back(scene.vertices[i].position[axis]);
        core.min[axis] = percentile(values, kLowPercentile);
        core.max[axis] = percentile(values, kHighPercentile);
    }
    const float margin = std::max(kSubjectMargin * glm::length(core.extent()), 1e-6f);
    const Bounds region{.min = core.min - margin, .max = core.max + margin};
    const float huge = glm::length(region.extent());
    Bounds subject;
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        Bounds triangle;
        for (size_t k = 0; k < 3; ++k)
            triangle.grow(scene.vertices[scene.indices[t + k]].position);
        if (!overlaps(triangle, region))
            continue;
        if (glm::length(triangle.extent()) > huge) { // a ground or sky plane: the part near
            triangle.min = glm::max(triangle.min, region.min);
            triangle.max = glm::min(triangle.max, region.max);
        }
        subject.grow(triangle.min);
        subject.grow(triangle.max);
    }
    return subject.empty() ? all : subject;
}

float automaticExposure(const Scene& scene) {
    constexpr float kTarget = 2.0f, kTolerance = 4.0f;
    const Bounds subject = subjectBounds(scene);
    if (subject.empty())
        return 0.0f;
    float brightest = 0.0f;
    for (const Light& l : scene.lights) {
        float irradiance = l.intensity;
        if (l.type != LightType::Directional) {
            const float d = std::max(glm::length(l.position - subject.center()),
                                     0.1f * std::max(subject.radius(), 1e-6f));
            irradiance = l.intensity / (d * d);
        }
        irradiance *= std::max({l.color.x, l.color.y, l.color.z});
        if (std::isfinite(irradiance))
            brightest = std::max(brightest, irradiance);
    }
    if (brightest <= 0.0f ||
        (brightest <= kTarget * kTolerance && brightest >= kTarget / kTolerance))
        return 0.0f;
    return std::clamp(std::round(2.0f * std::log2(kTarget / brightest)) / 2.0f, -30.0f, 30.0f);
}

glm::vec2 depthRangeFrom(const Scene& scene, const glm::vec3& position) {
    const Bounds b = scene.bounds();
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 c(corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y,
                          corner & 4 ? b.max.z : b.min.z);
        farthest = std::max(farthest, glm::length(c - position));
    }
    const float zfar = std::max(1.1f * farthest, 1e-3f);
    return {zfar * 1e-4f, zfar};
}

Camera exteriorCamera(const Scene& scene, const Bounds& subject) {
    const glm::vec3 extent = glm::max(subject.extent(), glm::vec3(1e-6f));
    const float width = std::max(extent.x, extent.z);
    // Compact subjects from low down, flat ones (a level) from higher up to see across them.
    const float flatness = std::clamp(1.0f - extent.y / width, 0.0f, 1.0f);
    const float elevation = glm::radians(kLowestElevation + kElevationRange * flatness);
    // A three-quarter view of compact subjects; flat ones (a level) from the front, which fills
    // the frame with their ground.
    const float azimuth = glm::radians(kAzimuthDegrees * (1.0f - flatness));
    const glm::vec3 toEye(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                          std::cos(azimuth) * std::cos(elevation));
    Camera c{.name = "auto", .automatic = true};
    const glm::vec3 forward = -toEye;
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    const float tanHalf = std::tan(0.5f * c.yfov);
    // A corner r (from the centre) is in view at distance d when |r.right| and |r.up| are at
    // most tanHalf x its depth, d - r.toEye: d >= |r.axis| / tanHalf + r.toEye.
    // The triangles' corners, clamped to the subject, must be in view: tighter than its box.
    const glm::vec3 centre = subject.center();
    float distance = 0.0f, radius = 0.0f;
    for (uint32_t i : scene.indices) {
        const glm::vec3 r =
            kFrameMargin *
            (glm::clamp(scene.vertices[i].position, subject.min, subject.max) - centre);
        const float side =
            std::max(std::abs(glm::dot(r, right)) / kAssumedAspect, std::abs(glm::dot(r, up)));
        distance = std::max(distance, side / tanHalf + glm::dot(r, toEye));
        radius = std::max(radius, glm::length(r));
    }
    distance = std::max(distance, radius * 1.05f);
    c.target = centre;
    c.position = centre + distance * toEye;
    c.znear = std::max(distance - radius, distance * 1e-3f) * 0.5f;
    // Far enough for everything, the sky planes the framing ignored included.
    const Bounds all = scene.bounds();
    float farthest = distance + radius;
    for (int corner = 0; corner < 8; ++corner)
        farthest = std::max(farthest, glm::length(glm::vec3(corner & 1 ? all.max.x : all.min.x,
                                                            corner & 2 ? all.max.y : all.min.y,
                                                            corner & 4 ? all.max.z : all.min.z) -
                                                  c.position));
    c.zfar = farthest * 1.05f;
    return c;
}

std::optional<size_t> ownCamera(const Scene& scene, int index) {
    if (index < 0 || static_cast<size_t>(index) >= scene.cameras.size() ||
        scene.cameras[static_cast<size_t>(index)].automatic)
        return std::nullopt;
    return static_cast<size_t>(index);
}

} // namespace penumbra
