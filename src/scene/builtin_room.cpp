// builtin:room — a point light among objects on all sides: a cut-away room (floor, ceiling,
// three walls; the fourth side open to the camera) with a bulb in the middle, so the camera sees
// surfaces lit through all six faces of the light's cube: the floor below (-y) and, farther out,
// through the four side faces; the ceiling (+y); the walls (-x, +x, -z); the floor towards the
// camera (+z). Objects around the bulb cast a shadow through each face: a hanging lamp shade
// onto the ceiling, a shelf onto the left wall, a cabinet onto the right wall, a sphere and a
// chair-like stack onto the floor and the back wall, a pillar onto the floor in front.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {
namespace {

glm::mat4 boxAt(const glm::vec3& center, const glm::vec3& size, float yawDegrees = 0.0f) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), center);
    m = glm::rotate(m, glm::radians(yawDegrees), {0, 1, 0});
    return glm::scale(m, size);
}

} // namespace

Scene room() {
    Scene scene;
    scene.name = "room";
    MeshBuilder mb(scene);
    const uint32_t plaster = mb.material("plaster", {0.75f, 0.73f, 0.7f});
    const uint32_t floorWood = mb.material("floor", {0.55f, 0.45f, 0.35f});
    const uint32_t fabric = mb.material("fabric", {0.25f, 0.4f, 0.6f});
    const uint32_t metal = mb.material("metal", {0.5f, 0.5f, 0.52f});
    const uint32_t red = mb.material("red", {0.7f, 0.2f, 0.15f});
    const float w = kRoomHalfWidth, h = kRoomHeight, back = -kRoomHalfWidth;
    const float front = kRoomFloorFront; // the floor runs out of the room towards the camera
    // Floor, ceiling (over the room only) and three walls, all facing inwards.
    mb.quad({-w, 0, front}, {w, 0, front}, {w, 0, back}, {-w, 0, back}, floorWood);
    mb.quad({-w, h, back}, {w, h, back}, {w, h, kRoomCeilingFront}, {-w, h, kRoomCeilingFront},
            plaster);
    mb.quad({-w, 0, back}, {w, 0, back}, {w, h, back}, {-w, h, back}, plaster);
    mb.quad({-w, 0, kRoomCeilingFront}, {-w, 0, back}, {-w, h, back}, {-w, h, kRoomCeilingFront},
            plaster);
    mb.quad({w, 0, back}, {w, 0, kRoomCeilingFront}, {w, h, kRoomCeilingFront}, {w, h, back},
            plaster);
    const glm::vec3 bulb = kRoomLightPosition;
    // A lamp shade above the bulb (its shadow on the ceiling) on a thin rod.
    mb.box(boxAt(bulb + glm::vec3(0.3f, 1.1f, 0.2f), {0.9f, 0.08f, 0.7f}, 20.0f), metal);
    mb.beam(bulb + glm::vec3(0.3f, 1.15f, 0.2f), {bulb.x + 0.3f, h, bulb.z + 0.2f}, 0.04f, metal);
    // A shelf on the left wall, a cabinet against the right wall.
    mb.box(boxAt({-w + 0.4f, 2.6f, -1.0f}, {0.8f, 0.1f, 2.2f}), floorWood);
    mb.box(boxAt({w - 0.5f, 1.1f, -2.0f}, {1.0f, 2.2f, 1.4f}), floorWood);
    // A sphere and a stool between the bulb and the back wall.
    mb.sphere({-1.6f, 0.9f, -3.2f}, 0.9f, red);
    mb.box(boxAt({1.4f, 0.5f, -3.6f}, {1.0f, 1.0f, 1.0f}, 30.0f), fabric);
    mb.beam({1.4f, 1.0f, -3.6f}, {1.6f, 2.6f, -4.1f}, 0.12f, metal);
    // Beside the bulb, low: a small box whose shadow falls across the floor.
    mb.box(boxAt({-2.2f, 0.35f, 0.6f}, {0.7f, 0.7f, 0.7f}, -15.0f), fabric);
    // In front, towards the open side: a pillar and a ball, shadows on the floor towards the
    // camera (the +z face).
    mb.beam({0.8f, 0.0f, 2.6f}, {0.8f, 3.0f, 2.6f}, 0.3f, plaster);
    mb.sphere({-1.0f, 0.45f, 3.3f}, 0.45f, red);
    scene.lights.push_back({.name = "bulb",
                            .type = LightType::Point,
                            .position = bulb,
                            .color = {1.0f, 0.9f, 0.75f},
                            .intensity = 14.0f,
                            .radius = 0.1f});
    scene.cameras.push_back(mainCamera({0.5f, 2.4f, 12.5f}, {0.0f, 1.9f, -1.0f}, 0.85f));
    return scene;
}

} // namespace penumbra::builtin
