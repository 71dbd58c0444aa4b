// builtin:figure — what real assets bring that boxes do not: a low-poly figure of smooth-shaded
// tubes and spheres (thin, curved parts whose facets disagree with their shading normals),
// raised arms, a thin ring and a thin curved shell, under a 2-degree sun at 40 degrees
// elevation. The bias corpus (docs/techniques.md "Bias") measures acne and leak here.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace penumbra::builtin {

Scene figure() {
    Scene scene;
    scene.name = "figure";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.68f});
    const uint32_t skin = mb.material("figure", {0.75f, 0.55f, 0.42f});
    const uint32_t metal = mb.material("ring", {0.55f, 0.55f, 0.6f});
    const uint32_t cloth = mb.material("shell", {0.3f, 0.45f, 0.65f});
    const float g = 6.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    // Legs, torso, neck, head: coarse on purpose (10-12 facets around).
    mb.tube({-0.18f, 0.0f, 0.0f}, {-0.14f, 0.95f, 0.02f}, 0.11f, skin, 10);
    mb.tube({0.18f, 0.0f, 0.0f}, {0.14f, 0.95f, -0.02f}, 0.11f, skin, 10);
    mb.sphere({0.0f, 1.3f, 0.0f}, 0.38f, skin, 12, 8);
    mb.tube({0.0f, 1.6f, 0.0f}, {0.0f, 1.82f, 0.0f}, 0.07f, skin, 8);
    mb.sphere({0.0f, 2.0f, 0.02f}, 0.2f, skin, 10, 6);
    // Arms: one raised towards the sun, one held forward; thin (radius 5 cm).
    mb.tube({-0.36f, 1.5f, 0.0f}, {-0.95f, 2.1f, 0.25f}, 0.05f, skin, 8);
    mb.tube({0.36f, 1.5f, 0.0f}, {0.75f, 1.25f, 0.6f}, 0.05f, skin, 8);
    // A thin ring held out at the forward arm's hand, and another lying on the ground.
    mb.torus({0.85f, 1.25f, 0.85f}, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)), 0.28f, 0.025f,
             metal, 28, 8);
    mb.torus({-1.4f, 0.04f, 1.0f}, {0.0f, 1.0f, 0.0f}, 0.45f, 0.04f, metal, 32, 8);
    // A thin curved shell (a quarter of a tube 2 cm thick) leaning behind the figure.
    const glm::mat4 shell = glm::rotate(glm::translate(glm::mat4(1.0f), {1.5f, 0.0f, -0.9f}),
                                        glm::radians(25.0f), {0, 1, 0});
    const float pi = 3.14159265358979f;
    const int pieces = 9;
    for (int i = 0; i < pieces; ++i) {
        const float a0 = 0.5f * pi * float(i) / pieces, a1 = 0.5f * pi * float(i + 1) / pieces;
        const auto at = [&](float a, float r, float y) {
            return glm::vec3(shell * glm::vec4(r * std::cos(a), y, -r * std::sin(a), 1.0f));
        };
        // Each piece a thin box through four corners: keeps the shell watertight per piece.
        const glm::vec3 mid = 0.5f * (at(a0, 1.0f, 0.0f) + at(a1, 1.0f, 0.0f));
        const glm::vec3 along = at(a1, 1.0f, 0.0f) - at(a0, 1.0f, 0.0f);
        const glm::vec3 out = glm::normalize(mid - glm::vec3(shell * glm::vec4(0, 0, 0, 1)));
        glm::mat4 box(1.0f);
        box[0] = glm::vec4(along * 1.02f, 0.0f);
        box[1] = glm::vec4(0.0f, 1.4f, 0.0f, 0.0f);
        box[2] = glm::vec4(out * 0.02f, 0.0f);
        box[3] = glm::vec4(mid + glm::vec3(0.0f, 0.7f, 0.0f), 1.0f);
        mb.box(box, cloth);
    }
    Light light = sun();
    light.direction = glm::normalize(glm::vec3(0.55f, -0.64f, -0.53f)); // 40 degrees up
    light.angularDiameter = 2.0f;
    scene.lights.push_back(light);
    scene.cameras.push_back(mainCamera({-1.2f, 2.4f, 4.6f}, {0.1f, 1.0f, 0.0f}, 0.75f, 40.0f));
    return scene;
}

} // namespace penumbra::builtin
