// builtin:sheets — coloured sheets stacked over a plane (docs/translucency.md): three filters
// (red, green, blue; KHR_materials_transmission, thin-walled) and a grey half-covering curtain
// (alpha BLEND), overlapping so that the ground shows every product of them, and an opaque post
// beside them. Under a light of no size the truth is the product of the sheets each ray crosses,
// in closed form (kSheets); tests/test_translucent.cpp checks it for every light type.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {

Scene sheets() {
    Scene scene;
    scene.name = "sheets";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.75f, 0.75f, 0.75f});
    const float g = kSheetsGroundHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);
    for (const SheetSpec& sheet : kSheets) {
        const uint32_t m = mb.material(sheet.name, sheet.colour);
        Material& material = scene.materials[m];
        if (sheet.transmission > 0.0f) {
            material.transmission = sheet.transmission;
        } else {
            material.alphaMode = AlphaMode::Blend;
            material.baseColor.w = sheet.alpha;
        }
        const glm::vec2 lo = sheet.centre - sheet.halfSize, hi = sheet.centre + sheet.halfSize;
        const float y = sheet.height;
        mb.quad({lo.x, y, hi.y}, {hi.x, y, hi.y}, {hi.x, y, lo.y}, {lo.x, y, lo.y}, m);
    }
    const uint32_t post = mb.material("post", {0.6f, 0.45f, 0.25f});
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {2.6f, 0.9f, 1.8f}), {0.3f, 1.8f, 0.3f}),
           post);
    Light light = sun();
    light.direction = glm::normalize(kSheetsSunDirection);
    scene.lights.push_back(light);
    // From the side the shadows fall to, over the sheets' edge: the coloured ground beside them.
    scene.cameras.push_back(mainCamera({5.5f, 5.0f, 4.0f}, {1.4f, 0.0f, 0.0f}, 0.9f));
    return scene;
}

} // namespace penumbra::builtin
