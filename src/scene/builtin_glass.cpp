// builtin:glass — stained glass over a floor (docs/translucency.md): a skylight of six coloured
// panes (KHR_materials_transmission, thin-walled) in an opaque lead frame on four posts, and a
// block of tinted glass (KHR_materials_volume) on the floor beside it. Under a light of no size
// each pane's shadow is its own colour and the block's its tint times its attenuation over its
// thickness (kGlassPanes, kGlassBlock); tests/test_translucent_scenes.cpp checks both against the
// truth for every light type.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::builtin {

Scene glass() {
    Scene scene;
    scene.name = "glass";
    MeshBuilder mb(scene);
    const uint32_t floor = mb.material("floor", {0.8f, 0.78f, 0.74f});
    const float g = kGlassFloorHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, floor);

    const float y = kGlassHeight, s = kGlassPaneSize;
    glm::vec2 lo(1e9f), hi(-1e9f);
    for (const PaneSpec& pane : kGlassPanes) {
        const uint32_t m = mb.material(pane.name, pane.colour);
        scene.materials[m].transmission = 1.0f;
        const glm::vec2 a = pane.corner, b = pane.corner + glm::vec2(s);
        mb.quad({a.x, y, b.y}, {b.x, y, b.y}, {b.x, y, a.y}, {a.x, y, a.y}, m);
        lo = glm::min(lo, a), hi = glm::max(hi, b);
    }
    // The lead: a bar along every pane edge (shared edges once), and a post under each corner.
    const uint32_t lead = mb.material("lead", {0.12f, 0.12f, 0.13f});
    for (float x = lo.x; x <= hi.x + 0.5f * s; x += s)
        mb.beam({x, y, lo.y}, {x, y, hi.y}, kGlassLead, lead);
    for (float z = lo.y; z <= hi.y + 0.5f * s; z += s)
        mb.beam({lo.x, y, z}, {hi.x, y, z}, kGlassLead, lead);
    for (const glm::vec2 post : {lo, glm::vec2(hi.x, lo.y), hi, glm::vec2(lo.x, hi.y)})
        mb.beam({post.x, 0.0f, post.y}, {post.x, y, post.y}, kGlassPost, lead);

    const GlassBlockSpec& block = kGlassBlock;
    const uint32_t m = mb.material("glass block", block.colour);
    Material& glassBlock = scene.materials[m];
    glassBlock.transmission = 1.0f;
    glassBlock.thickness = block.size;
    glassBlock.attenuationDistance = block.attenuationDistance;
    glassBlock.attenuationColor = block.attenuationColor;
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), block.centre), glm::vec3(block.size)), m);

    Light light = sun();
    light.direction = glm::normalize(kGlassSunDirection);
    scene.lights.push_back(light);
    // Below the skylight, towards where its colours fall, the block to the right.
    scene.cameras.push_back(mainCamera({-1.8f, 1.9f, 4.6f}, {1.3f, 0.0f, 0.5f}, 0.9f));
    return scene;
}

} // namespace penumbra::builtin
