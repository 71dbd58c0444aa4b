// Every bounds and limit check of the glTF loader, at its exact boundary: each row builds two
// assets that differ only in the checked value, the last valid one (it loads) and the first
// invalid one (refused by name). A test that only tries a value far out of range cannot tell
// `<` from `<=`; an off-by-one there turns a crafted file into a heap overflow.
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

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

fs::path dir(const std::string& name) {
    return scratchDir("bounds", name);
}

void writeBytes(const fs::path& file, const std::vector<uint8_t>& bytes) {
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void setU32(std::vector<uint8_t>& bytes, size_t at, uint32_t value) {
    for (int k = 0; k < 4; ++k)
        bytes[at + k] = uint8_t(value >> (8 * k));
}

uint32_t u32At(const std::vector<uint8_t>& bytes, size_t at) {
    return bytes[at] | bytes[at + 1] << 8 | bytes[at + 2] << 16 | uint32_t(bytes[at + 3]) << 24;
}

// The last valid index into `array` (its size - 1), or on the invalid side the first index
// past it (its size).
size_t lastOr(const J& array, bool past) {
    return array.size() - 1 + (past ? 1 : 0);
}

// The smallest float above zero, and the last float below `x`: the edges of open intervals.
const double kTinyPositive = std::numeric_limits<float>::denorm_min();
double floatBelow(float x) {
    return std::nextafter(x, -std::numeric_limits<float>::infinity());
}
double floatAbove(float x) {
    return std::nextafter(x, std::numeric_limits<float>::infinity());
}

std::vector<uint8_t> png(uint32_t width, uint32_t height) {
    return encodePng(width, height, 4, std::vector<uint8_t>(size_t(width) * height * 4, 255));
}

// floatingQuad with the quad textured: TEXCOORD_0, material 0 (alpha-tested) whose base colour
// texture 0 reads a 2x2 PNG (image 0, the last bufferView) through sampler 0.
GltfBuilder textured() {
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
GltfBuilder sparseGround(const std::vector<uint16_t>& indices, int count) {
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
int spareView(GltfBuilder& b, size_t length) {
    while (b.bin.size() < length)
        b.bin.push_back(0);
    b.j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", length}});
    return static_cast<int>(b.j["bufferViews"].size() - 1);
}

// A GLB file image: the header, the JSON chunk (padded with spaces) and, unless `bin` is empty,
// a BIN chunk (padded with zeros).
std::vector<uint8_t> glb(std::string json, std::vector<uint8_t> bin) {
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
std::vector<uint8_t> glbWithBin() {
    GltfBuilder b = floatingQuad();
    while (b.bin.size() % 4)
        b.bin.push_back(0);
    b.j["buffers"] = J::array({{{"byteLength", b.bin.size()}}});
    return glb(b.j.dump(), b.bin);
}

// floatingQuad as a GLB of one JSON chunk (the buffer a data URI) that ends in padding spaces.
std::vector<uint8_t> glbJsonOnly() {
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
void PrintTo(const Boundary& row, std::ostream* os) {
    *os << row.name;
}

using Change = std::function<void(GltfBuilder&, bool past)>;

// A row that edits the JSON (or bytes) of a base asset and writes it as .gltf.
std::function<Asset(const fs::path&, bool)> gltf(std::function<GltfBuilder()> base, Change change) {
    return [base, change](const fs::path& d, bool past) {
        GltfBuilder b = base();
        change(b, past);
        return Asset{b.writeGltf(d / "a.gltf")};
    };
}

// A row that edits the bytes of a GLB.
std::function<Asset(const fs::path&, bool)>
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
Change dataUri(std::string edge, std::string past, size_t byteLength) {
    return [=](GltfBuilder& b, bool isPast) {
        b.j["buffers"] =
            J::array({J::object(),
                      {{"uri", "data:application/octet-stream;base64," + (isPast ? past : edge)},
                       {"byteLength", byteLength}}});
    };
}

// The 2x2 PNG of textured(), edited, as image 0.
Change pngBytes(std::function<void(std::vector<uint8_t>&, bool past)> edit) {
    return [edit](GltfBuilder& b, bool past) {
        std::vector<uint8_t> image = png(2, 2);
        edit(image, past);
        b.j["images"][0]["bufferView"] = b.view(image);
    };
}

Change cameraValue(const char* key, double edge, double past) {
    return [=](GltfBuilder& b, bool isPast) {
        b.j["cameras"][0]["perspective"][key] = isPast ? past : edge;
    };
}

Change lightValue(std::function<J&(J& light)> field, double edge, double past) {
    return [=](GltfBuilder& b, bool isPast) {
        field(b.j["extensions"]["KHR_lights_punctual"]["lights"][0]) = isPast ? past : edge;
    };
}

std::vector<Boundary> boundaries() {
    const uint64_t u64max = std::numeric_limits<uint64_t>::max();
    return {
        // ---- The container: file size, GLB header and chunks (gltf_container.cpp) ----
        {"file_size_cap",
         [](const fs::path& d, bool past) {
             const fs::path f = floatingQuad().writeGltf(d / "a.gltf");
             return Asset{f, {.maxFileSize = fs::file_size(f) - (past ? 1 : 0)}};
         },
         "bytes is past the size cap of"},
        {"external_bin_size_cap",
         [](const fs::path& d, bool past) {
             GltfBuilder b = floatingQuad();
             b.view(std::vector<float>(1024, 0.0f)); // the .bin outgrows the .gltf
             const fs::path f = b.writeGltf(d / "a.gltf", true);
             const uint64_t bin = fs::file_size(d / "a.bin");
             EXPECT_LT(fs::file_size(f), bin - 1);
             return Asset{f, {.maxFileSize = bin - (past ? 1 : 0)}};
         },
         "is past the size cap of"},
        {"glb_header_size",
         [](const fs::path& d, bool past) { // 20 bytes: a header with an empty JSON chunk
             std::vector<uint8_t> bytes(20);
             setU32(bytes, 0, 0x46546C67);
             setU32(bytes, 4, 2);
             setU32(bytes, 16, 0x4E4F534A);
             bytes.resize(past ? 19 : 20);
             setU32(bytes, 8, uint32_t(bytes.size()));
             writeBytes(d / "a.glb", bytes);
             return Asset{d / "a.glb"};
         },
         "GLB: truncated header", "GLB: JSON chunk length 0 is invalid"},
        {"glb_version", glbFile(glbWithBin, [](auto& v, bool past) { setU32(v, 4, past ? 3 : 2); }),
         "GLB: version 3 is not supported"},
        {"glb_header_length_above",
         glbFile(glbWithBin,
                 [](auto& v, bool past) { setU32(v, 8, uint32_t(v.size() + (past ? 1 : 0))); }),
         "GLB: header length"},
        {"glb_header_length_below",
         glbFile(glbWithBin,
                 [](auto& v, bool past) { setU32(v, 8, uint32_t(v.size() - (past ? 1 : 0))); }),
         "GLB: header length"},
        {"glb_json_chunk_not_empty",
         [](const fs::path& d, bool past) { // "{}  ": a JSON chunk of 4 bytes, or declared 0
             std::vector<uint8_t> bytes = glb("{}", {});
             setU32(bytes, 12, past ? 0 : 4);
             writeBytes(d / "a.glb", bytes);
             return Asset{d / "a.glb"};
         },
         "GLB: JSON chunk length 0 is invalid", "asset.version: missing"},
        {"glb_json_chunk_inside_file", // ends exactly at the end of the file (no BIN chunk)
         glbFile(glbJsonOnly,
                 [](auto& v, bool past) { setU32(v, 12, u32At(v, 12) + (past ? 4 : 0)); }),
         "GLB: JSON chunk length"},
        {"glb_json_chunk_aligned", // a multiple of 4; one less still ends the JSON text
         glbFile(glbJsonOnly,
                 [](auto& v, bool past) { setU32(v, 12, u32At(v, 12) - (past ? 1 : 0)); }),
         "GLB: JSON chunk length"},
        {"glb_chunk_header_inside_file", // 8 bytes after the JSON chunk hold a chunk header
         glbFile(glbJsonOnly,
                 [](auto& v, bool past) {
                     const std::vector<uint8_t> header = {0, 0, 0, 0, 'B', 'I', 'N', 0};
                     v.insert(v.end(), header.begin(), header.end() - (past ? 1 : 0));
                     setU32(v, 8, uint32_t(v.size()));
                 }),
         "GLB: truncated chunk header", "Insufficient storage space for Chunk1"},
        {"glb_bin_chunk_inside_file",
         glbFile(glbWithBin,
                 [](auto& v, bool past) {
                     const size_t at = 20 + u32At(v, 12);
                     setU32(v, at, u32At(v, at) + (past ? 1 : 0));
                 }),
         "GLB: BIN chunk length"},
        {"glb_buffer_inside_bin_chunk",
         [](const fs::path& d, bool past) {
             GltfBuilder b = floatingQuad();
             while (b.bin.size() % 4)
                 b.bin.push_back(0);
             b.j["buffers"] = J::array({{{"byteLength", b.bin.size() + (past ? 1 : 0)}}});
             writeBytes(d / "a.glb", glb(b.j.dump(), b.bin));
             return Asset{d / "a.glb"};
         },
         "Must be equal or less than binary size"},

        // ---- URIs: data URIs and percent-encoding (gltf_container.cpp) ----
        {"data_uri_byte_length", // decodes to exactly the buffer's byteLength (tinygltf's check)
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["buffers"] =
                      J::array({J::object(),
                                {{"uri", "data:application/octet-stream;base64,AAAAAA=="},
                                 {"byteLength", past ? 5 : 4}}});
              }),
         "Failed to decode 'uri'"},
        {"base64_length_multiple_of_4", gltf(floatingQuad, dataUri("AAAAAA==", "AAAAAA=", 4)),
         "buffers[1].uri: data URI has malformed base64"},
        {"base64_padding_from_third_character", gltf(floatingQuad, dataUri("AA==", "A===", 1)),
         "buffers[1].uri: data URI has malformed base64"},
        {"base64_padding_only_in_last_quad", gltf(floatingQuad, dataUri("AAAAAA==", "AA==AAAA", 4)),
         "buffers[1].uri: data URI has malformed base64"},
        {"base64_nothing_after_padding", gltf(floatingQuad, dataUri("AAA=", "AA=A", 2)),
         "buffers[1].uri: data URI has malformed base64"},
        {"data_uri_marks_base64",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["buffers"] =
                      J::array({J::object(),
                                {{"uri", past ? "data:application/octet-stream,AAAA"
                                              : "data:application/octet-stream;base64,AAAA"},
                                 {"byteLength", 3}}});
              }),
         "buffers[1].uri: data URI is not base64"},
        {"percent_escape_at_the_end",
         [](const fs::path& d, bool past) { // "buf%41" names the file "bufA"
             writeBytes(d / "bufA", {1, 2, 3, 4});
             GltfBuilder b = floatingQuad();
             b.j["buffers"] =
                 J::array({J::object(), {{"uri", past ? "buf%4" : "buf%41"}, {"byteLength", 4}}});
             return Asset{b.writeGltf(d / "a.gltf")};
         },
         "buffers[1].uri: malformed percent-encoding ('buf%4')"},
        {"external_bin_byte_length",
         [](const fs::path& d, bool past) {
             GltfBuilder b = floatingQuad();
             writeBytes(d / "more.bin", {1, 2, 3, 4});
             b.j["buffers"] =
                 J::array({J::object(), {{"uri", "more.bin"}, {"byteLength", past ? 5 : 4}}});
             return Asset{b.writeGltf(d / "a.gltf")};
         },
         "File size mismatch"},

        // ---- JSON references, before any parser follows them (gltf_container.cpp) ----
        {"scene_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) { b.j["scene"] = lastOr(b.j["scenes"], past); }),
         "scene: index 1 is out of range (1 scenes)"},
        {"scene_node_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["scenes"][0]["nodes"].push_back(lastOr(b.j["nodes"], past));
              }),
         "scenes[0].nodes[4]: index 4 is out of range (4 nodes)"},
        {"node_mesh_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["nodes"][0]["mesh"] = lastOr(b.j["meshes"], past);
              }),
         "nodes[0].mesh: index 2 is out of range (2 meshes)"},
        {"node_mesh_index_negative",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) { b.j["nodes"][0]["mesh"] = past ? -1 : 0; }),
         "nodes[0].mesh: index -1 is out of range"},
        {"node_camera_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["nodes"][2]["camera"] = lastOr(b.j["cameras"], past);
              }),
         "nodes[2].camera: index 1 is out of range (1 cameras)"},
        {"node_child_index", // the light node, also a root: a second instance of the light
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["nodes"][0]["children"] = {lastOr(b.j["nodes"], past)};
              }),
         "nodes[0].children[0]: index 4 is out of range (4 nodes)"},
        {"attribute_accessor_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.positions({-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5}); // a valid last accessor
                  b.j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
                      lastOr(b.j["accessors"], past);
              }),
         "meshes[0].primitives[0].attributes.POSITION: index 5 is out of range (5 accessors)"},
        {"indices_accessor_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<uint16_t>{0, 2, 1, 0, 3, 2}), 5123, 6, "SCALAR");
                  b.j["meshes"][0]["primitives"][0]["indices"] = lastOr(b.j["accessors"], past);
              }),
         "meshes[0].primitives[0].indices: index 5 is out of range (5 accessors)"},
        {"material_index",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["meshes"][1]["primitives"][0]["material"] = lastOr(b.j["materials"], past);
              }),
         "meshes[1].primitives[0].material: index 1 is out of range (1 materials)"},
        {"base_color_texture_index",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] =
                      lastOr(b.j["textures"], past);
              }),
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: index 1 is out of range "
         "(1 textures)"},
        {"normal_texture_index",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["materials"][0]["normalTexture"] = {{"index", lastOr(b.j["textures"], past)}};
              }),
         "materials[0].normalTexture.index: index 1 is out of range (1 textures)"},
        {"texture_source_index",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["textures"][0]["source"] = lastOr(b.j["images"], past);
              }),
         "textures[0].source: index 1 is out of range (1 images)"},
        {"texture_sampler_index",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["textures"][0]["sampler"] = lastOr(b.j["samplers"], past);
              }),
         "textures[0].sampler: index 1 is out of range (1 samplers)"},
        {"image_buffer_view_index", // the PNG is the last bufferView
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["images"][0]["bufferView"] = lastOr(b.j["bufferViews"], past);
              }),
         "images[0].bufferView: index 6 is out of range (6 bufferViews)"},
        {"accessor_buffer_view_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int p = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0}); // on the last view
                  b.j["accessors"][p]["bufferView"] = lastOr(b.j["bufferViews"], past);
              }),
         "accessors[4].bufferView: index 5 is out of range (5 bufferViews)"},
        {"buffer_view_buffer_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["buffers"] = J::array({J::object()}); // the builder's, filled on writing
                  b.j["bufferViews"][0]["buffer"] = lastOr(b.j["buffers"], past);
              }),
         "bufferViews[0].buffer: index 1 is out of range (1 buffers)"},
        {"light_index",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] =
                      lastOr(b.j["extensions"]["KHR_lights_punctual"]["lights"], past);
              }),
         "KHR_lights_punctual: light 1 is out of range"},
        {"light_index_negative",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = past ? -1 : 0;
              }),
         "KHR_lights_punctual: light -1 is out of range"},
        {"texcoord_set_non_negative",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] =
                      past ? -1 : 0;
              }),
         "baseColorTexture.texCoord: not a non-negative integer"},

        // ---- bufferViews: strides and byte ranges ----
        {"stride_minimum", // 0 is a multiple of 4: only the lower bound refuses it
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["bufferViews"][spareView(b, 8)]["byteStride"] = past ? 0 : 4;
              }),
         "bufferViews[4].byteStride: 0 is not a multiple of 4 in [4, 252]"},
        {"stride_maximum", // 256, the first multiple of 4 past 252
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["bufferViews"][spareView(b, 8)]["byteStride"] = past ? 256 : 252;
              }),
         "bufferViews[4].byteStride: 256 is not a multiple of 4 in [4, 252]"},
        {"stride_multiple_of_4", // 10 is even: only a divisor of 4 refuses it
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["bufferViews"][spareView(b, 8)]["byteStride"] = past ? 10 : 8;
              }),
         "bufferViews[4].byteStride: 10 is not a multiple of 4 in [4, 252]"},
        {"buffer_view_length_minimum",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["bufferViews"][spareView(b, 1)]["byteLength"] = past ? 0 : 1;
              }),
         "bufferViews[4].byteLength: must be at least 1"},
        {"buffer_view_length_inside_buffer",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int v = spareView(b, 1);
                  b.j["bufferViews"][v]["byteLength"] = b.bin.size() + (past ? 1 : 0);
              }),
         "bufferViews[4]: bytes 0..113 run past buffer 0"},
        {"buffer_view_offset_inside_buffer",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int v = spareView(b, 1);
                  b.j["bufferViews"][v]["byteOffset"] = b.bin.size() - (past ? 0 : 1);
              }),
         "bufferViews[4]: bytes 112..113 run past buffer 0"},
        {"image_buffer_view_inside_buffer", // image bytes reach the decoder before validateModel
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  auto& view = b.j["bufferViews"][b.j["images"][0]["bufferView"].get<int>()];
                  view["byteLength"] =
                      b.bin.size() - view["byteOffset"].get<size_t>() + (past ? 1 : 0);
              }),
         "bufferViews[5]: bytes"},

        // ---- Accessors (gltf_validate.cpp) ----
        {"accessor_count_minimum",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<float>{1, 2, 3}), 5126, past ? 0 : 1, "VEC3");
              }),
         "accessors[4].count: must be at least 1"},
        {"accessor_count_inside_view",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<float>(6, 1.0f)), 5126, past ? 3 : 2, "VEC3");
              }),
         "accessors[4]: 3 elements need bytes 0..36 but bufferView 4 has 24"},
        {"accessor_offset_inside_view",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int a =
                      b.accessor(b.view(std::vector<uint8_t>{1, 2, 3, 4}), 5121, 1, "SCALAR");
                  b.j["accessors"][a]["byteOffset"] = past ? 4 : 3;
              }),
         "accessors[4]: 1 elements need bytes 4..5 but bufferView 4 has 4"},
        {"accessor_offset_aligned", // 6 is even: only the component size (4) refuses it
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int a =
                      b.accessor(b.view(std::vector<float>{1, 2, 3, 4}), 5126, 1, "SCALAR");
                  b.j["accessors"][a]["byteOffset"] = past ? 6 : 4;
              }),
         "accessors[4].byteOffset: not a multiple of the component size"},
        {"strided_last_element_needs_no_padding", // 3 VEC3 floats 16 apart: 2 x 16 + 12 bytes
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int v = b.view(std::vector<float>(12, 1.0f), 16);
                  b.j["bufferViews"][v]["byteLength"] = past ? 43 : 44;
                  b.accessor(v, 5126, 3, "VEC3");
              }),
         "accessors[4]: 3 elements need bytes 0..44 but bufferView 4 has 43"},
        {"stride_at_least_one_element",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<float>(9, 1.0f), past ? 8 : 12), 5126, 3, "VEC3");
              }),
         "accessors[4]: byteStride is smaller than one element"},
        {"stride_multiple_of_component", // DOUBLE (5130, which tinygltf parses): 8-byte parts
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<double>{1.0, 2.0}, past ? 12 : 8), 5130, 1,
                             "SCALAR");
              }),
         "accessors[4]: byteStride is not a multiple of the component size"},
        {"component_type_above_float",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<float>{1}), past ? 5127 : 5126, 1, "SCALAR");
              }),
         "accessors[4]: invalid componentType or type"},
        {"component_type_below_byte",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<uint8_t>{1}), past ? 5119 : 5120, 1, "SCALAR");
              }),
         "Invalid `componentType` in accessor. Got 5119"},
        {"byte_range_sum_overflow", // offset + count bytes = 2^64 - 1 fits in 64 bits, 2^64 not
         gltf(floatingQuad,
              [u64max](GltfBuilder& b, bool past) {
                  const int a =
                      b.accessor(b.view(std::vector<uint8_t>{1, 2, 3, 4}), 5121, 1, "SCALAR");
                  b.j["accessors"][a]["count"] = u64max;
                  b.j["accessors"][a]["byteOffset"] = past ? 1 : 0;
              }),
         "accessors[4]: byte range overflows",
         "accessors[4]: 18446744073709551615 elements need bytes 0..18446744073709551615"},
        {"byte_range_product_overflow", // (count - 1) x stride 4: 2^64 - 4, then 2^64 (wraps to 0)
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<uint8_t>(8, 1), 4), 5121,
                             (uint64_t{1} << 62) + (past ? 1 : 0), "SCALAR");
              }),
         "accessors[4]: byte range overflows", "elements need bytes"},
        {"sparse_only_accessor_count_overflow", // no bufferView: count x 12 bytes must fit 64 bits
         gltf(floatingQuad,
              [u64max](GltfBuilder& b, bool past) {
                  b.j["accessors"].push_back(
                      {{"componentType", 5126},
                       {"count", u64max / 12 + (past ? 1 : 0)},
                       {"type", "VEC3"},
                       {"sparse",
                        {{"count", 1},
                         {"indices",
                          {{"bufferView", b.view(std::vector<uint8_t>{1})},
                           {"componentType", 5121}}},
                         {"values", {{"bufferView", b.view(std::vector<float>{1, 0, 0})}}}}}});
                  b.node({{"mesh", b.mesh(static_cast<int>(b.j["accessors"].size() - 1))}});
              }),
         "accessors[4]: byte range overflows", "more than 100000000 triangles"},

        // ---- Sparse accessors ----
        {"sparse_index_value",
         gltf(
             [] {
                 return sparseGround({3, 4}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 if (past) // the index is the first uint16 of view 0
                     b.bin[0] = 4;
             }),
         "accessors[0].sparse.indices[0]: 4 is out of range (4 elements)"},
        {"sparse_second_index_value",
         gltf(
             [] {
                 return sparseGround({0, 3}, 2);
             },
             [](GltfBuilder& b, bool past) {
                 if (past)
                     b.bin[2] = 4;
             }),
         "accessors[0].sparse.indices[1]: 4 is out of range (4 elements)"},
        {"sparse_count_minimum",
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["count"] = past ? 0 : 1;
             }),
         "accessors[0].sparse.count: 0 is outside 1..4"},
        {"sparse_count_maximum",
         gltf(
             [] {
                 return sparseGround({0, 1, 2, 3, 3}, 4);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["count"] = past ? 5 : 4;
             }),
         "accessors[0].sparse.count: 5 is outside 1..4"},
        {"sparse_indices_inside_view",
         gltf(
             [] {
                 return sparseGround({0, 3}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["byteOffset"] = past ? 3 : 2;
             }),
         "accessors[0].sparse.indices: 1 elements need bytes 3..5 but bufferView 0 has 4"},
        {"sparse_values_inside_view", // view 1 holds 5 VEC3s: the last starts at byte 48
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["values"]["byteOffset"] = past ? 49 : 48;
             }),
         "accessors[0].sparse.values: 1 elements need bytes 49..61 but bufferView 1 has 60"},
        {"sparse_indices_buffer_view_index", // the last view: the ground's uint16 indices
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["bufferView"] =
                     lastOr(b.j["bufferViews"], past);
             }),
         "accessors[0].sparse.indices.bufferView: bufferView index 4 is out of range"},
        {"sparse_indices_buffer_view_negative",
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["bufferView"] = past ? -1 : 0;
             }),
         "accessors[0].sparse.indices.bufferView: bufferView index -1 is out of range"},
        {"sparse_values_buffer_view_index", // the last view (12 bytes): one VEC3 of any floats
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["values"]["bufferView"] =
                     lastOr(b.j["bufferViews"], past);
             }),
         "accessors[0].sparse.values.bufferView: bufferView index 4 is out of range"},
        {"sparse_index_type_unsigned_byte",
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["componentType"] = past ? 5120 : 5121;
             }),
         "sparse.indices.componentType: must be an unsigned integer type"},
        {"sparse_index_type_unsigned_short",
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["componentType"] = past ? 5122 : 5123;
             }),
         "sparse.indices.componentType: must be an unsigned integer type"},
        {"sparse_index_type_unsigned_int_below",
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["componentType"] = past ? 5124 : 5125;
             }),
         "sparse.indices.componentType: must be an unsigned integer type"},
        {"sparse_index_type_unsigned_int_above",
         gltf(
             [] {
                 return sparseGround({3, 0}, 1);
             },
             [](GltfBuilder& b, bool past) {
                 b.j["accessors"][0]["sparse"]["indices"]["componentType"] = past ? 5126 : 5125;
             }),
         "sparse.indices.componentType: must be an unsigned integer type"},

        // ---- Primitives ----
        {"attribute_count_equals_position",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  const int n =
                      b.accessor(b.view(std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}),
                                 5126, past ? 3 : 4, "VEC3");
                  b.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = n;
              }),
         "meshes[0].primitives[0].attributes.NORMAL: has 3 elements but POSITION has 4"},
        {"index_type_unsigned_byte",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["accessors"][3]["componentType"] = past ? 5120 : 5121; // the fan's
              }),
         "meshes[1].primitives[0].indices: must be unsigned byte, short or int"},
        {"index_type_unsigned_short",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["accessors"][1]["componentType"] = past ? 5122 : 5123; // the ground's
              }),
         "meshes[0].primitives[0].indices: must be unsigned byte, short or int"},
        {"index_type_unsigned_int",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["accessors"][1]["bufferView"] =
                      b.view(std::vector<uint32_t>{0, 2, 1, 0, 3, 2});
                  b.j["accessors"][1]["componentType"] = past ? 5124 : 5125;
              }),
         "meshes[0].primitives[0].indices: must be unsigned byte, short or int"},
        {"mode_maximum",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["meshes"][1]["primitives"][0]["mode"] = past ? 7 : 6;
              }),
         "meshes[1].primitives[0].mode: not a glTF mode"},
        {"mode_minimum", // points: skipped with a warning, the ground still has triangles
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["meshes"][1]["primitives"][0]["mode"] = past ? -1 : 0;
              }),
         "meshes[1].primitives[0].mode: not a glTF mode"},
        {"index_value_below_vertex_count",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["accessors"][1]["bufferView"] =
                      b.view(std::vector<uint16_t>{0, 2, 1, 0, uint16_t(past ? 4 : 3), 2});
              }),
         "meshes[0]: index 4 is past the 4 vertices"},

        // ---- Materials ----
        {"base_color_factor_maximum",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {
                      0.5, 0.5, past ? std::nextafter(1.0, 2.0) : 1.0, 1.0};
              }),
         "materials[0].pbrMetallicRoughness.baseColorFactor: values must be in [0, 1]"},
        {"base_color_factor_minimum",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {
                      past ? -std::numeric_limits<double>::denorm_min() : 0.0, 0.5, 0.5, 1.0};
              }),
         "materials[0].pbrMetallicRoughness.baseColorFactor: values must be in [0, 1]"},
        {"base_color_factor_size",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  J factor = {0.5, 0.5, 0.5};
                  if (!past)
                      factor.push_back(1.0);
                  b.j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = factor;
              }),
         "materials[0].pbrMetallicRoughness.baseColorFactor: needs 4 numbers"},
        {"alpha_cutoff_minimum",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["materials"][0]["alphaCutoff"] =
                      past ? -std::numeric_limits<double>::denorm_min() : 0.0;
              }),
         "materials[0].alphaCutoff: must be a finite number >= 0"},

        // ---- Nodes, cameras and lights (gltf_loader.cpp) ----
        {"node_matrix_size",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  J m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0};
                  if (!past)
                      m.push_back(1);
                  b.j["nodes"][0]["matrix"] = m;
              }),
         "nodes[0].matrix: needs 16 numbers"},
        {"camera_znear_positive", gltf(floatingQuad, cameraValue("znear", kTinyPositive, 0.0)),
         "cameras: 'eye' has invalid parameters"},
        {"camera_zfar_above_znear", // znear 0.1 (as a float)
         gltf(floatingQuad, cameraValue("zfar", floatAbove(0.1f), double(0.1f))),
         "cameras: 'eye' has invalid parameters"},
        {"camera_zfar_zero_is_infinite", // 0 means absent (infinite); any positive one is used
         gltf(floatingQuad, cameraValue("zfar", 0.0, kTinyPositive)),
         "cameras: 'eye' has invalid parameters"},
        {"camera_yfov_positive", gltf(floatingQuad, cameraValue("yfov", kTinyPositive, 0.0)),
         "cameras: 'eye' has invalid parameters"},
        {"camera_yfov_below_3_1", gltf(floatingQuad, cameraValue("yfov", floatBelow(3.1f), 3.1f)),
         "cameras: 'eye' has invalid parameters"},
        {"camera_ymag_positive",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["cameras"][0] = {{"type", "orthographic"},
                                       {"name", "eye"},
                                       {"orthographic",
                                        {{"xmag", 1.0},
                                         {"ymag", past ? 0.0 : kTinyPositive},
                                         {"znear", 0.1},
                                         {"zfar", 10.0}}}};
              }),
         "cameras: 'eye' has invalid parameters"},
        {"light_intensity_minimum",
         gltf(floatingQuad,
              lightValue([](J& l) -> J& { return l["intensity"]; }, 0.0, -kTinyPositive)),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},
        {"light_intensity_finite", // past FLT_MAX by half an ulp: rounds to infinity as a float
         gltf(floatingQuad,
              lightValue([](J& l) -> J& { return l["intensity"]; },
                         std::numeric_limits<float>::max(),
                         double(std::numeric_limits<float>::max()) + std::ldexp(1.0, 103))),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},
        {"light_radius_minimum",
         gltf(floatingQuad,
              lightValue([](J& l) -> J& { return l["extras"]["radius"]; }, 0.0, -kTinyPositive)),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},
        {"light_angular_diameter_minimum",
         gltf(floatingQuad, lightValue([](J& l) -> J& { return l["extras"]["angularDiameter"]; },
                                       0.0, -kTinyPositive)),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},
        {"light_angular_diameter_maximum",
         gltf(floatingQuad, lightValue([](J& l) -> J& { return l["extras"]["angularDiameter"]; },
                                       30.0, floatAbove(30.0f))),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},

        // ---- Caps on what a small file can ask for ----
        {"max_triangles", // ground 2 + fan 2
         [](const fs::path& d, bool past) {
             return Asset{floatingQuad().writeGltf(d / "a.gltf"),
                          {.maxTriangles = uint64_t(past ? 3 : 4)}};
         },
         "meshes[1]: the scene would have more than 3 triangles after instancing"},
        {"max_vertices_three_per_triangle", // cap 2: 1 triangle over 6 vertices, then over 7
         [](const fs::path& d, bool past) {
             GltfBuilder b;
             std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 0, 1};
             xyz.resize(past ? 21 : 18, 0.5f);
             const int i = b.accessor(b.view(std::vector<uint16_t>{0, 1, 2}), 5123, 3, "SCALAR");
             b.node({{"mesh", b.mesh(b.positions(xyz), i)}});
             return Asset{b.writeGltf(d / "a.gltf"), {.maxTriangles = 2}};
         },
         "meshes[0]: the scene would have more than 2 triangles"},
        {"scene_has_a_triangle", // 3 indices make one triangle, 2 make none
         [](const fs::path& d, bool past) {
             GltfBuilder b;
             const int p = b.positions({0, 0, 0, 1, 0, 0, 0, 0, 1});
             const int i =
                 b.accessor(b.view(std::vector<uint16_t>{0, 2, 1}), 5123, past ? 2 : 3, "SCALAR");
             b.node({{"mesh", b.mesh(p, i)}});
             return Asset{b.writeGltf(d / "a.gltf")};
         },
         "the default scene has no triangles"},
        {"image_width_maximum",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["images"][0]["bufferView"] = b.view(png(past ? 16385 : 16384, 1));
              }),
         "images[0]: 16385x1 pixels is outside 1..16384 per side"},
        {"image_height_maximum",
         gltf(textured,
              [](GltfBuilder& b, bool past) {
                  b.j["images"][0]["bufferView"] = b.view(png(1, past ? 16385 : 16384));
              }),
         "images[0]: 1x16385 pixels is outside 1..16384 per side"},
        {"decoded_image_bytes", // 2 x 2 x 4 bytes
         [](const fs::path& d, bool past) {
             return Asset{textured().writeGltf(d / "a.gltf"),
                          {.maxImageBytes = uint64_t(past ? 15 : 16)}};
         },
         "images[0]: the images need more than 15 bytes decoded"},
        {"decoded_image_bytes_add_up", // a second 2x2 image, used by a second material
         [](const fs::path& d, bool past) {
             GltfBuilder b = textured();
             b.j["images"].push_back(
                 {{"bufferView", b.view(png(2, 2))}, {"mimeType", "image/png"}});
             b.j["textures"].push_back({{"source", 1}});
             b.j["materials"].push_back(
                 {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}});
             return Asset{b.writeGltf(d / "a.gltf"), {.maxImageBytes = uint64_t(past ? 31 : 32)}};
         },
         "images[1]: the images need more than 31 bytes decoded"},
        {"png_last_chunk_inside_image", // one byte short: IEND's CRC is cut
         gltf(textured, pngBytes([](std::vector<uint8_t>& png, bool past) {
                  if (past)
                      png.pop_back();
              })),
         "images[0]: a PNG chunk runs past the end of the image"},
        {"png_chunk_length_inside_image", // IEND declares 1 byte of data where the image has 0
         gltf(textured, pngBytes([](std::vector<uint8_t>& png, bool past) {
                  png[png.size() - 12 + 3] = past ? 1 : 0;
              })),
         "images[0]: a PNG chunk runs past the end of the image"},
    };
}

