#include "scene/first_picture.h"

#include "scene/framing.h"
#include "scene/interior.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr int kGridWidth = 64, kGridHeight = 36; // the default image's 16:9
constexpr float kSunAzimuths[] = {85.0f, -85.0f, 45.0f, -45.0f, 135.0f, -135.0f, 0.0f};
constexpr float kSunElevations[] = {45.0f, 30.0f, 60.0f, 20.0f}; // the standard's first
constexpr float kBulbAlong[] = {0.0f, 0.3f, 0.6f};               // of the free line ahead
constexpr float kBulbSide[] = {0.0f, -0.3f, 0.3f}; // of the free line ahead, clamped by walls
constexpr float kBulbHeights[] = {0.5f, 0.8f};     // of the way to the ceiling
constexpr int kLightViews = 8;                     // cameras round a light's spot
constexpr size_t kMostLights = 4;                  // lights a camera is sought near
constexpr float kLightViewElevation = 35.0f;       // degrees
constexpr float kInteriorFovDegrees = 70.0f;
constexpr int kExteriorViews = 8;                   // directions round an exterior's target
constexpr int kInteriorViews = 8;                   // directions an interior camera may turn to
constexpr float kInteriorPitches[] = {0.0f, 20.0f}; // degrees down
constexpr int kFloorGrid = 9;                       // rays down per horizontal axis of the subject
// Where the rays down start, in the subject's height above its bottom: just above it (a ground),
// a quarter and half way up (a terrain's hills, a model's own thick base).
constexpr float kFloorStarts[] = {0.02f, 0.25f, 0.5f};
constexpr float kFloorShare = 0.5f; // of the rays: the subject stands on a floor

float sceneSize(const Scene& scene) {
    return std::max(glm::length(scene.bounds().extent()), 1e-6f);
}

glm::vec3 flatForward(const Camera& camera) {
    glm::vec3 f = camera.target - camera.position;
    f.y = 0.0f;
    return glm::length(f) > 1e-6f ? glm::normalize(f) : glm::vec3(0, 0, -1);
}

// How far a ray runs before it meets a surface; `otherwise` when it meets none.
float freeDistance(const TriangleBvh& bvh, const glm::vec3& from, const glm::vec3& dir,
                   float otherwise) {
    const auto hit = bvh.firstHit({.origin = from, .direction = dir});
    return hit ? hit->distance : otherwise;
}

// A bulb as bright on the floor under it as the default sun.
Light bulbAt(const TriangleBvh& bvh, const glm::vec3& position, const Light& standard, float size) {
    const float height = freeDistance(bvh, position, glm::vec3(0, -1, 0), size);
    Light l = standard;
    l.position = position;
    l.intensity = defaultSun().intensity * std::max(height * height, 1e-6f);
    return l;
}

std::vector<Light> bulbCandidates(const Scene& scene, const TriangleBvh& bvh, const Camera& camera,
                                  const Light& standard) {
    const float size = sceneSize(scene);
    const glm::vec3 forward = flatForward(camera);
    const glm::vec3 right = glm::cross(forward, glm::vec3(0, 1, 0));
    const float ahead = freeDistance(bvh, camera.position, forward, 0.5f * size);
    const float top = scene.bounds().max.y;
    std::vector<Light> lights;
    for (float along : kBulbAlong) {
        const glm::vec3 base = camera.position + along * ahead * forward;
        for (float side : kBulbSide) {
            const glm::vec3 dir = side < 0.0f ? -right : right;
            const float room = 0.7f * freeDistance(bvh, base, dir, size);
            const glm::vec3 foot = base + std::min(std::abs(side) * ahead, room) * dir;
            const float up = freeDistance(bvh, foot, glm::vec3(0, 1, 0), top - foot.y);
            for (float h : kBulbHeights)
                lights.push_back(bulbAt(bvh, foot + glm::vec3(0, h * up, 0), standard, size));
        }
    }
    return lights;
}

std::vector<Light> sunCandidates(const Camera& camera, const Light& standard) {
    const glm::vec3 forward = flatForward(camera);
    const glm::vec3 right = glm::cross(forward, glm::vec3(0, 1, 0));
    std::vector<Light> lights;
    for (float elevation : kSunElevations)
        for (float azimuth : kSunAzimuths) {
            const float round = glm::radians(azimuth), up = glm::radians(elevation);
            // Towards the light: turned `round` from straight behind the camera, to its left.
            const glm::vec3 towards =
                std::cos(up) * (-std::cos(round) * forward - std::sin(round) * right) +
                std::sin(up) * glm::vec3(0, 1, 0);
            Light l = standard;
            l.direction = -glm::normalize(towards);
            lights.push_back(l);
        }
    return lights;
}

