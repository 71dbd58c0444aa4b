// builtin:town — an animated built-in (issue 59): a small town of houses and a tower under a sun
// that crosses the sky in kTownDaySeconds, rising low in the east (+x), highest at noon in the
// south (-z), setting low in the west. Its long morning and evening shadows sweep across the
// streets and climb the walls. `--time T` poses it; before 0 and after the day the ends hold,
// as a glTF animation's do. The tests pose it from kTown* alone.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace penumbra::builtin {

glm::vec3 townSunDirection(double time) {
    const double day = std::clamp(time / kTownDaySeconds, 0.0, 1.0);
    // The sun's angle along its arc, from kTownSunriseAngle above the east to as far above the
    // west; the arc's plane leans kTownNoonElevation from the horizon towards the south.
    const double arc = kTownSunriseAngle + (std::numbers::pi - 2.0 * kTownSunriseAngle) * day;
    const glm::dvec3 towardsSun(std::cos(arc), std::sin(arc) * std::sin(kTownNoonElevation),
                                -std::sin(arc) * std::cos(kTownNoonElevation));
    return glm::vec3(-towardsSun); // the direction the light travels
}

Scene town(double time) {
    Scene scene;
    scene.name = "town";
    scene.animation = "day";
    scene.animationDuration = static_cast<float>(kTownDaySeconds);
    MeshBuilder mb(scene);
    const float g = kTownHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("street", {0.45f, 0.45f, 0.43f}));
    const uint32_t walls = mb.material("walls", {0.75f, 0.68f, 0.58f});
    const uint32_t roofs = mb.material("roofs", {0.55f, 0.25f, 0.2f});
    // Four blocks of four houses, streets between them; heights from a fixed pattern.
    constexpr float kHeights[16] = {2.0f, 3.0f, 2.5f, 4.0f, 3.5f, 2.0f, 5.0f, 2.5f,
                                    3.0f, 4.5f, 2.0f, 3.0f, 2.5f, 3.5f, 2.0f, 4.0f};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            const float x = -6.0f + 4.0f * float(i), z = -6.0f + 4.0f * float(k);
            if ((i == 1 || i == 2) && (k == 1 || k == 2))
                continue; // the square, where the tower stands
            const float h = kHeights[4 * i + k];
            mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {x, h / 2, z}), {2.4f, h, 2.4f}),
                   walls);
            mb.box(
                glm::scale(glm::translate(glm::mat4(1.0f), {x, h + 0.15f, z}), {2.7f, 0.3f, 2.7f}),
                roofs);
        }
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, kTownTowerHeight / 2, 0.0f}),
                      {1.2f, kTownTowerHeight, 1.2f}),
           walls);
    mb.tube({0.0f, kTownTowerHeight, 0.0f}, {0.0f, kTownTowerHeight + 2.0f, 0.0f}, 0.08f, roofs);
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = townSunDirection(time),
                            .color = {1.0f, 0.95f, 0.88f},
                            .intensity = 2.0f,
                            .angularDiameter = 0.53f});
    scene.cameras.push_back(mainCamera({7.0f, 16.0f, 22.0f}, {0.0f, 1.0f, 0.0f}, 0.8f));
    return scene;
}

} // namespace penumbra::builtin
