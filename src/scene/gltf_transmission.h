#pragma once
// KHR_materials_transmission and KHR_materials_volume read from a material's JSON
// (gltf_transmission.cpp).
#include "penumbra/scene.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace penumbra::gltf {

// What the material's textures are read with: the scene texture of each glTF texture (-1: none)
// and the coordinates the base colour's texture left on the vertices.
struct TransmissionTextures {
    const std::vector<int32_t>& sceneTextureOf;
    int baseTexCoord = 0;
    bool baseTransformed = false; // KHR_texture_transform on the base colour's texture
};

// Sets `out`'s transmission and volume from `material` (at JSON path `path`); InputError for a
// value outside the extensions' ranges. A transmission texture read with other coordinates than
// the base colour's is left out with a warning (the vertices hold one set).
void readTransmission(const std::filesystem::path& file, const std::string& path,
                      const nlohmann::json& material, const TransmissionTextures& textures,
                      Material& out, const std::function<void(const std::string&)>& warn);

} // namespace penumbra::gltf
