// The glTF loader's bounds at their exact boundaries: the container (file size, GLB header and
// chunks), URIs, JSON references and bufferViews. The rows' helpers and the test are in
// gltf_bounds.h and test_gltf_bounds.cpp.
#include "gltf_bounds.h"

using namespace penumbra;
using namespace penumbra::test;
using namespace penumbra::test::bounds;

namespace {

std::vector<Boundary> containerBoundaries() {
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
        // Bytes past the declared length are ignored (a warning): the BIN chunk then runs past it.
        {"glb_header_length_below",
         glbFile(glbWithBin,
                 [](auto& v, bool past) { setU32(v, 8, uint32_t(v.size() - (past ? 1 : 0))); }),
         "GLB: BIN chunk length 112 runs past the file"},
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
         "GLB: truncated chunk header"},
        {"glb_bin_chunk_inside_file",
         glbFile(glbWithBin,
                 [](auto& v, bool past) {
                     const size_t at = 20 + u32At(v, 12);
                     setU32(v, at, u32At(v, at) + (past ? 1 : 0));
                 }),
         "GLB: BIN chunk length"},
        // ---- URIs: data URIs and percent-encoding (gltf_container.cpp) ----
        {"data_uri_byte_length", // decodes to exactly the buffer's byteLength
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["buffers"] =
                      J::array({J::object(),
                                {{"uri", "data:application/octet-stream;base64,AAAAAA=="},
                                 {"byteLength", past ? 5 : 4}}});
              }),
         "buffers[1].uri: the data URI holds 4 bytes but byteLength says 5"},
        {"base64_length_multiple_of_4", gltf(floatingQuad, dataUri("AAAAAA==", "AAAAAA=", 4)),
         "buffers[1].uri: data URI has malformed base64"},
        {"base64_padding_from_third_character", gltf(floatingQuad, dataUri("AA==", "A===", 1)),
         "buffers[1].uri: data URI has malformed base64"},
        {"base64_padding_only_in_last_quad", gltf(floatingQuad, dataUri("AAAAAA==", "AA==AAAA", 4)),
         "buffers[1].uri: data URI has malformed base64"},
        {"base64_nothing_after_padding", gltf(floatingQuad, dataUri("AAA=", "AA=A", 2)),
         "buffers[1].uri: data URI has malformed base64"},
        // Without ;base64 the data is its (percent-decoded) text: 4 bytes, not 3.
        {"data_uri_marks_base64",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["buffers"] =
                      J::array({J::object(),
                                {{"uri", past ? "data:application/octet-stream,AAAA"
                                              : "data:application/octet-stream;base64,AAAA"},
                                 {"byteLength", 3}}});
              }),
         "buffers[1].uri: the data URI holds 4 bytes but byteLength says 3"},
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
         "scenes[0].nodes[4]: index 4 is out of range (4 nodes)",
         "scenes[0].nodes[4]: node 3 is listed twice"},
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
        {"node_child_index", // the light node, listed as a root too: refused as not a root
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["nodes"][0]["children"] = {lastOr(b.j["nodes"], past)};
              }),
         "nodes[0].children[0]: index 4 is out of range (4 nodes)",
         "node 3 is not a root (its parent is node 0)"},
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
    };
}

} // namespace

INSTANTIATE_TEST_SUITE_P(Container, GltfBounds, ::testing::ValuesIn(containerBoundaries()),
                         [](const auto& p) { return std::string(p.param.name); });
