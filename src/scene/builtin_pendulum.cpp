// builtin:pendulum — an animated built-in (issue 59): a ball on a rod swinging over a floor, its
// lowest point a hand's width above it, under a small sun nearly overhead and a spot from the
// side. At the bottom of the swing the ball's shadow touches its contact; at the ends it
// detaches and stretches. `--time T` poses it; any T is a pose (the swing is periodic), and the
// animation 'swing' is one period long. The tests pose it from kPendulum* alone.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <cmath>
#include <numbers>

namespace penumbra::builtin {

glm::vec3 pendulumBob(double time) {
    const double angle =
        kPendulumAmplitude * std::cos(2.0 * std::numbers::pi * time / kPendulumPeriod);
    return kPendulumPivot + kPendulumLength * glm::vec3(static_cast<float>(std::sin(angle)),
                                                        -static_cast<float>(std::cos(angle)), 0.0f);
}

Scene pendulum(double time) {
    Scene scene;
    scene.name = "pendulum";
    scene.animation = "swing";
    scene.animationDuration = static_cast<float>(kPendulumPeriod);
    MeshBuilder mb(scene);
    const float g = kPendulumFloorHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("floor", {0.7f, 0.7f, 0.7f}));
    const uint32_t metal = mb.material("pendulum", {0.55f, 0.5f, 0.45f});
    const glm::vec3 bob = pendulumBob(time);
    mb.sphere(bob, kPendulumBobRadius, metal);
    mb.tube(kPendulumPivot, bob, 0.03f, metal, 12); // the rod, pivot to the ball's centre
    // The frame it hangs from: two posts and a beam along z, clear of the swing's plane.
    const float top = kPendulumPivot.y, side = 1.2f;
    mb.tube({0.0f, 0.0f, -side}, {0.0f, top, -side}, 0.06f, metal, 12);
    mb.tube({0.0f, 0.0f, side}, {0.0f, top, side}, 0.06f, metal, 12);
    mb.tube({0.0f, top, -side}, {0.0f, top, side}, 0.05f, metal, 12);
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = glm::normalize(kPendulumSunDirection),
                            .intensity = 2.5f,
                            .angularDiameter = 1.0f});
    scene.lights.push_back({.name = "spot",
                            .type = LightType::Spot,
                            .position = {-5.0f, 4.5f, 3.5f},
                            .direction = glm::normalize(glm::vec3(5.0f, -4.5f, -3.5f)),
                            .intensity = 60.0f,
                            .innerConeAngle = 0.45f,
                            .outerConeAngle = 0.6f,
                            .radius = 0.1f});
    scene.cameras.push_back({.name = "side",
                             .position = {2.0f, 3.4f, 10.0f},
                             .target = {0.0f, 1.8f, 0.0f},
                             .yfov = 0.8f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

} // namespace penumbra::builtin
