#pragma once
// The boundary rows of the glTF loader's bounds tests (test_gltf_bounds.cpp: accessors, sparse
// accessors, primitives, materials, nodes, cameras, lights, caps, images;
// test_gltf_bounds_container.cpp: the container, URIs, JSON references, bufferViews): each row
// builds two assets that differ only in the checked value, the last valid one (it loads) and the
// first invalid one (refused by name). A test that only tries a value far out of range cannot
// tell `<` from `<=`; an off-by-one there turns a crafted file into a heap overflow.
//
// A few checks have no loadable asset on their valid side (a GLB of exactly 20 bytes passes the
// header check but has no JSON): those rows name the later check that refuses the edge instead,
// which still proves the first check let the edge value through.
#include "core/image_io.h"
#include "expect_refused.h"
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra::test::bounds {

namespace fs = std::filesystem;
using J = nlohmann::json;

inline fs::path dir(const std::string& name) {
    return scratchDir("bounds", name);
}

inline void writeBytes(const fs::path& file, const std::vector<uint8_t>& bytes) {
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

inline void setU32(std::vector<uint8_t>& bytes, size_t at, uint32_t value) {
    for (int k = 0; k < 4; ++k)
        bytes[at + k] = uint8_t(value >> (8 * k));
}

inline uint32_t u32At(const std::vector<uint8_t>& bytes, size_t at) {
    return bytes[at] | bytes[at + 1] << 8 | bytes[at + 2] << 16 | uint32_t(bytes[at + 3]) << 24;
}

// The last valid index into `array` (its size - 1), or on the invalid side the first index
// past it (its size).
inline size_t lastOr(const J& array, bool past) {
    return array.size() - 1 + (past ? 1 : 0);
}

// The smallest float above zero, and the last float below `x`: the edges of open intervals.
inline const double kTinyPositive = std::numeric_limits<float>::denorm_min();
inline double floatBelow(float x) {
    return std::nextafter(x, -std::numeric_limits<float>::infinity());
}
inline double floatAbove(float x) {
    return std::nextafter(x, std::numeric_limits<float>::infinity());
}

inline std::vector<uint8_t> png(uint32_t width, uint32_t height) {
    return encodePng(width, height, 4, std::vector<uint8_t>(size_t(width) * height * 4, 255));
}

// floatingQuad with the quad textured: TEXCOORD_0, material 0 (alpha-tested) whose base colour
// texture 0 reads a 2x2 PNG (image 0, the last bufferView) through sampler 0.
inline GltfBuilder textured() {
    GltfBuilder b = floatingQuad();
    const int uv = b.accessor(b.view(std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}), 5126, 4, "VEC2");
    auto& prim = b.j["meshes"][1]["primitives"][0];
    prim["attributes"]["TEXCOORD_0"] = uv;
    prim["material"] = 0;
    b.j["images"] = J::array({{{"bufferView", b.view(png(2, 2))}, {"mimeType", "image/png"}}});
    b.j["samplers"] = J::array({{{"magFilter", 9728}}});
    b.j["textures"] = J::array({{{"source", 0}, {"sampler", 0}}});
    b.j["materials"] = J::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                  {"alphaMode", "MASK"}}});
    return b;
}

// The ground quad whose POSITION accessor (0) has sparse substitutes: `indices` (uint16) in
// bufferView 0, the values in bufferView 1 (the ground's own 4 corners and one more, so any
// substitution keeps a triangle).
inline GltfBuilder sparseGround(const std::vector<uint16_t>& indices, int count) {
    GltfBuilder b;
    b.view(indices);
    b.view(std::vector<float>{-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5, -5, 0, 5});
    b.ground();
    b.j["accessors"][0]["sparse"] = {{"count", count},
                                     {"indices", {{"bufferView", 0}, {"componentType", 5123}}},
                                     {"values", {{"bufferView", 1}}}};
    return b;
}

// A bufferView over the first `length` bytes of buffer 0 that no accessor uses: its own checks
// still run.
inline int spareView(GltfBuilder& b, size_t length) {
    while (b.bin.size() < length)
        b.bin.push_back(0);
    b.j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", length}});
    return static_cast<int>(b.j["bufferViews"].size() - 1);
}

