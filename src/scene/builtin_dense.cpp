// builtin:dense — the raster passes' benchmark scene: about 100k triangles (24 finely tessellated
// spheres and 24 boxes on a ground) under one spot light, so that the shadow and G-buffer passes
// cost what they cost on real assets (the other built-in scenes hold a few thousand triangles).
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {

Scene dense() {
    Scene scene;
    scene.name = "dense";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.68f});
    const uint32_t colours[] = {
        mb.material("red", {0.75f, 0.2f, 0.15f}), mb.material("blue", {0.2f, 0.35f, 0.75f}),
        mb.material("green", {0.25f, 0.6f, 0.25f}), mb.material("sand", {0.7f, 0.6f, 0.4f})};
    const float g = kDenseHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    // A 6 x 4 grid; in each cell a sphere floating over a box turned a little, heights varying
    // so that shadows fall on the ground, on boxes and on other spheres.
    for (int row = 0; row < kDenseRows; ++row)
        for (int column = 0; column < kDenseColumns; ++column) {
            const int i = row * kDenseColumns + column;
            const glm::vec3 cell{-7.5f + 3.0f * static_cast<float>(column), 0.0f,
                                 -6.0f + 3.2f * static_cast<float>(row)};
            const float height = 0.4f + 0.25f * static_cast<float>((i * 7) % 5);
            glm::mat4 box = glm::translate(glm::mat4(1.0f), cell + glm::vec3(0, 0.5f * height, 0));
            box = glm::rotate(box, glm::radians(12.0f * static_cast<float>(i % 7)), {0, 1, 0});
            mb.box(glm::scale(box, glm::vec3(1.1f, height, 1.1f)), colours[(i + 1) % 4]);
            const float radius = 0.55f + 0.05f * static_cast<float>(i % 4);
            mb.sphere(cell +
                          glm::vec3(0.4f, height + radius + 0.3f * static_cast<float>(i % 3), 0.3f),
                      radius, colours[i % 4], kDenseSphereSlices, kDenseSphereStacks);
        }
    scene.lights.push_back(spotLight(kDenseSpotPosition, {0.0f, 0.0f, 0.5f}, 0.55f, 0.65f));
    scene.cameras.push_back(mainCamera({0.0f, 9.0f, 14.0f}, {0.0f, 0.5f, -0.5f}, 0.75f));
    return scene;
}

} // namespace penumbra::builtin
