// builtin:fan — an animated built-in (issue 59): a ceiling fan's three thin blades turning fast
// under a spot light, over a floor. The blades are kFanBladeThickness thick (thin casters: a
// bias or a blur that loses them loses the shadow) and turn once in kFanTurnSeconds, so that at
// 60 frames a second each frame moves them a large step: a fast caster. `--time T` poses it; any
// T is a pose (the turn is periodic), and the animation 'spin' is one turn long. The tests pose
// it from kFan* alone.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace penumbra::builtin {

float fanAngle(double time) {
    const double turns = time / kFanTurnSeconds;
    return static_cast<float>(2.0 * std::numbers::pi * (turns - std::floor(turns)));
}

Scene fan(double time) {
    Scene scene;
    scene.name = "fan";
    scene.animation = "spin";
    scene.animationDuration = static_cast<float>(kFanTurnSeconds);
    MeshBuilder mb(scene);
    const float g = kFanFloorHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("floor", {0.7f, 0.7f, 0.7f}));
    const uint32_t wood = mb.material("blades", {0.5f, 0.35f, 0.2f});
    const uint32_t metal = mb.material("hub", {0.6f, 0.6f, 0.62f});
    const glm::vec3 hub(0.0f, kFanHeight, 0.0f);
    mb.tube(hub + glm::vec3(0.0f, -0.1f, 0.0f), hub + glm::vec3(0.0f, 0.1f, 0.0f), 0.18f, metal,
            24);
    mb.tube(hub + glm::vec3(0.0f, 0.1f, 0.0f), {0.0f, kFanHeight + 1.5f, 0.0f}, 0.03f, metal);
    // Blade b points along angle + b * 120 degrees about +y (right-hand rule: x towards -z),
    // from the hub's rim to kFanBladeLength from the axis.
    for (int b = 0; b < 3; ++b) {
        const float angle = fanAngle(time) + float(b) * 2.0f * std::numbers::pi_v<float> / 3.0f;
        const float middle = 0.5f * (0.15f + kFanBladeLength);
        const glm::mat4 place =
            glm::rotate(glm::translate(glm::mat4(1.0f), hub), angle, glm::vec3(0, 1, 0)) *
            glm::scale(glm::translate(glm::mat4(1.0f), {middle, 0.0f, 0.0f}),
                       {kFanBladeLength - 0.15f, kFanBladeThickness, kFanBladeWidth});
        mb.box(place, wood);
    }
    // The spot above the fan, pointing straight down, and a ball on the floor under a blade's
    // sweep for the blades' shadows to cross.
    mb.sphere({1.2f, 0.3f, 0.8f}, 0.3f, metal);
    scene.lights.push_back({.name = "spot",
                            .type = LightType::Spot,
                            .position = kFanSpotPosition,
                            .direction = {0.0f, -1.0f, 0.0f},
                            .intensity = 40.0f,
                            .innerConeAngle = 0.7f,
                            .outerConeAngle = 0.85f,
                            .radius = 0.05f});
    scene.cameras.push_back(mainCamera({3.5f, 4.0f, 6.5f}, {0.0f, 1.0f, 0.0f}, 0.9f));
    return scene;
}

} // namespace penumbra::builtin
