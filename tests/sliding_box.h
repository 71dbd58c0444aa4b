#pragma once
// An animated glTF asset for the CLI tests of time (compare --timeline, a sweep's `times`): a
// box that slides across the ground in the first second, with or without lights and camera.
#include "process.h"
#include "three_light_asset.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra::test {

// Float accessor of `type` over `values`, in a buffer of its own (base64 in a data URI) added
// to the asset `j`; its index.
inline int floatAccessor(nlohmann::json& j, const std::vector<float>& values, const char* type) {
    std::vector<uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    j["buffers"].push_back(
        {{"byteLength", bytes.size()},
         {"uri", "data:application/octet-stream;base64," + GltfBuilder::base64(bytes)}});
    j["bufferViews"].push_back({{"buffer", j["buffers"].size() - 1}, {"byteLength", bytes.size()}});
    const size_t per = std::string(type) == "SCALAR" ? 1 : 3;
    j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1},
                              {"componentType", 5126},
                              {"count", values.size() / per},
                              {"type", type}});
    return static_cast<int>(j["accessors"].size()) - 1;
}

// The ground and box under the three lights (`lit`; else the box alone without lights or
// camera: the automatic ones frame it); `animated`: the box (nodes[1], at rest at the origin)
// slides from x = 0.5 to 2.5 in the first second, then holds.
inline std::filesystem::path boxAsset(const std::filesystem::path& where, bool animated,
                                      bool lit = true) {
    std::filesystem::path file = where / "unlit.gltf";
    if (lit) {
        file = threeLightAsset(where);
    } else {
        GltfBuilder b;
        b.node({{"name", "empty"}}); // nodes[0]: the box alone is nodes[1], as above
        twoUnitBox(b, true);
        std::filesystem::create_directories(where);
        b.writeGltf(file);
    }
    if (!animated)
        return file;
    nlohmann::json j = nlohmann::json::parse(slurp(file));
    const int times = floatAccessor(j, {0.0f, 1.0f}, "SCALAR");
    j["accessors"][times]["min"] = {0.0};
    j["accessors"][times]["max"] = {1.0};
    const int places = floatAccessor(j, {0.5f, 0.0f, 0.0f, 2.5f, 0.0f, 0.0f}, "VEC3");
    j["animations"] = {
        {{"name", "slide"},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}},
         {"samplers", {{{"input", times}, {"output", places}}}}}};
    std::ofstream(file) << j.dump();
    return file;
}

} // namespace penumbra::test