// A GLB file image: the header, the JSON chunk (padded with spaces) and, unless `bin` is empty,
// a BIN chunk (padded with zeros).
inline std::vector<uint8_t> glb(std::string json, std::vector<uint8_t> bin) {
    while (json.size() % 4)
        json += ' ';
    while (bin.size() % 4)
        bin.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&out](uint32_t v) {
        for (int k = 0; k < 4; ++k)
            out.push_back(uint8_t(v >> (8 * k)));
    };
    const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
    u32(0x46546C67), u32(2), u32(uint32_t(total));
    u32(uint32_t(json.size())), u32(0x4E4F534A);
    for (char c : json)
        out.push_back(uint8_t(c));
    if (!bin.empty()) {
        u32(uint32_t(bin.size())), u32(0x004E4942);
        for (uint8_t byte : bin)
            out.push_back(byte);
    }
    return out;
}

// floatingQuad as a GLB whose buffer 0 is the BIN chunk (declared at exactly its length).
inline std::vector<uint8_t> glbWithBin() {
    GltfBuilder b = floatingQuad();
    while (b.bin.size() % 4)
        b.bin.push_back(0);
    b.j["buffers"] = J::array({{{"byteLength", b.bin.size()}}});
    return glb(b.j.dump(), b.bin);
}

// floatingQuad as a GLB of one JSON chunk (the buffer a data URI) that ends in padding spaces.
inline std::vector<uint8_t> glbJsonOnly() {
    GltfBuilder b = floatingQuad();
    b.j["buffers"] =
        J::array({{{"byteLength", b.bin.size()},
                   {"uri", "data:application/octet-stream;base64," + GltfBuilder::base64(b.bin)}}});
    return glb(b.j.dump() + " ", {});
}

struct Asset {
    fs::path file;
    SceneLoadOptions options{};
};

struct Boundary {
    const char* name; // the check
    // Writes the asset into `d`: the last valid value, or (past) the first invalid one.
    std::function<Asset(const fs::path& d, bool past)> make;
    std::string refusal;     // in the message that refuses the first invalid value
    std::string edgeRefusal; // empty: the last valid value loads; else the later check's message
};

// gtest names a failing row by its check, not by its bytes.
inline void PrintTo(const Boundary& row, std::ostream* os) {
    *os << row.name;
}

using Change = std::function<void(GltfBuilder&, bool past)>;

// A row that edits the JSON (or bytes) of a base asset and writes it as .gltf.
inline std::function<Asset(const fs::path&, bool)> gltf(std::function<GltfBuilder()> base,
                                                        Change change) {
    return [base, change](const fs::path& d, bool past) {
        GltfBuilder b = base();
        change(b, past);
        return Asset{b.writeGltf(d / "a.gltf")};
    };
}

// A row that edits the bytes of a GLB.
inline std::function<Asset(const fs::path&, bool)>
glbFile(std::function<std::vector<uint8_t>()> base,
        std::function<void(std::vector<uint8_t>&, bool past)> change) {
    return [base, change](const fs::path& d, bool past) {
        std::vector<uint8_t> bytes = base();
        change(bytes, past);
        writeBytes(d / "a.glb", bytes);
        return Asset{d / "a.glb"};
    };
}

// A second buffer, unused, holding a data URI: its base64 is checked all the same.
inline Change dataUri(std::string edge, std::string past, size_t byteLength) {
    return [=](GltfBuilder& b, bool isPast) {
        b.j["buffers"] =
            J::array({J::object(),
                      {{"uri", "data:application/octet-stream;base64," + (isPast ? past : edge)},
                       {"byteLength", byteLength}}});
    };
}

// The 2x2 PNG of textured(), edited, as image 0.
inline Change pngBytes(std::function<void(std::vector<uint8_t>&, bool past)> edit) {
    return [edit](GltfBuilder& b, bool past) {
        std::vector<uint8_t> image = png(2, 2);
        edit(image, past);
        b.j["images"][0]["bufferView"] = b.view(image);
    };
}

inline Change cameraValue(const char* key, double edge, double past) {
    return [=](GltfBuilder& b, bool isPast) {
        b.j["cameras"][0]["perspective"][key] = isPast ? past : edge;
    };
}

inline Change lightValue(std::function<J&(J& light)> field, double edge, double past) {
    return [=](GltfBuilder& b, bool isPast) {
        field(b.j["extensions"]["KHR_lights_punctual"]["lights"][0]) = isPast ? past : edge;
    };
}

class GltfBounds : public ::testing::TestWithParam<Boundary> {};

} // namespace penumbra::test::bounds