// Whether the ray down the column (i, k) of a kFloorGrid grid over the subject's footprint, from
// above it, leaves the scene through the front of an open surface.
bool columnEndsOnAnOpenSurface(const TriangleBvh& bvh, const Bounds& subject, int i, int k) {
    const glm::vec3 extent = subject.extent();
    const float x = (static_cast<float>(i) + 0.5f) / kFloorGrid;
    const float z = (static_cast<float>(k) + 0.5f) / kFloorGrid;
    return endsOnAnOpenSurface(bvh,
                               glm::vec3(subject.min.x + x * extent.x,
                                         subject.max.y + 0.01f * extent.y,
                                         subject.min.z + z * extent.z),
                               1e-5f * std::max(glm::length(extent), 1e-6f));
}

// Whether something under the subject can receive its shadow: in at least half of a 9 x 9 grid
// of columns over its footprint, a ray down from 2%, 25% or 50% of its height above its bottom
// meets the front of a surface (one facing up), or one from above it leaves through the front
// of an open surface. A ray that meets a back face first (the underside of a model, from
// within) goes on through it: a lone model's feet are no floor; the ground under a floating
// ball, a terrain and a model's own thick base are.
bool somethingBelow(const Scene& scene, const TriangleBvh& bvh) {
    return floorShare(scene, bvh) >= kFloorShare;
}

} // namespace

float floorShare(const Scene& scene, const TriangleBvh& bvh) {
    constexpr int kCrossings = 4; // back faces a ray goes through
    const Bounds subject = subjectBounds(scene);
    const glm::vec3 extent = subject.extent();
    const float height = std::max(extent.y, 1e-3f * std::max(extent.x, extent.z));
    int floors = 0;
    for (int i = 0; i < kFloorGrid; ++i)
        for (int k = 0; k < kFloorGrid; ++k) {
            bool floor = false;
            for (float start : kFloorStarts) {
                const float x = (static_cast<float>(i) + 0.5f) / kFloorGrid;
                const float z = (static_cast<float>(k) + 0.5f) / kFloorGrid;
                Ray ray{.origin =
                            subject.min + glm::vec3(x * extent.x, start * height, z * extent.z)};
                for (int crossing = 0; crossing < kCrossings && !floor; ++crossing) {
                    const auto hit = bvh.firstHit(ray);
                    if (!hit)
                        break;
                    floor = hit->front;
                    ray.origin.y -= hit->distance + 1e-5f * height;
                }
            }
            floors += floor || columnEndsOnAnOpenSurface(bvh, subject, i, k);
        }
    return static_cast<float>(floors) / (kFloorGrid * kFloorGrid);
}

bool endsOnAnOpenSurface(const TriangleBvh& bvh, const glm::vec3& top, float step) {
    Ray ray{.origin = top};
    bool lastFront = false;
    for (int met = 0;; ++met) {
        const auto hit = bvh.firstHit(ray);
        if (!hit)
            return lastFront;
        if (met == kMostSurfacesDown)
            return false; // one surface more than it follows
        lastFront = hit->front;
        ray.origin.y -= hit->distance + step;
    }
}

ViewProbe::ViewProbe(const Scene& scene, const TriangleBvh& bvh, const Camera& camera)
    : ViewProbe(scene, bvh, camera, subjectBounds(scene)) {}