class GltfBounds : public ::testing::TestWithParam<Boundary> {};

} // namespace

TEST_P(GltfBounds, LastValidValueLoadsFirstInvalidIsRefused) {
    const Boundary& row = GetParam();
    const fs::path edgeDir = dir(std::string(row.name) + "/edge");
    const fs::path pastDir = dir(std::string(row.name) + "/past");
    const Asset edge = row.make(edgeDir, false);
    if (row.edgeRefusal.empty()) {
        try {
            loadScene(edge.file.string(), edge.options);
        } catch (const std::exception& e) {
            ADD_FAILURE() << "the last valid value was refused: " << e.what();
        }
    } else {
        expectRefused(edge.file, row.edgeRefusal, edge.options);
    }
    const Asset past = row.make(pastDir, true);
    expectRefused(past.file, row.refusal, past.options);
}

INSTANTIATE_TEST_SUITE_P(GltfBounds, GltfBounds, ::testing::ValuesIn(boundaries()),
                         [](const auto& p) { return std::string(p.param.name); });

// An image's bufferView is handed to the decoder while tinygltf parses, before validateModel
// checks any byte range: a view far past its buffer must be refused before a byte is read.
TEST(GltfBoundsImages, ViewsFarPastTheirBufferAreRefusedBeforeDecoding) {
    GltfBuilder b = textured();
    auto& view = b.j["bufferViews"][b.j["images"][0]["bufferView"].get<int>()];
    view["byteOffset"] = uint64_t{1} << 40;
    expectRefused(b.writeGltf(dir("image-view-far") / "a.gltf"), "bufferViews[5]: bytes");
}

