// builtin:bleeding — occluders stacked along the light: a small plate 4 units up over a wide
// plate 1 unit up, over the ground. The shadow map sees both plates; where a filter kernel
// straddles the small plate's edge, it mixes depths 3 units apart, and for the ground in the
// wide plate's umbra the variance that makes is what variance-based maps (vsm) turn into light
// that should not be there: the small plate's outline glows inside the wide plate's shadow
// (light bleeding). The exponential warps (evsm) and moment maps are measured against it.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {

Scene bleeding() {
    Scene scene;
    scene.name = "bleeding";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.68f});
    const uint32_t wide = mb.material("wide plate", {0.3f, 0.45f, 0.65f});
    const uint32_t small = mb.material("small plate", {0.7f, 0.3f, 0.2f});
    const float g = 10.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    // Thin boxes rather than quads: watertight, so second-depth works here too.
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}), {6.0f, 0.1f, 6.0f}),
           wide);
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {-0.7f, 4.0f, -0.5f}), {2.0f, 0.1f, 2.0f}),
           small);
    // A post from the ground to the wide plate: contact, inside its shadow.
    mb.box(
        glm::scale(glm::translate(glm::mat4(1.0f), {-0.4f, 0.475f, -0.3f}), {0.15f, 0.95f, 0.15f}),
        small);
    Light light = sun();
    light.direction = glm::normalize(glm::vec3(0.25f, -1.0f, 0.15f));
    scene.lights.push_back(light);
    // Low, looking under the wide plate at the ground in its shadow.
    scene.cameras.push_back(mainCamera({0.4f, 0.55f, 6.5f}, {0.0f, 0.15f, 0.0f}, 0.9f));
    return scene;
}

} // namespace penumbra::builtin