ViewProbe::ViewProbe(const Scene& scene, const TriangleBvh& bvh, const Camera& camera,
                     Bounds subject)
    : mBvh(bvh), mPixels(size_t{kGridWidth} * kGridHeight), mOffset(1e-4f * sceneSize(scene)) {
    const ViewFrustum f = viewFrustum(camera, static_cast<float>(kGridWidth) / kGridHeight);
    subject.min -= mOffset, subject.max += mOffset;
    for (int y = 0; y < kGridHeight; ++y)
        for (int x = 0; x < kGridWidth; ++x) {
            const glm::vec2 ndc((2.0f * static_cast<float>(x) + 1.0f) / kGridWidth - 1.0f,
                                1.0f - (2.0f * static_cast<float>(y) + 1.0f) / kGridHeight);
            const Ray ray{.origin = f.position + ndc.x * f.halfExtent.x * f.right +
                                    ndc.y * f.halfExtent.y * f.up,
                          .direction = glm::normalize(f.forward +
                                                      ndc.x * f.halfExtentPerDistance.x * f.right +
                                                      ndc.y * f.halfExtentPerDistance.y * f.up)};
            const auto hit = bvh.firstHit(ray);
            if (!hit)
                continue;
            const glm::vec3 p = ray.origin + hit->distance * ray.direction;
            const uint32_t* t = &scene.indices[3 * size_t{hit->triangle}];
            const glm::vec3 a = scene.vertices[t[0]].position;
            glm::vec3 n =
                glm::cross(scene.vertices[t[1]].position - a, scene.vertices[t[2]].position - a);
            n = glm::length(n) > 0.0f ? glm::normalize(n) : -ray.direction;
            if (glm::dot(n, ray.direction) > 0.0f) // the side the camera sees
                n = -n;
            mSamples.push_back({.point = p,
                                .normal = n,
                                .inSubject = glm::all(glm::lessThanEqual(subject.min, p)) &&
                                             glm::all(glm::lessThanEqual(p, subject.max))});
        }
}

std::optional<ViewProbe::Arrival> ViewProbe::arrival(const Sample& s, const Light& light) const {
    glm::vec3 toLight = -light.direction;
    float reach = std::numeric_limits<float>::infinity(), falloff = 1.0f;
    if (light.type != LightType::Directional) {
        toLight = light.position - s.point;
        reach = glm::length(toLight);
        if (!(reach > 0.0f))
            return std::nullopt;
        toLight /= reach;
        // KHR_lights_punctual as shading.glsl shades it: inverse square, the range's window.
        const float window =
            light.range > 0.0f ? std::clamp(1.0f - std::pow(reach / light.range, 4.0f), 0.0f, 1.0f)
                               : 1.0f;
        falloff = window * window / (reach * reach);
        if (light.type == LightType::Spot) {
            const float cosine = glm::dot(-toLight, light.direction);
            const float outer = std::cos(light.outerConeAngle);
            if (cosine < outer)
                return std::nullopt; // outside the cone: unlit, not shadowed
            const float inner = std::cos(light.innerConeAngle);
            const float t =
                inner > outer ? std::clamp((cosine - outer) / (inner - outer), 0.0f, 1.0f) : 1.0f;
            falloff *= t * t * (3.0f - 2.0f * t);
        }
    }
    const float lambert = glm::dot(s.normal, toLight);
    if (lambert <= 0.05f)
        return std::nullopt; // turned away (or grazing): dark whatever casts
    const Ray ray{.origin = s.point + mOffset * s.normal, .direction = toLight};
    const glm::vec3 colour = light.color * light.intensity;
    return Arrival{.irradiance = lambert * falloff * (colour.x + colour.y + colour.z) / 3.0f,
                   .visible = !mBvh.occluded(ray, reach)};
}

ViewShadow ViewProbe::measure(const Light& light) const {
    size_t lit = 0, shadowed = 0;
    for (const Sample& s : mSamples)
        if (const auto a = arrival(s, light))
            ++(a->visible ? lit : shadowed);
    return {.covered = share(mSamples.size()),
            .subject = subject(),
            .lit = share(lit),
            .castShadow = share(shadowed)};
}

float ViewProbe::subject() const {
    return share(static_cast<size_t>(std::count_if(mSamples.begin(), mSamples.end(),
                                                   [](const Sample& s) { return s.inSubject; })));
}

float ViewProbe::share(size_t pixels) const {
    return static_cast<float>(pixels) / static_cast<float>(mPixels);
}

float ViewProbe::castShadow(std::span<const Light> lights) const {
    std::vector<const Light*> counted;
    for (const Light& l : lights)
        if (castsShadowMap(l) && lightsTheView(measure(l)))
            counted.push_back(&l);
    // A pixel shows a shadow when what reaches it is under half of what would.
    size_t shadowed = 0;
    for (const Sample& s : mSamples) {
        double reaching = 0.0, unblocked = 0.0;
        for (const Light* l : counted)
            if (const auto a = arrival(s, *l))
                reaching += a->irradiance, unblocked += a->visible ? a->irradiance : 0.0f;
        shadowed += reaching > 0.0 && unblocked < kVisibleShadow * reaching;
    }
    return share(shadowed);
}

