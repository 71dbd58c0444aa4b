#pragma once
// Scenes whose shadows the tests know by construction, shared by several test files.
#include "penumbra/scene.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"

#include <array>
#include <string>

namespace penumbra::test {

// Spheres of several sizes and heights over a 60-unit plane, seen from above, under `light`
// (the point-light tests put a bulb low above the plane, so that the lit plane is seen through
// five cube faces).
inline Scene spheresOverPlane(const Light& light) {
    Scene scene;
    scene.name = "spheres over a plane";
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("plane", {0.7f, 0.7f, 0.7f});
    const uint32_t red = mb.material("spheres", {0.7f, 0.25f, 0.2f});
    const float g = 30.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, grey);
    const std::array<glm::vec4, 8> spheres = {{{2.0f, 0.6f, 0.5f, 0.4f},
                                               {-1.5f, 1.0f, -2.0f, 0.5f},
                                               {0.5f, 0.5f, -3.5f, 0.45f},
                                               {-3.0f, 0.8f, 2.5f, 0.6f},
                                               {4.0f, 1.5f, -1.0f, 0.5f},
                                               {1.2f, 0.4f, 2.2f, 0.35f},
                                               {-0.9f, 0.35f, 0.4f, 0.3f},
                                               {0.3f, 0.5f, -0.9f, 0.25f}}};
    for (const glm::vec4& s : spheres)
        mb.sphere(glm::vec3(s), s.w, red);
    scene.lights.push_back(light);
    scene.cameras.push_back({.name = "above",
                             .position = {0.5f, 10.0f, 8.0f},
                             .target = {0.0f, 0.0f, -0.5f},
                             .yfov = 1.0f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

// One sphere of radius 0.8 whose lowest point is 0.5 above a 40-unit plane, seen obliquely from
// above, under `light`: the soft techniques' acceptance scene (its penumbra widens with the light's
// size from contact-sharp under the sphere to wide on the far side of its shadow).
inline Scene sphereOverPlane(const Light& light) {
    Scene scene;
    scene.name = "sphere over a plane";
    MeshBuilder mb(scene);
    const float g = 20.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("plane", {0.7f, 0.7f, 0.7f}));
    mb.sphere({0.0f, 1.3f, 0.0f}, 0.8f, mb.material("sphere", {0.7f, 0.25f, 0.2f}));
    scene.lights.push_back(light);
    scene.cameras.push_back({.name = "above",
                             .position = {0.0f, 6.0f, 6.0f},
                             .target = {-0.3f, 0.0f, -0.6f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

// builtin:resting's objects resting on a plane under `light`.
// Point-like lights of each type over builtin:resting's objects: a sun, a spot from the side and
// a bulb low above them (the virtual-map and repose tests).
inline Light sharpSun() {
    return {.name = "sun",
            .type = LightType::Directional,
            .direction = glm::normalize(glm::vec3(0.5f, -0.7f, -0.4f))};
}
inline Light sharpSpot() {
    const glm::vec3 at{-2.5f, 5.0f, 3.0f};
    return {.name = "spot",
            .type = LightType::Spot,
            .position = at,
            .direction = glm::normalize(glm::vec3(0.0f, 0.0f, -0.5f) - at),
            .intensity = 40.0f,
            .outerConeAngle = 0.75f};
}
inline Light sharpPoint() {
    return {.name = "point",
            .type = LightType::Point,
            .position = {0.6f, 2.4f, -0.4f},
            .intensity = 10.0f};
}

inline Scene restingObjects(const Light& light) {
    Scene scene = builtin::restingGeometry();
    scene.lights.push_back(light);
    return scene;
}

// restingObjects with a small ball beside them, before and after it slid a little (the scene's
// bounds unchanged): what a virtual map's moved-caster tests move.
struct SlidBall {
    Scene before, after;
};
inline SlidBall slidBall(const Light& light) {
    SlidBall s{.before = restingObjects(light)};
    const size_t firstBallVertex = s.before.vertices.size();
    MeshBuilder(s.before).sphere({-1.2f, 0.9f, -1.0f}, 0.25f, 1);
    s.after = s.before;
    for (size_t v = firstBallVertex; v < s.after.vertices.size(); ++v)
        s.after.vertices[v].position += glm::vec3(0.25f, 0.0f, 0.1f);
    return s;
}

// The soft techniques' acceptance lights over sphereOverPlane: a spot of `radius` from above and
// aside, a sun of `degrees`, a bulb of `radius` low beside the sphere.
inline Light acceptanceSpot(float radius) {
    const glm::vec3 at{1.0f, 6.0f, 1.5f};
    return {.name = "spot radius " + std::to_string(radius).substr(0, 3),
            .type = LightType::Spot,
            .position = at,
            .direction = glm::normalize(-at),
            .intensity = 40.0f,
            .outerConeAngle = 0.7f,
            .radius = radius};
}
inline Light acceptanceSun(float degrees) {
    return {.name = "sun " + std::to_string(degrees).substr(0, 3) + " degrees",
            .type = LightType::Directional,
            .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)),
            .angularDiameter = degrees};
}
inline Light acceptancePoint(float radius) {
    return {.name = "point radius " + std::to_string(radius).substr(0, 3),
            .type = LightType::Point,
            .position = {0.6f, 3.5f, 0.4f},
            .intensity = 8.0f,
            .radius = radius};
}

} // namespace penumbra::test
