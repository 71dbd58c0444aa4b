// The parts of a glTF asset Penumbra does not use: animations, skins, camera aspect ratios and
// material extensions. Their references are checked (a bad one is reported, never followed) and
// their presence is said once per class. (KHR_texture_transform on the base colour is used.)
#include "scene/gltf_validate.h"

#include <fmt/format.h>

namespace penumbra::gltf {

void reportUnusedParts(const tinygltf::Model& m, OnceWarnings& once) {
    const auto accessorRef = [&](const std::string& path, int i, bool required, const char* cls,
                                 const char* part) {
        if ((i < 0 && !required) || (i >= 0 && static_cast<size_t>(i) < m.accessors.size()))
            return;
        once.add(cls, path,
                 fmt::format("index {} is out of range ({} accessors); {} are ignored", i,
                             m.accessors.size(), part));
    };
    for (size_t a = 0; a < m.animations.size(); ++a) {
        const auto& anim = m.animations[a];
        for (size_t k = 0; k < anim.samplers.size(); ++k) {
            const std::string path = fmt::format("animations[{}].samplers[{}]", a, k);
            accessorRef(path + ".input", anim.samplers[k].input, true, "animation reference",
                        "animations");
            accessorRef(path + ".output", anim.samplers[k].output, true, "animation reference",
                        "animations");
        }
        for (size_t k = 0; k < anim.channels.size(); ++k) {
            const auto& c = anim.channels[k];
            const std::string path = fmt::format("animations[{}].channels[{}]", a, k);
            if (c.sampler < 0 || static_cast<size_t>(c.sampler) >= anim.samplers.size())
                once.add("animation reference", path + ".sampler",
                         fmt::format("index {} is out of range ({} samplers); animations "
                                     "are ignored",
                                     c.sampler, anim.samplers.size()));
            if (c.target_node >= 0 && static_cast<size_t>(c.target_node) >= m.nodes.size())
                once.add("animation reference", path + ".target.node",
                         fmt::format("index {} is out of range ({} nodes); animations are "
                                     "ignored",
                                     c.target_node, m.nodes.size()));
        }
    }
    if (!m.animations.empty())
        once.add("animations", "animations",
                 fmt::format("{} animation(s) ignored; the scene is drawn at rest",
                             m.animations.size()));
    for (size_t s = 0; s < m.skins.size(); ++s) {
        const auto& skin = m.skins[s];
        const std::string path = fmt::format("skins[{}]", s);
        accessorRef(path + ".inverseBindMatrices", skin.inverseBindMatrices, false,
                    "skin reference", "skins");
        for (size_t k = 0; k < skin.joints.size(); ++k)
            if (skin.joints[k] < 0 || static_cast<size_t>(skin.joints[k]) >= m.nodes.size())
                once.add("skin reference", fmt::format("{}.joints[{}]", path, k),
                         fmt::format("index {} is out of range ({} nodes); skins are ignored",
                                     skin.joints[k], m.nodes.size()));
        if (skin.skeleton >= 0 && static_cast<size_t>(skin.skeleton) >= m.nodes.size())
            once.add("skin reference", path + ".skeleton",
                     fmt::format("index {} is out of range ({} nodes); skins are ignored",
                                 skin.skeleton, m.nodes.size()));
    }
    if (!m.skins.empty())
        once.add("skins", "skins",
                 fmt::format("{} skin(s) ignored; skinned meshes are drawn in their bind pose",
                             m.skins.size()));
    for (size_t c = 0; c < m.cameras.size(); ++c)
        if (m.cameras[c].type == "perspective" && m.cameras[c].perspective.aspectRatio > 0)
            once.add("aspect ratio", fmt::format("cameras[{}].perspective.aspectRatio", c),
                     "ignored; the image's own width over height is used");
    for (size_t i = 0; i < m.materials.size(); ++i)
        for (const auto& [name, value] : m.materials[i].extensions)
            if (name != "KHR_materials_emissive_strength" && name != "KHR_materials_unlit")
                once.add("material extension " + name,
                         fmt::format("materials[{}].extensions.{}", i, name),
                         "not used; shadows and the lit image use the base colour only");
}

} // namespace penumbra::gltf
