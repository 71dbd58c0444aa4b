// The parts of a glTF asset Penumbra does not use: camera aspect ratios and material extensions
// (all but unlit, emissive strength, transmission and volume), each said once per class.
// (Animations are read in gltf_animation.cpp, skins in gltf_skin.cpp; KHR_texture_transform on the
// base colour is used.)
#include "scene/gltf_validate.h"

#include <fmt/format.h>

namespace penumbra::gltf {

void reportUnusedParts(const tinygltf::Model& m, OnceWarnings& once) {
    for (size_t c = 0; c < m.cameras.size(); ++c)
        if (m.cameras[c].type == "perspective" && m.cameras[c].perspective.aspectRatio > 0)
            once.add("aspect ratio", fmt::format("cameras[{}].perspective.aspectRatio", c),
                     "ignored; the image's own width over height is used");
    for (size_t i = 0; i < m.materials.size(); ++i)
        for (const auto& [name, value] : m.materials[i].extensions)
            if (name != "KHR_materials_emissive_strength" && name != "KHR_materials_unlit" &&
                name != "KHR_materials_transmission" && name != "KHR_materials_volume")
                once.add("material extension " + name,
                         fmt::format("materials[{}].extensions.{}", i, name),
                         "not used; shadows and the lit image use the base colour only");
}

} // namespace penumbra::gltf