// Scene::coverage (material_coverage.cpp) indexes materials, textures, images and texels: at
// each edge. A 2x1 texture, nearest: texel 0 is a hole (alpha 0), texel 1 is solid.
TEST(GltfBoundsCoverage, WrapModesAndReferencesAtTheirEdges) {
    Scene s;
    s.images = {{.name = "holes", .width = 2, .height = 1, .rgba = {0, 0, 0, 0, 0, 0, 0, 255}}};
    s.materials = {
        {.baseColor = glm::vec4(1.0f), .baseColorTexture = 0, .alphaMode = AlphaMode::Mask}};
    auto alphaAt = [&s](TextureWrap wrap, float u) {
        s.textures = {{.image = 0, .wrapS = wrap, .wrapT = wrap, .nearest = true}};
        return s.coverage(0, {u, 0.5f}, 1.0f);
    };
    // u = -0.25, 0.25, 0.75, 1.25, 1.75, 2.25: texels -1, 0, 1, 2, 3, 4 before wrapping.
    const std::vector<float> u = {-0.25f, 0.25f, 0.75f, 1.25f, 1.75f, 2.25f};
    const std::vector<std::pair<TextureWrap, std::vector<float>>> expected = {
        {TextureWrap::Repeat, {1, 0, 1, 0, 1, 0}},
        {TextureWrap::ClampToEdge, {0, 0, 1, 1, 1, 1}},
        {TextureWrap::MirroredRepeat, {0, 0, 1, 1, 0, 0}}, // period 4: 0 1 | 1 0 | 0 1
    };
    for (const auto& [wrap, alphas] : expected)
        for (size_t k = 0; k < u.size(); ++k)
            EXPECT_EQ(alphaAt(wrap, u[k]), alphas[k]) << "wrap " << int(wrap) << ", u " << u[k];
    s.textures = {{.image = 0, .nearest = true}};
    EXPECT_EQ(s.coverage(0, {0.25f, 0.5f}, 1.0f), 0.0f); // the last material: textured
    EXPECT_EQ(s.coverage(1, {0.25f, 0.5f}, 1.0f), 1.0f); // one past: no material, covered
    EXPECT_TRUE(s.covers(1, {0.25f, 0.5f}, 1.0f));
    s.materials[0].baseColorTexture = 1; // one past the last texture: the factor alone
    EXPECT_EQ(s.coverage(0, {0.25f, 0.5f}, 1.0f), 1.0f);
    s.materials[0].baseColorTexture = 0;
    s.textures[0].image = 1; // one past the last image: the factor alone
    EXPECT_EQ(s.coverage(0, {0.25f, 0.5f}, 1.0f), 1.0f);
}
