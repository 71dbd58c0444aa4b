// builtin:field — a large outdoor scene for cascaded shadow maps: an 800-unit ground under a
// low sun, and small objects from 2 to 180 units ahead of the camera (posts, boxes, balls, fence
// rails, a few tall masts far away), so that one shadow map over the whole scene gives each
// nearby object a handful of texels while the camera sees it over hundreds of pixels.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace penumbra::builtin {

Scene field() {
    Scene scene;
    scene.name = "field";
    MeshBuilder mb(scene);
    const uint32_t grass = mb.material("ground", {0.45f, 0.55f, 0.35f});
    const uint32_t wood = mb.material("wood", {0.6f, 0.45f, 0.25f});
    const uint32_t stone = mb.material("stone", {0.65f, 0.63f, 0.6f});
    const uint32_t red = mb.material("red", {0.75f, 0.2f, 0.15f});
    const float g = kFieldHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, grass);
    // Objects at distances growing by 15% from 2 to about 180 units, left and right of the view
    // axis in turn, sized a little larger with distance (a post, a box, a ball, a fence panel).
    int k = 0;
    for (float d = 2.0f; d <= kFieldFarthest; d *= 1.15f, ++k) {
        const float side = (k % 2 == 0 ? -1.0f : 1.0f) * (0.6f + 0.12f * d);
        const glm::vec3 at(side, 0.0f, -d);
        const float s = 0.25f + 0.02f * d;
        switch (k % 4) {
        case 0:
            mb.beam(at, at + glm::vec3(0, 6.0f * s, 0), 0.4f * s, wood);
            break;
        case 1:
            mb.box(glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), at + glm::vec3(0, s, 0)),
                                          0.4f * static_cast<float>(k), glm::vec3(0, 1, 0)),
                              glm::vec3(2.0f * s)),
                   stone);
            break;
        case 2:
            mb.sphere(at + glm::vec3(0, 1.6f * s, 0), s, red, 32, 16);
            break;
        default:
            for (int rail = 0; rail < 2; ++rail) {
                const float y = (1.0f + 1.4f * static_cast<float>(rail)) * s;
                mb.beam(at + glm::vec3(-2.0f * s, y, 0), at + glm::vec3(2.0f * s, y, 0), 0.25f * s,
                        wood);
            }
            for (float x : {-2.0f, 0.0f, 2.0f})
                mb.beam(at + glm::vec3(x * s, 0, 0), at + glm::vec3(x * s, 3.0f * s, 0), 0.3f * s,
                        wood);
            break;
        }
    }
    // Masts far off to the sides: long shadows across the middle distance.
    for (float x : {-60.0f, 45.0f})
        mb.beam({x, 0, -150.0f}, {x, 30.0f, -150.0f}, 1.0f, stone);
    scene.lights.push_back({.name = "low sun",
                            .type = LightType::Directional,
                            .direction = glm::normalize(kFieldSunDirection),
                            .color = {1.0f, 0.95f, 0.85f},
                            .intensity = 2.0f,
                            .angularDiameter = 0.53f});
    scene.cameras.push_back(mainCamera({0.0f, 1.7f, 0.0f}, {0.0f, 0.2f, -12.0f}, 0.9f, 1000.0f));
    return scene;
}

} // namespace penumbra::builtin
