#pragma once
// A glTF asset for tests that must cover every light type at once: written by the CLI tests and
// the fault sweep.
#include "gltf_builder.h"

#include <filesystem>
#include <utility>
#include <vector>

namespace penumbra::test {

// A 2-unit box standing on y = 0, its triangles wound as groundAndBox has always had them, or
// reversed (`outward`: counter-clockwise seen from outside, a closed model as exporters write
// it).
inline void twoUnitBox(GltfBuilder& b, bool outward) {
    const int p = b.positions(
        {-1, 0, -1, 1, 0, -1, 1, 2, -1, -1, 2, -1, -1, 0, 1, 1, 0, 1, 1, 2, 1, -1, 2, 1});
    std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 3, 7, 0, 7, 4,
                                     1, 5, 6, 1, 6, 2, 3, 2, 6, 3, 6, 7, 0, 4, 5, 0, 5, 1};
    for (size_t t = 0; outward && t < indices.size(); t += 3)
        std::swap(indices[t + 1], indices[t + 2]);
    b.node({{"mesh", b.mesh(p, b.accessor(b.view(indices), 5123, 36, "SCALAR"))}});
}

// A 10 x 10 ground with a 2-unit box standing on it, no lights.
inline void groundAndBox(GltfBuilder& b) {
    b.ground();
    twoUnitBox(b, false);
}

// The ground and box under a sun, a spot and a point light.
inline std::filesystem::path threeLightAsset(const std::filesystem::path& where) {
    GltfBuilder b;
    groundAndBox(b);
    const auto light = [&](int index, nlohmann::json node) {
        node["extensions"] = {{"KHR_lights_punctual", {{"light", index}}}};
        b.node(std::move(node));
    };
    light(0, {{"rotation", {-0.6, 0.2, 0.1, 0.77}}});
    light(1, {{"translation", {3, 6, 3}}, {"rotation", {-0.38, 0.2, 0.08, 0.9}}});
    light(2, {{"translation", {-2, 3, 1}}});
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.j["extensions"] = {
        {"KHR_lights_punctual",
         {{"lights",
           {{{"type", "directional"}, {"intensity", 1.5}},
            {{"type", "spot"}, {"intensity", 40}, {"spot", {{"outerConeAngle", 0.7}}}},
            {{"type", "point"}, {"name", "bulb"}, {"intensity", 5}}}}}}};
    std::filesystem::create_directories(where);
    return b.writeGltf(where / "lights.gltf");
}

} // namespace penumbra::test