PictureMeasure measurePicture(const Scene& scene, const Camera& camera) {
    const TriangleBvh bvh(scene);
    const ViewProbe probe(scene, bvh, camera);
    return {.castShadow = probe.castShadow(scene.lights), .subject = probe.subject()};
}

std::vector<Light> defaultLightCandidates(const Scene& scene, const TriangleBvh& bvh,
                                          const Camera& camera, const Light& standard) {
    return standard.type == LightType::Directional ? sunCandidates(camera, standard)
                                                   : bulbCandidates(scene, bvh, camera, standard);
}

bool lightsTheView(const ViewShadow& v) {
    return v.lit >= kLeastLit * v.covered;
}

namespace {

// The light and the cast shadow it shows (-1 when no candidate lights the view).
struct Lit {
    Light light;
    float shadow = -1.0f;
};

Lit bestDefaultLight(const Scene& scene, const TriangleBvh& bvh, const Bounds& subject,
                     const Camera& camera, const Light& standard) {
    const ViewProbe probe(scene, bvh, camera, subject);
    const ViewShadow first = probe.measure(standard);
    Lit best{standard, lightsTheView(first) ? first.castShadow : -1.0f};
    if (first.castShadow >= kEnoughShadow)
        return {standard, first.castShadow};
    for (const Light& l : defaultLightCandidates(scene, bvh, camera, standard)) {
        const ViewShadow v = probe.measure(l);
        if (lightsTheView(v) && v.castShadow > best.shadow)
            best = {l, v.castShadow};
    }
    return best;
}

} // namespace

Light chooseDefaultLight(const Scene& scene, const Camera& camera, const Light& standard) {
    if (scene.triangleCount() == 0)
        return standard;
    const TriangleBvh bvh(scene);
    return bestDefaultLight(scene, bvh, subjectBounds(scene), camera, standard).light;
}

std::optional<Camera> betterInteriorView(const Scene& scene, const Camera& standard) {
    if (scene.triangleCount() == 0)
        return std::nullopt;
    const TriangleBvh bvh(scene);
    const Bounds subject = subjectBounds(scene);
    const auto shadowOf = [&](const Camera& c) {
        return bestDefaultLight(scene, bvh, subject, c, standardLightFor(scene, c, true)).shadow;
    };
    float best = shadowOf(standard);
    if (best >= kEnoughShadow)
        return std::nullopt;
    const float reach = std::max(glm::length(standard.target - standard.position), 1e-6f);
    std::optional<Camera> chosen;
    for (int a = 0; a < kInteriorViews; ++a)
        for (float pitch : kInteriorPitches) {
            const float round = 2.0f * glm::pi<float>() * static_cast<float>(a) / kInteriorViews;
            const float down = glm::radians(pitch);
            Camera c = standard;
            c.target =
                c.position + reach * glm::vec3(std::cos(down) * std::cos(round), -std::sin(down),
                                               std::cos(down) * std::sin(round));
            if (const float s = shadowOf(c); s > best) {
                best = s;
                chosen = c;
            }
        }
    return chosen;
}

bool addGroundWhereNothingReceives(Scene& scene) {
    if (scene.cameras.empty() || scene.triangleCount() == 0)
        return false;
    const Camera camera = scene.cameras.front();
    float before = 0.0f;
    {
        const TriangleBvh bvh(scene);
        if (somethingBelow(scene, bvh))
            return false;
        before = ViewProbe(scene, bvh, camera).castShadow(scene.lights);
    }
    // Tried in place and taken back when it gains too little: a copy of the scene would copy
    // its decoded images too.
    const size_t vertices = scene.vertices.size(), indices = scene.indices.size(),
                 materials = scene.materials.size();
    const std::vector<Light> lights = scene.lights;
    addGround(scene, "ground (automatic)");
    if (scene.defaultLight)
        scene.lights.front() = defaultLightFor(scene, camera, camera.name == "auto (interior)");
    const TriangleBvh bvh(scene);
    const float after = ViewProbe(scene, bvh, camera).castShadow(scene.lights);
    if (after >= before + kGroundGain) {
        scene.automaticGround = true;
        return true;
    }
    scene.vertices.resize(vertices);
    scene.indices.resize(indices);
    scene.materials.resize(materials);
    scene.lights = lights;
    return false;
}

