#include "scene/interior.h"

#include "scene/first_picture.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace penumbra {
namespace {

constexpr float kInteriorFovDegrees = 70.0f;
constexpr int kGrid = 5;                       // room candidates per horizontal axis
constexpr std::array kHeights = {0.5f, 0.25f}; // of the subject's height
constexpr int kAzimuths = 8;                   // horizontal rays per candidate
constexpr int kMinFrontRays = 7;               // of kAzimuths
constexpr float kMinOpenness = 0.05f;          // of the subject's width
constexpr float kMinCoverage = 0.5f;           // of the subject's footprint
constexpr float kExteriorElevation = 15.0f;    // degrees
constexpr float kSunFromLeft = 85.0f;          // degrees round from the camera's back
constexpr float kSunElevation = 45.0f;         // degrees
constexpr float kDefaultSunIntensity = 2.0f;

glm::vec3 horizontal(int k) {
    const float a = 2.0f * glm::pi<float>() * static_cast<float>(k) / kAzimuths;
    return {std::cos(a), 0.0f, std::sin(a)};
}

} // namespace

bool ViewMeasure::interior() const {
    return room && room->openness >= kMinOpenness * subjectWidth &&
           room->coverage >= kMinCoverage && exteriorFront < 0.5f;
}

ViewMeasure measureView(const Scene& scene, const Bounds& subject) {
    ViewMeasure m{.subjectWidth = std::max(subject.extent().x, subject.extent().z)};
    if (scene.triangleCount() == 0 || subject.empty())
        return m;
    // Room candidates: kAzimuths horizontal rays and one down from each.
    std::vector<glm::vec3> candidates;
    for (float h : kHeights)
        for (int i = 0; i < kGrid; ++i)
            for (int k = 0; k < kGrid; ++k) {
                const glm::vec3 f((static_cast<float>(i) + 0.5f) / kGrid, h,
                                  (static_cast<float>(k) + 0.5f) / kGrid);
                candidates.push_back(subject.min + f * subject.extent());
            }
    std::vector<Ray> rays;
    for (const glm::vec3& p : candidates) {
        for (int a = 0; a < kAzimuths; ++a)
            rays.push_back({.origin = p, .direction = horizontal(a)});
        rays.push_back({.origin = p, .direction = glm::vec3(0, -1, 0)});
    }
    // Exterior rays: from 8 sides towards the subject's lower half.
    const glm::vec3 centre = subject.center();
    const float reach = 1.5f * std::max(subject.radius(), 1e-6f);
    const size_t exteriorStart = rays.size();
    for (int a = 0; a < kAzimuths; ++a)
        for (float h : {0.2f, 0.5f}) {
            const glm::vec3 aim(centre.x, subject.min.y + h * subject.extent().y, centre.z);
            const float e = glm::radians(kExteriorElevation);
            const glm::vec3 from =
                aim + reach * (std::cos(e) * horizontal(a) + std::sin(e) * glm::vec3(0, 1, 0));
            rays.push_back({.origin = from, .direction = glm::normalize(aim - from)});
        }
    const std::vector<std::optional<RayHit>> hits = firstHits(scene, rays);

    for (size_t c = 0; c < candidates.size(); ++c) {
        const size_t first = c * (kAzimuths + 1);
        const auto& down = hits[first + kAzimuths];
        if (!down || !down->front)
            continue;
        int fronts = 0, longest = 0;
        float longestDistance = -1.0f;
        std::vector<float> free;
        glm::vec2 lo(candidates[c].x, candidates[c].z), hi = lo; // the walls met, seen from above
        for (int a = 0; a < kAzimuths; ++a) {
            const auto& hit = hits[first + static_cast<size_t>(a)];
            if (!hit)
                continue;
            fronts += hit->front ? 1 : 0;
            free.push_back(hit->distance);
            const glm::vec3 wall = candidates[c] + hit->distance * horizontal(a);
            lo = glm::min(lo, glm::vec2(wall.x, wall.z));
            hi = glm::max(hi, glm::vec2(wall.x, wall.z));
            if (hit->distance > longestDistance)
                longest = a, longestDistance = hit->distance;
        }
        if (fronts < kMinFrontRays)
            continue;
        // How much of the subject's footprint the room spans: an inside-out box on a wide
        // ground is a mis-wound model, not a room.
        const glm::vec2 sLo(subject.min.x, subject.min.z), sHi(subject.max.x, subject.max.z);
        const glm::vec2 overlap = glm::max(glm::min(hi, sHi) - glm::max(lo, sLo), glm::vec2(0));
        const glm::vec2 footprint = glm::max(sHi - sLo, glm::vec2(1e-12f));
        const float coverage = overlap.x * overlap.y / (footprint.x * footprint.y);
        // The clearance to the nearest wall; of equals, the one nearest the centre.
        const float openness = *std::min_element(free.begin(), free.end());
        const float tie = 1e-4f * m.subjectWidth;
        const auto nearer = [&](const glm::vec3& a, const glm::vec3& b) {
            return glm::length(a - centre) < glm::length(b - centre) - tie;
        };
        if (!m.room || openness > m.room->openness + tie ||
            (openness > m.room->openness - tie && nearer(candidates[c], m.room->position)))
            m.room = RoomPoint{.position = candidates[c],
                               .along = horizontal(longest),
                               .openness = openness,
                               .coverage = coverage};
    }
    int met = 0, fronts = 0;
    for (size_t r = exteriorStart; r < rays.size(); ++r)
        if (hits[r]) {
            ++met;
            fronts += hits[r]->front ? 1 : 0;
        }
    m.exteriorFront = met ? static_cast<float>(fronts) / static_cast<float>(met) : 1.0f;
    return m;
}

