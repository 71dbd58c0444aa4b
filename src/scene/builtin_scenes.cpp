#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace penumbra::builtin {
namespace {

// Everything in the showcase but its light: ground, floating sphere, resting cube, leaning pole
// (its shadow starts at its base) and a row of thin open fence slats.
Scene showcaseGeometry(std::string name) {
    Scene scene;
    scene.name = std::move(name);
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.68f});
    const uint32_t red = mb.material("sphere", {0.75f, 0.2f, 0.15f});
    const uint32_t blue = mb.material("cube", {0.2f, 0.35f, 0.75f});
    const uint32_t wood = mb.material("wood", {0.6f, 0.45f, 0.25f});
    const float g = kGroundHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    mb.sphere(kSphereCenter, kSphereRadius, red);
    glm::mat4 cube = glm::translate(glm::mat4(1.0f), {2.6f, 0.8f, 0.6f});
    cube = glm::rotate(cube, glm::radians(25.0f), {0, 1, 0});
    mb.box(glm::scale(cube, glm::vec3(1.6f)), blue);
    mb.beam(kPoleBase, kPoleTip, kPoleThickness, wood);
    for (int i = 0; i < 9; ++i) {
        const float x = -2.8f + 0.3f * static_cast<float>(i), z = -3.2f;
        mb.quad({x, 0, z}, {x + 0.12f, 0, z}, {x + 0.12f, 1.4f, z}, {x, 1.4f, z}, wood);
    }
    scene.cameras.push_back(mainCamera({0.0f, 6.5f, 11.0f}, {-0.3f, 0.5f, -0.4f}, 0.75f));
    return scene;
}

} // namespace

Light sun() {
    return {.name = "sun",
            .type = LightType::Directional,
            .direction = glm::normalize(kSunDirection),
            .color = {1.0f, 0.97f, 0.92f},
            .intensity = 1.8f,
            .angularDiameter = 0.53f};
}

Scene showcase() {
    Scene scene = showcaseGeometry("showcase");
    scene.lights.push_back(sun());
    return scene;
}

Light spotLight(const glm::vec3& position, const glm::vec3& target, float innerConeAngle,
                float outerConeAngle) {
    const float distance = glm::length(target - position);
    return {.name = "spot",
            .type = LightType::Spot,
            .position = position,
            .direction = glm::normalize(target - position),
            .color = {1.0f, 0.95f, 0.85f},
            .intensity = 1.8f * distance * distance, // ~1.8 at the target
            .innerConeAngle = innerConeAngle,
            .outerConeAngle = outerConeAngle,
            .radius = 0.2f};
}

Scene spot() {
    Scene scene = showcaseGeometry("spot");
    scene.lights.push_back(spotLight(kSpotPosition, kSpotTarget, 0.42f, 0.52f));
    return scene;
}

Scene grazing() {
    Scene scene;
    scene.name = "grazing";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.7f});
    const uint32_t box = mb.material("box", {0.7f, 0.3f, 0.2f});
    const float g = kGrazingHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), kGrazingBoxCenter), kGrazingBoxSize), box);
    // Light travels mostly along +x and down, exactly 85 degrees from the plane's normal; a small
    // azimuth keeps texel rows from lining up with the camera's pixel rows.
    const float a = glm::radians(kGrazingAngleDegrees), azimuth = glm::radians(11.0f);
    const glm::vec3 direction(std::sin(a) * std::cos(azimuth), -std::cos(a),
                              std::sin(a) * std::sin(azimuth));
    scene.lights.push_back({.name = "low sun",
                            .type = LightType::Directional,
                            .direction = direction,
                            .intensity = 8.0f});
    scene.cameras.push_back(mainCamera({-2.0f, 7.0f, 9.0f}, {0.5f, 0.0f, -1.0f}, 0.9f));
    return scene;
}

} // namespace penumbra::builtin