bool turnExteriorView(Scene& scene) {
    if (scene.cameras.empty() || scene.cameras.front().name != "auto (exterior)" ||
        scene.triangleCount() == 0)
        return false;
    const TriangleBvh bvh(scene);
    const Bounds subject = subjectBounds(scene);
    const auto shown = [&](const Camera& c) -> Lit {
        const ViewProbe probe(scene, bvh, c, subject);
        if (probe.subject() < kLeastSubject)
            return {};
        if (scene.defaultLight) // the default light follows the camera
            return bestDefaultLight(scene, bvh, subject, c, defaultSun(c));
        return {Light{}, probe.castShadow(scene.lights)};
    };
    const Camera standard = scene.cameras.front();
    Lit best = shown(standard);
    if (best.shadow >= kEnoughShadow)
        return false;
    std::optional<Camera> chosen;
    const glm::vec3 offset = standard.position - standard.target;
    for (int a = 1; a < kExteriorViews; ++a) {
        const float round = 2.0f * glm::pi<float>() * static_cast<float>(a) / kExteriorViews;
        const float c = std::cos(round), s = std::sin(round);
        Camera turned = standard;
        turned.position = standard.target + glm::vec3(c * offset.x + s * offset.z, offset.y,
                                                      -s * offset.x + c * offset.z);
        if (const Lit l = shown(turned); l.shadow > best.shadow) {
            best = l;
            chosen = turned;
        }
    }
    if (!chosen)
        return false;
    scene.cameras.front() = *chosen;
    if (scene.defaultLight)
        scene.lights.front() = best.light;
    return true;
}

std::string automaticGroundNote(const Scene& scene) {
    return "added a ground under '" + scene.name +
           "': nothing in view received its cast shadow (--no-ground leaves it out)";
}

std::optional<Camera> cameraFromLights(const Scene& scene, const Camera& standard,
                                       bool levelOrInterior) {
    std::vector<const Light*> bulbs;
    for (const Light& l : scene.lights)
        if (l.type != LightType::Directional && castsShadowMap(l) && bulbs.size() < kMostLights)
            bulbs.push_back(&l);
    if (bulbs.empty() || scene.triangleCount() == 0)
        return std::nullopt;
    const TriangleBvh bvh(scene);
    const Bounds subject = subjectBounds(scene);
    const auto score = [&](const Camera& c) {
        const ViewProbe probe(scene, bvh, c, subject);
        return probe.subject() >= kLeastSubject ? probe.castShadow(scene.lights) : -1.0f;
    };
    if (!levelOrInterior && ViewProbe(scene, bvh, standard, subject).subject() >= kLeastSubject)
        return std::nullopt; // an exterior framed as it should be
    float best = score(standard);
    std::optional<Camera> chosen;
    const float size = sceneSize(scene);
    for (const Light* l : bulbs) {
        const glm::vec3 aim = l->type == LightType::Spot ? l->direction : glm::vec3(0, -1, 0);
        const auto spot = bvh.firstHit({.origin = l->position, .direction = aim});
        if (!spot)
            continue;
        const glm::vec3 target = l->position + spot->distance * aim;
        const float reach = std::max(1.5f * spot->distance, 1e-3f * size);
        for (int a = 0; a < kLightViews; ++a) {
            const float round = 2.0f * glm::pi<float>() * static_cast<float>(a) / kLightViews;
            const float up = glm::radians(kLightViewElevation);
            const glm::vec3 dir(std::cos(up) * std::cos(round), std::sin(up),
                                std::cos(up) * std::sin(round));
            const glm::vec3 from = target + 1e-4f * size * dir;
            const float distance = std::min(reach, 0.8f * freeDistance(bvh, from, dir, 2 * reach));
            if (distance < 0.25f * spot->distance)
                continue; // a wall at the spot: no view of it
            Camera c{.name = "auto (from the lights)",
                     .position = target + distance * dir,
                     .target = target,
                     .yfov = glm::radians(kInteriorFovDegrees),
                     .automatic = true};
            const glm::vec2 depth = depthRangeFrom(scene, c.position);
            c.znear = depth.x, c.zfar = depth.y;
            if (const float s = score(c); s > best) {
                best = s;
                chosen = c;
            }
        }
    }
    return chosen;
}

} // namespace penumbra