bool isInterior(const Scene& scene) {
    return measureView(scene, subjectBounds(scene)).interior();
}

Camera interiorCamera(const Scene& scene, const ViewMeasure& measure, const Bounds& subject) {
    const glm::vec3 extent = subject.extent();
    glm::vec3 position = subject.center();
    glm::vec3 along = extent.x >= extent.z ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, -1);
    if (measure.room) {
        position = measure.room->position;
        along = measure.room->along;
    }
    const Bounds all = scene.bounds();
    const float size = std::max(glm::length(all.extent()), 1e-3f);
    return {.name = "auto (interior)",
            .position = position,
            .target = position + along * (0.25f * size),
            .yfov = glm::radians(kInteriorFovDegrees),
            .znear = size * 1e-4f,
            .zfar = size * 1.5f,
            .automatic = true};
}

Camera interiorCamera(const Scene& scene) {
    const Bounds subject = subjectBounds(scene);
    return interiorCamera(scene, measureView(scene, subject), subject);
}

Camera automaticCamera(const Scene& scene, ViewChoice choice) {
    const Bounds subject = subjectBounds(scene);
    if (choice != ViewChoice::Exterior) {
        const ViewMeasure m = measureView(scene, subject);
        if (choice == ViewChoice::Interior || m.interior())
            return interiorCamera(scene, m, subject);
    }
    Camera c = exteriorCamera(scene, subject);
    c.name = "auto (exterior)";
    return c;
}

Light defaultSun(const Camera& camera) {
    glm::vec3 forward = camera.target - camera.position;
    forward.y = 0.0f;
    forward = glm::length(forward) > 1e-6f ? glm::normalize(forward) : glm::vec3(0, 0, -1);
    const glm::vec3 right = glm::cross(forward, glm::vec3(0, 1, 0));
    const float round = glm::radians(kSunFromLeft), up = glm::radians(kSunElevation);
    // Towards the light: behind-left of the view axis, turned `round` from straight behind.
    const glm::vec3 towards =
        std::cos(up) * (-std::cos(round) * forward - std::sin(round) * right) +
        std::sin(up) * glm::vec3(0, 1, 0);
    return {.name = "default sun",
            .type = LightType::Directional,
            .direction = -glm::normalize(towards),
            .intensity = kDefaultSunIntensity};
}

Light defaultLightFor(const Scene& scene, const Camera& camera, bool interior) {
    return chooseDefaultLight(scene, camera, standardLightFor(scene, camera, interior));
}

Light standardLightFor(const Scene& scene, const Camera& camera, bool interior) {
    const Light sun = defaultSun(camera);
    if (!interior)
        return sun;
    const glm::vec3 from = camera.position;
    if (!firstHit(scene, from, -sun.direction))
        return sun; // the sun reaches the room (an open roof)
    const Bounds b = scene.bounds();
    const auto ceiling = firstHit(scene, from, glm::vec3(0, 1, 0));
    const float up = ceiling ? ceiling->distance : b.max.y - from.y;
    const glm::vec3 position = from + glm::vec3(0.0f, 0.5f * up, 0.0f);
    const auto floor = firstHit(scene, position, glm::vec3(0, -1, 0));
    const float height = floor ? floor->distance : position.y - b.min.y;
    // A point light's irradiance at distance d is I / d^2: the sun's irradiance on that floor.
    return {.name = "default light (interior)",
            .type = LightType::Point,
            .position = position,
            .intensity = sun.intensity * std::max(height * height, 1e-6f)};
}

} // namespace penumbra
