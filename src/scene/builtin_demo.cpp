// builtin:demo — what `make demo` compares: the family's differences in one view. A sun 4
// degrees wide (eight times the real sun's), so that penumbrae are wide enough to see; a post
// leaning from the ground (contact hardening: its shadow sharp at its foot, soft at its tip); a
// ball floating high (a shadow that is mostly penumbra); a cube resting on the ground; and a
// small plate over a wide one (light bleeding: the variance-based maps' glow inside the wide
// plate's shadow). builtin:showcase stays as it is: tests and baselines use it.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {

Scene demo() {
    Scene scene;
    scene.name = "demo";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.68f});
    const uint32_t red = mb.material("ball", {0.75f, 0.2f, 0.15f});
    const uint32_t blue = mb.material("cube", {0.2f, 0.35f, 0.75f});
    const uint32_t wood = mb.material("post", {0.6f, 0.45f, 0.25f});
    const uint32_t plate = mb.material("plates", {0.3f, 0.45f, 0.65f});
    const float g = 12.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    mb.sphere({-3.2f, 3.4f, -0.6f}, 0.8f, red);
    glm::mat4 cube = glm::translate(glm::mat4(1.0f), {2.8f, 0.7f, 1.2f});
    mb.box(glm::scale(glm::rotate(cube, glm::radians(30.0f), {0, 1, 0}), glm::vec3(1.4f)), blue);
    mb.beam({-0.9f, 0.0f, 0.6f}, {0.3f, 3.2f, -0.4f}, 0.2f, wood);
    // Thin boxes (watertight, for second-depth): the wide plate low, the small one high over it.
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {1.2f, 0.9f, -3.2f}), {3.2f, 0.1f, 2.4f}),
           plate);
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0.1f, 3.4f, -3.9f}), {1.2f, 0.1f, 1.2f}),
           plate);
    mb.beam({2.4f, 0.0f, -2.6f}, {2.4f, 0.85f, -2.6f}, 0.12f, wood); // under the wide plate
    Light light = sun();
    light.direction = glm::normalize(glm::vec3(0.45f, -1.0f, 0.3f));
    light.angularDiameter = kDemoSunDegrees;
    scene.lights.push_back(light);
    scene.cameras.push_back(mainCamera({0.0f, 6.0f, 10.0f}, {0.0f, 0.8f, -1.0f}, 0.8f));
    return scene;
}

} // namespace penumbra::builtin
