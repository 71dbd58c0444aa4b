// builtin:resting — objects resting on a 24-unit plane, seen obliquely from above: boxes of two
// sizes (one turned), a sphere touching the plane at one point, an upright cylinder and a thin
// slab lying flat, under a 0.5-degree sun at 45 degrees elevation. Every shadow starts at its
// caster's foot: where a shadow map's bias detaches it (peter-panning), the truth keeps a contact
// shadow. The contact layer's scene (docs/techniques.md, "Contact shadows"); the tests light it
// with a spot and a point light too.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {

Scene restingGeometry() {
    Scene scene;
    scene.name = "resting";
    MeshBuilder mb(scene);
    const float g = 12.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("plane", {0.7f, 0.7f, 0.7f}));
    const uint32_t grey = mb.material("objects", {0.6f, 0.55f, 0.5f});
    mb.box(glm::translate(glm::mat4(1.0f), {-1.6f, 0.5f, 0.2f}), grey);
    mb.box(glm::rotate(glm::translate(glm::mat4(1.0f), {1.4f, 0.3f, -1.2f}), 0.6f,
                       glm::vec3(0.0f, 1.0f, 0.0f)) *
               glm::scale(glm::mat4(1.0f), glm::vec3(0.8f, 0.6f, 0.5f)),
           grey);
    mb.sphere({0.3f, 0.6f, 1.3f}, 0.6f, grey);
    mb.tube({-0.2f, 0.0f, -2.0f}, {-0.2f, 1.6f, -2.0f}, 0.15f, grey, 16);
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {2.2f, 0.04f, 1.4f}),
                      glm::vec3(1.0f, 0.08f, 0.7f)),
           grey);
    scene.cameras.push_back({.name = "above",
                             .position = {0.6f, 3.4f, 4.6f},
                             .target = {0.2f, 0.2f, -0.3f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

Scene resting() {
    Scene scene = restingGeometry();
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = glm::normalize(glm::vec3(0.5f, -0.7f, -0.4f)),
                            .intensity = 3.0f,
                            .angularDiameter = 0.5f});
    return scene;
}

} // namespace penumbra::builtin
