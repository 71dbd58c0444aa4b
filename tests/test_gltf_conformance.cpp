// glTF conformance (issue 16), one minimal asset per case: constructs the specification calls
// valid load (however unusual), each error class of the glTF-Validator that we handle refuses the
// file with its JSON path, and each part Penumbra does not use loads with one warning naming it.
#include "base64_decode.h"
#include "expect_refused.h"
#include "gltf_builder.h"
#include "penumbra/scene.h"
#include "scratch_dir.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>

#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

struct Case {
    const char* name;
    std::function<fs::path(GltfBuilder&, const fs::path&)> make; // returns the file to load
    const char* expected; // the refusal, or the warning (empty: loads without a word)
};

using Edit = std::function<void(GltfBuilder&)>;

// The ground quad, changed, as .gltf (data URI).
auto gltf(Edit change) {
    return [change](GltfBuilder& b, const fs::path& d) {
        b.ground();
        change(b);
        return b.writeGltf(d / "a.gltf");
    };
}
// ... as .glb (buffer 0 the BIN chunk, declared as its length before `change`, which may say
// otherwise), then its bytes changed.
auto glb(Edit change, std::function<void(std::vector<uint8_t>&)> bytes = {}) {
    return [change, bytes](GltfBuilder& b, const fs::path& d) {
        b.ground();
        while (b.bin.size() % 4)
            b.bin.push_back(0);
        b.j["buffers"] = J::array({{{"byteLength", b.bin.size()}}});
        change(b);
        std::string json = b.j.dump();
        while (json.size() % 4)
            json += ' ';
        std::vector<uint8_t> v;
        auto u32 = [&](size_t x) {
            for (int k = 0; k < 4; ++k)
                v.push_back(static_cast<uint8_t>(x >> (8 * k)));
        };
        u32(0x46546C67), u32(2), u32(12 + 8 + json.size() + 8 + b.bin.size());
        u32(json.size()), u32(0x4E4F534A);
        v.insert(v.end(), json.begin(), json.end());
        u32(b.bin.size()), u32(0x004E4942);
        v.insert(v.end(), b.bin.begin(), b.bin.end());
        if (bytes)
            bytes(v);
        const fs::path f = d / "a.glb";
        std::ofstream(f, std::ios::binary)
            .write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size()));
        return f;
    };
}
// The ground's JSON text changed by `replace(text)` (what JSON objects cannot say).
auto text(std::function<void(std::string&)> replace) {
    return [replace](GltfBuilder& b, const fs::path& d) {
        b.ground();
        const fs::path f = b.writeGltf(d / "a.gltf");
        std::ifstream in(f);
        std::string t((std::istreambuf_iterator<char>(in)), {});
        replace(t);
        std::ofstream(f) << t;
        return f;
    };
}

// The ground with its buffer's data URI rewritten by `form` from the buffer's bytes and their
// base64.
auto dataUri(std::function<std::string(const std::vector<uint8_t>&, const std::string&)> form) {
    return [form](GltfBuilder& b, const fs::path& d) {
        b.ground();
        const fs::path f = b.writeGltf(d / "a.gltf");
        J j = J::parse(std::ifstream(f));
        const std::string uri = j["buffers"][0]["uri"];
        const std::string base64 = uri.substr(uri.find(',') + 1);
        j["buffers"][0]["uri"] = form(decodeBase64(base64), base64);
        std::ofstream(f) << j.dump();
        return f;
    };
}

J spot(double inner, double outer) {
    return {
        {"lights", J::array({{{"type", "spot"},
                              {"spot", {{"innerConeAngle", inner}, {"outerConeAngle", outer}}}}})}};
}
void addLight(GltfBuilder& b, const J& lights) {
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.j["extensions"] = {{"KHR_lights_punctual", lights}};
    b.node({{"translation", {0, 4, 0}},
            {"rotation", {-0.7071068, 0, 0, 0.7071068}},
            {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
}

fs::path caseDir(const char* table, const char* name) {
    return scratchDir("conformance", std::string(table) + "-" + name, true);
}

class GltfValid : public ::testing::TestWithParam<Case> {};
class GltfInvalid : public ::testing::TestWithParam<Case> {};
class GltfIgnoredPart : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(GltfValid, LoadsWithoutAWord) {
    GltfBuilder b;
    const fs::path f = GetParam().make(b, caseDir("valid", GetParam().name));
    std::vector<std::string> warnings;
    const Scene s = loadScene(f.string(), {.warnings = &warnings});
    EXPECT_EQ(s.triangleCount(), 2u) << "the ground";
    EXPECT_NEAR(s.bounds().max.x, 5.0f, 1e-6f);
    if (std::string(GetParam().expected).empty())
        EXPECT_TRUE(warnings.empty()) << warnings.front();
    else
        ASSERT_EQ(warnings.size(), 1u) << GetParam().expected;
    for (const std::string& w : warnings)
        EXPECT_NE(w.find(GetParam().expected), std::string::npos) << w;
}

INSTANTIATE_TEST_SUITE_P(
    Spec, GltfValid,
    ::testing::Values(
        Case{"integers_written_as_floats", // JSON Schema's integer admits 1.0
             text([](std::string& json) {
                 for (const char* key : {"\"mesh\":0", "\"indices\":1", "\"count\":4",
                                         "\"componentType\":5126", "\"buffer\":0"}) {
                     const size_t at = json.find(key);
                     ASSERT_NE(at, std::string::npos) << key;
                     json.insert(at + std::strlen(key), ".0");
                 }
             }),
             ""},
        Case{"skin_no_node_uses", gltf([](GltfBuilder& b) {
                 b.j["skins"] = {{{"joints", {0}}}};
             }),
             ""},
        Case{"morph_target_at_weight_zero", gltf([](GltfBuilder& b) {
                 b.j["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 0}}};
             }),
             ""},
        Case{"primitive_without_position", // the spec: skip the primitive
             gltf([](GltfBuilder& b) {
                 b.j["meshes"][0]["primitives"].push_back({{"attributes", {{"NORMAL", 0}}}});
             }),
             "meshes[0].primitives[1].attributes: POSITION is missing; such primitives are "
             "skipped"},
        Case{"accessor_without_buffer_view", // zeros, here replaced by sparse values
             gltf([](GltfBuilder& b) {
                 const std::vector<float> xyz = {-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5};
                 const int values = b.view(xyz);
                 const int indices = b.view(std::vector<uint8_t>{0, 1, 2, 3});
                 b.j["accessors"][0].erase("bufferView");
                 b.j["accessors"][0]["sparse"] = {
                     {"count", 4},
                     {"indices", {{"bufferView", indices}, {"componentType", 5121}}},
                     {"values", {{"bufferView", values}}}};
             }),
             ""},
        // Zeros, which its bounds need not describe (the validator does not hold them to zeros).
        Case{"accessor_without_buffer_view_bounds_not_its_zeros", gltf([](GltfBuilder& b) {
                 b.j["accessors"].push_back({{"type", "VEC3"},
                                             {"componentType", 5126},
                                             {"count", 4},
                                             {"min", {-1, -1, -1}},
                                             {"max", {1, 1, 1}}});
             }),
             ""},
        Case{"buffer_without_uri_that_nothing_drawn_reads", gltf([](GltfBuilder& b) {
                 b.j["buffers"] = J::array({J::object(), {{"byteLength", 4}}});
                 b.j["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 4}});
                 b.j["accessors"].push_back({{"type", "SCALAR"},
                                             {"componentType", 5126},
                                             {"count", 1},
                                             {"bufferView", b.j["bufferViews"].size() - 1}});
             }),
             "buffers[1]: no uri and so no data; nothing drawn reads it, so it is left out"},
        // A mesh no node places reads it, beside a node without a mesh: a missing index is no
        // index, not the second mesh.
        Case{"buffer_without_uri_read_by_a_mesh_no_node_places", gltf([](GltfBuilder& b) {
                 b.j["buffers"] = J::array({J::object(), {{"byteLength", 36}}});
                 b.j["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 36}});
                 b.j["accessors"].push_back({{"type", "VEC3"},
                                             {"componentType", 5126},
                                             {"count", 3},
                                             {"bufferView", b.j["bufferViews"].size() - 1},
                                             {"min", {0, 0, 0}},
                                             {"max", {1, 1, 1}}});
                 b.j["meshes"].push_back(
                     {{"primitives",
                       J::array({{{"attributes", {{"POSITION", b.j["accessors"].size() - 1}}}}})}});
                 b.node({{"name", "empty"}});
             }),
             "buffers[1]: no uri and so no data; nothing drawn reads it, so it is left out"},
        Case{"glb_with_bytes_after_its_length", // the validator's GLB_EXTRA_DATA
             glb([](GltfBuilder&) {}, [](std::vector<uint8_t>& v) { v.push_back(0); }),
             "GLB: 1 bytes after the header's length"},
        Case{"unused_image_with_a_name_too_long", // never read: no file-system error (fuzzer)
             gltf([](GltfBuilder& b) {
                 b.j["images"] = {{{"uri", std::string(5000, 'b') + ".png"}}};
             }),
             ""},
        Case{"glb_with_trailing_bytes", // after its chunks, inside the header's length
             glb([](GltfBuilder&) {},
                 [](std::vector<uint8_t>& v) {
                     v.insert(v.end(), 8, 0);
                     const uint32_t length = static_cast<uint32_t>(v.size());
                     std::memcpy(v.data() + 8, &length, 4);
                 }),
             ""},
        Case{"glb_placeholder_buffer_longer_than_its_chunk", glb([](GltfBuilder& b) {
                 b.j["buffers"] = J::array({{{"byteLength", 4096}}});
             }),
             "buffers[0].byteLength: 4096 bytes declared but the BIN chunk holds"},
        Case{"mesh_quantization", // normalized shorts scaled back by the node: the same ground
             gltf([](GltfBuilder& b) {
                 b.j["extensionsUsed"] = {"KHR_mesh_quantization"};
                 b.j["extensionsRequired"] = {"KHR_mesh_quantization"};
                 const std::vector<int16_t> q = {-32767, 0, -32767, 32767,  0, -32767,
                                                 32767,  0, 32767,  -32767, 0, 32767};
                 b.j["accessors"][0] = {{"bufferView", b.view(q)}, {"componentType", 5122},
                                        {"normalized", true},      {"count", 4},
                                        {"type", "VEC3"},          {"min", {-32767, 0, -32767}},
                                        {"max", {32767, 0, 32767}}};
                 b.j["nodes"][0]["scale"] = {5, 1, 5};
             }),
             ""},
        Case{"basisu_texture", // not decoded: the factor stands in, with a warning
             gltf([](GltfBuilder& b) {
                 b.j["extensionsUsed"] = {"KHR_texture_basisu"};
                 b.j["extensionsRequired"] = {"KHR_texture_basisu"};
                 const std::vector<uint8_t> ktx2 = {0xAB, 'K',  'T',  'X',  ' ', '2', '0', 0xBB,
                                                    '\r', '\n', 0x1A, '\n', 0,   0,   0,   0};
                 b.j["images"] = {{{"bufferView", b.view(ktx2)}, {"mimeType", "image/ktx2"}}};
                 b.j["textures"] = {
                     {{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}, {"source", 0}}};
                 b.j["materials"] = {{{"pbrMetallicRoughness",
                                       {{"baseColorTexture", {{"index", 0}}},
                                        {"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}}};
                 b.j["meshes"][0]["primitives"][0]["material"] = 0;
                 b.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = b.accessor(
                     b.view(std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}), 5126, 4, "VEC2");
             }),
             "images[0]: KTX2 (KHR_texture_basisu) is not decoded here"}),
    [](const auto& row) { return std::string(row.param.name); });

INSTANTIATE_TEST_SUITE_P(
    DataUris, GltfValid,
    ::testing::Values(
        // RFC 2397's other forms: percent-encoded (letters as they are), no media type, more
        // parameters before ;base64.
        Case{"data_uri_percent_encoded", dataUri([](const std::vector<uint8_t>& bytes, auto&) {
                 std::string uri = "data:application/gltf-buffer,";
                 for (uint8_t c : bytes)
                     uri += std::isalnum(c) ? std::string(1, char(c)) : fmt::format("%{:02X}", c);
                 return uri;
             }),
             ""},
        Case{"data_uri_without_media_type",
             dataUri([](auto&, const std::string& base64) { return "data:;base64," + base64; }),
             ""},
        Case{"data_uri_with_parameters", dataUri([](auto&, const std::string& base64) {
                 return "data:application/octet-stream;name=ground.bin;base64," + base64;
             }),
             ""}),
    [](const auto& row) { return std::string(row.param.name); });

TEST_P(GltfInvalid, IsRefusedWithItsJsonPath) {
    GltfBuilder b;
    const fs::path f = GetParam().make(b, caseDir("invalid", GetParam().name));
    expectRefused(f, GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
    ValidatorErrors, GltfInvalid,
    ::testing::Values(
        Case{"byte_order_mark", text([](std::string& json) { json.insert(0, "\xEF\xBB\xBF"); }),
             "the JSON starts with a byte-order mark"},
        // json.dump() recursed once a level and overflowed the stack (a break-test's file).
        // Brackets in a string, after an escaped quote, do not nest.
        Case{"nested_too_deep", text([](std::string& json) {
                 json.insert(json.rfind('}'), ",\"note\":\"\\\"" + std::string(600, '[') +
                                                  "\",\"extras\":" + std::string(100000, '[') +
                                                  std::string(100000, ']'));
             }),
             "the JSON nests 100001 levels deep (at most 512)"},
        // One level past the limit (the root object, then 512 arrays); 512 load (test_gltf.cpp).
        Case{"nested_one_past_the_limit", text([](std::string& json) {
                 json.insert(json.rfind('}'),
                             ",\"extras\":" + std::string(512, '[') + std::string(512, ']'));
             }),
             "the JSON nests 513 levels deep (at most 512)"},
        Case{"not_gltf_at_all",
             text([](std::string& json) { json = "solid cube\nfacet normal 0 0 1\n"; }),
             "not a glTF file: neither a JSON object nor a GLB"},
        Case{"spot_inner_not_below_outer",
             gltf([](GltfBuilder& b) { addLight(b, spot(0.6, 0.6)); }),
             "extensions.KHR_lights_punctual.lights[0].spot.innerConeAngle: 0.6 must be at least "
             "0 and less than outerConeAngle 0.6"},
        Case{"spot_outer_past_half_pi", gltf([](GltfBuilder& b) { addLight(b, spot(0.1, 1.6)); }),
             "extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle: 1.6 is outside (0, "
             "pi/2]"},
        Case{"skin_joint_out_of_range", gltf([](GltfBuilder& b) {
                 b.j["skins"] = {{{"joints", {0, 9}}}};
             }),
             "skins[0].joints[1]: index 9 is out of range (1 nodes)"},
        Case{"morph_target_not_vec3", gltf([](GltfBuilder& b) {
                 b.j["meshes"][0]["primitives"][0]["targets"] = {{{"NORMAL", 1}}};
             }),
             "meshes[0].primitives[0].targets[0].NORMAL: accessors[1] has 6 elements for the "
             "primitive's 4 vertices"},
        Case{"matrix_and_trs", gltf([](GltfBuilder& b) {
                 b.j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
                 b.j["nodes"][0]["scale"] = {2, 2, 2};
             }),
             "nodes[0]: has both a matrix and translation, rotation or scale"},
        Case{"rotation_not_unit", gltf([](GltfBuilder& b) {
                 b.j["nodes"][0]["rotation"] = {0, 0, 0, 1.01};
             }),
             "nodes[0].rotation: not a unit quaternion (length 1.01)"},
        Case{"min_not_the_data_minimum", gltf([](GltfBuilder& b) {
                 b.j["accessors"][0]["min"] = {-5, 0, -4};
             }),
             "accessors[0].min[2]: -4 but the data's minimum is -5"},
        Case{"max_not_the_data_maximum", gltf([](GltfBuilder& b) {
                 b.j["accessors"][0]["max"] = {5, 0.5, 5};
             }),
             "accessors[0].max[1]: 0.5 but the data's maximum is 0"},
        Case{"bounds_of_the_wrong_length", gltf([](GltfBuilder& b) {
                 b.j["accessors"][0]["min"] = {-5, 0};
             }),
             "accessors[0]: min and max need 3 numbers each"},
        Case{"quantized_without_the_extension", gltf([](GltfBuilder& b) {
                 b.j["accessors"][0]["componentType"] = 5122; // shorts: 24 bytes of the 48
                 b.j["accessors"][0].erase("min");
                 b.j["accessors"][0].erase("max");
             }),
             "integer types need KHR_mesh_quantization"},
        Case{"required_extension_unsupported",
             gltf([](GltfBuilder& b) { b.j["extensionsRequired"] = {"KHR_materials_sheen"}; }),
             "extensionsRequired: 'KHR_materials_sheen' is not supported"},
        Case{"buffer_without_uri_that_a_primitive_reads", gltf([](GltfBuilder& b) {
                 b.j["buffers"] = J::array({J::object(), {{"byteLength", 4096}}});
                 b.j["bufferViews"][0]["buffer"] = 1;
             }),
             "buffers[1].uri: missing, and a drawn primitive or an image reads the buffer"},
        Case{"glb_shorter_than_its_length",
             glb([](GltfBuilder&) {}, [](std::vector<uint8_t>& v) { v.resize(v.size() - 4); }),
             "GLB: header length"},
        Case{"data_uri_with_bad_percent_encoding",
             dataUri([](auto&, auto&) { return std::string("data:application/gltf-buffer,%G0"); }),
             "buffers[0].uri: data URI has malformed percent-encoding"},
        Case{"buffer_file_name_too_long", // ENAMETOOLONG: refused, not thrown (fuzzer)
             gltf([](GltfBuilder& b) {
                 b.j["buffers"] =
                     J::array({J::object(), {{"byteLength", 4}, {"uri", std::string(5000, 'a')}}});
             }),
             "buffers[1].uri: 'aaaa"},
        Case{"buffer_file_missing", gltf([](GltfBuilder& b) {
                 b.j["buffers"] = J::array({J::object(), {{"byteLength", 4}, {"uri", "gone.bin"}}});
             }),
             "buffers[1].uri: 'gone.bin' is not a file beside the asset"},
        Case{"sampler_filter_not_an_enum", gltf([](GltfBuilder& b) {
                 b.j["samplers"] = {{{"magFilter", 9986}}}; // a min filter
             }),
             "samplers[0].magFilter: 9986 is not a glTF magFilter value"},
        Case{"metallic_factor_past_one", gltf([](GltfBuilder& b) {
                 b.j["materials"] = {{{"pbrMetallicRoughness", {{"metallicFactor", 1.5}}}}};
             }),
             "materials[0].pbrMetallicRoughness.metallicFactor: 1.5 is outside [0, 1]"},
        Case{"normalized_floats",
             gltf([](GltfBuilder& b) { b.j["accessors"][0]["normalized"] = true; }),
             "accessors[0].normalized: only byte and short components can be normalized"},
        Case{"light_colour_past_one", gltf([](GltfBuilder& b) {
                 J lights = spot(0.2, 0.6);
                 lights["lights"][0]["color"] = {1.0, 2.0, 1.0};
                 addLight(b, lights);
             }),
             "extensions.KHR_lights_punctual.lights[0].color: 2 is outside [0, 1]"},
        Case{"camera_in_use_without_a_field_of_view", gltf([](GltfBuilder& b) {
                 b.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"znear", 0.1}}}}};
                 b.node({{"camera", 0}});
             }),
             "cameras[0].perspective.yfov: missing (required)"},
        Case{"scene_lists_a_child", gltf([](GltfBuilder& b) {
                 const int child = b.node({{"translation", {0, 1, 0}}}, false);
                 b.j["nodes"][0]["children"] = {child};
                 b.j["scenes"][0]["nodes"].push_back(child);
             }),
             "scenes[0].nodes[1]: node 1 is not a root (its parent is node 0)"},
        Case{"scene_lists_a_node_twice",
             gltf([](GltfBuilder& b) { b.j["scenes"][0]["nodes"].push_back(0); }),
             "scenes[0].nodes[1]: node 0 is listed twice"},
        Case{"extension_not_declared", gltf([](GltfBuilder& b) {
                 b.j["nodes"][0]["extensions"] = {{"EXT_example", J::object()}};
             }),
             "nodes[0].extensions.EXT_example: not declared in extensionsUsed"},
        Case{"required_but_not_used",
             gltf([](GltfBuilder& b) { b.j["extensionsRequired"] = {"KHR_mesh_quantization"}; }),
             "extensionsRequired: 'KHR_mesh_quantization' is not in extensionsUsed"},
        Case{"primitive_restart_index", gltf([](GltfBuilder& b) {
                 const std::vector<float> xyz(3 * 300, 0.0f);
                 b.j["accessors"][0] = {{"bufferView", b.view(xyz)},
                                        {"componentType", 5126},
                                        {"count", 300},
                                        {"type", "VEC3"},
                                        {"min", {0, 0, 0}},
                                        {"max", {0, 0, 0}}};
                 b.j["accessors"][1] = {
                     {"bufferView", b.view(std::vector<uint8_t>{0, 255, 1, 0, 0, 0})},
                     {"componentType", 5121},
                     {"count", 6},
                     {"type", "SCALAR"}};
             }),
             "meshes[0]: index 255 is the primitive-restart value"},
        Case{"name_not_a_string", gltf([](GltfBuilder& b) { b.j["scenes"][0]["name"] = 42; }),
             "scenes[0].name: wrong JSON type (a string is expected)"},
        Case{"extension_not_an_object", gltf([](GltfBuilder& b) {
                 b.j["extensionsUsed"] = {"KHR_texture_transform"};
                 b.j["nodes"][0]["extensions"] = {{"KHR_texture_transform", "Not an object"}};
             }),
             "nodes[0].extensions.KHR_texture_transform: wrong JSON type (an object is expected)"},
        Case{"normal_not_unit_length", gltf([](GltfBuilder& b) {
                 const std::vector<float> n = {0, 1, 0, 0, 1, 0, 0, 1.01f, 0, 0, 1, 0};
                 b.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
                     b.accessor(b.view(n), 5126, 4, "VEC3");
             }),
             "meshes[0].primitives[0].attributes.NORMAL: normal 2 has length 1.01, not 1"},
        Case{"texture_coordinate_not_finite", gltf([](GltfBuilder& b) {
                 const float inf = std::numeric_limits<float>::infinity();
                 const std::vector<float> uv = {0, 0, 1, 0, inf, 1, 0, 1};
                 b.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
                     b.accessor(b.view(uv), 5126, 4, "VEC2");
             }),
             "attributes.TEXCOORD_0: element 2 is NaN or infinite"},
        Case{"texcoord_set_missing", gltf([](GltfBuilder& b) {
                 b.j["images"] = {{{"uri", "data:image/png;base64,AAAA"}}};
                 b.j["textures"] = {{{"source", 0}}};
                 b.j["materials"] = {{{"normalTexture", {{"index", 0}, {"texCoord", 1}}}}};
                 b.j["meshes"][0]["primitives"][0]["material"] = 0;
             }),
             "meshes[0].primitives[0].attributes: no TEXCOORD_1 for materials[0].normalTexture"},
        Case{"shared_vertex_view_without_stride", gltf([](GltfBuilder& b) {
                 b.j["accessors"].push_back(b.j["accessors"][0]);
                 b.j["accessors"].back().erase("min");
                 b.j["accessors"].back().erase("max");
                 b.j["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] =
                     b.j["accessors"].size() - 1;
             }),
             "bufferViews[0].byteStride: required: 2 vertex accessors share the view"},
        Case{"index_view_with_stride", gltf([](GltfBuilder& b) {
                 const std::vector<uint16_t> strided = {0, 0, 2, 0, 1, 0, 0, 0, 3, 0, 2, 0};
                 b.j["accessors"][1]["bufferView"] = b.view(strided, 4);
             }),
             "meshes[0].primitives[0].indices: its bufferView must not have a byteStride"},
        Case{"accessor_misaligned_in_its_buffer", gltf([](GltfBuilder& b) {
                 b.bin.insert(b.bin.begin(), 2, 0); // every view moves by 2 bytes
                 for (auto& v : b.j["bufferViews"])
                     v["byteOffset"] = v.value("byteOffset", 0) + 2;
             }),
             "accessors[0]: starts at buffer byte 2, not a multiple of its component size 4"},
        Case{"sparse_indices_not_increasing", gltf([](GltfBuilder& b) {
                 const std::vector<float> xyz = {-5, 0, -5, 5, 0, -5};
                 b.j["accessors"][0]["sparse"] = {
                     {"count", 2},
                     {"indices",
                      {{"bufferView", b.view(std::vector<uint8_t>{1, 1})},
                       {"componentType", 5121}}},
                     {"values", {{"bufferView", b.view(xyz)}}}};
             }),
             "accessors[0].sparse.indices[1]: 1 does not follow 1"},
        Case{"translation_of_two_numbers", gltf([](GltfBuilder& b) {
                 b.j["nodes"][0]["translation"] = {1, 2};
             }),
             "nodes[0].translation: needs 3 numbers"},
        Case{"matrix_with_a_projection", gltf([](GltfBuilder& b) {
                 b.j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1};
             }),
             "nodes[0].matrix: is not a translation, rotation and scale"},
        Case{"only_lines", // valid, and nothing to draw: said so
             gltf([](GltfBuilder& b) { b.j["meshes"][0]["primitives"][0]["mode"] = 1; }),
             "the default scene has no triangles, only points or lines"},
        Case{"view_past_a_placeholder_chunk", glb([](GltfBuilder& b) {
                 b.j["buffers"] = J::array({{{"byteLength", 4096}}});
                 b.j["bufferViews"][1]["byteOffset"] = 4000;
             }),
             "bufferViews[1]"}),
    [](const auto& row) { return std::string(row.param.name); });

TEST_P(GltfIgnoredPart, LoadsWithOneWarningNamingIt) {
    GltfBuilder b;
    const fs::path f = GetParam().make(b, caseDir("ignored", GetParam().name));
    std::vector<std::string> warnings;
    const Scene s = loadScene(f.string(), {.warnings = &warnings});
    EXPECT_EQ(s.triangleCount(), 2u);
    bool named = false;
    for (const std::string& w : warnings) {
        named = named || w.find(GetParam().expected) != std::string::npos;
        EXPECT_EQ(w.rfind(f.string() + ": ", 0), 0u) << "names the file: " << w;
    }
    EXPECT_TRUE(named) << GetParam().expected << "\nwarnings:\n"
                       << (warnings.empty() ? "none" : warnings.front());
}

INSTANTIATE_TEST_SUITE_P(
    UnusedParts, GltfIgnoredPart,
    ::testing::Values(
        Case{"animation", gltf([](GltfBuilder& b) {
                 const int time = b.accessor(b.view(std::vector<float>{0, 1}), 5126, 2, "SCALAR");
                 const int scale =
                     b.accessor(b.view(std::vector<float>{1, 1, 1, 2, 2, 2}), 5126, 2, "VEC3");
                 b.j["animations"] = {
                     {{"channels",
                       {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "scale"}}}}}},
                      {"samplers", {{{"input", time}, {"output", scale}}}}}};
             }),
             "animations: 1 animation(s); the scene is drawn at rest (--time T poses it in "
             "animation '0', 1 s long)"},
        Case{"camera_aspect_ratio", gltf([](GltfBuilder& b) {
                 b.j["cameras"] = {
                     {{"type", "perspective"},
                      {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"aspectRatio", 2.0}}}}};
                 b.node({{"camera", 0}, {"translation", {0, 3, 9}}});
             }),
             "cameras[0].perspective.aspectRatio: ignored"},
        Case{"material_extension", gltf([](GltfBuilder& b) {
                 b.j["extensionsUsed"] = {"KHR_materials_clearcoat"};
                 b.j["materials"] = {{{"extensions", {{"KHR_materials_clearcoat", J::object()}}}}};
                 b.j["meshes"][0]["primitives"][0]["material"] = 0;
             }),
             "materials[0].extensions.KHR_materials_clearcoat: not used"},
        Case{"unused_camera_without_a_field_of_view", gltf([](GltfBuilder& b) {
                 b.j["cameras"] = {
                     {{"type", "perspective"}, {"perspective", {{"yfov", 0}, {"znear", 0.1}}}}};
             }),
             "cameras[0]: perspective: yfov and znear must be positive, zfar past znear; the "
             "camera is not used"},
        Case{"texture_transform", gltf([](GltfBuilder& b) {
                 b.j["extensionsUsed"] = {"KHR_texture_transform"};
                 const std::vector<uint8_t> ktx2 = {0xAB, 'K',  'T',  'X',  ' ', '2', '0', 0xBB,
                                                    '\r', '\n', 0x1A, '\n', 0,   0,   0,   0};
                 b.j["images"] = {{{"bufferView", b.view(ktx2)}, {"mimeType", "image/ktx2"}}};
                 b.j["textures"] = {{{"source", 0}}};
                 b.j["materials"] = {
                     {{"pbrMetallicRoughness",
                       {{"baseColorTexture",
                         {{"index", 0},
                          {"extensions", {{"KHR_texture_transform", {{"scale", {2, 2}}}}}}}}}}}};
             }),
             "images[0]: KTX2 (KHR_texture_basisu) is not decoded here"},
        Case{"position_without_bounds", gltf([](GltfBuilder& b) {
                 b.j["accessors"][0].erase("min");
                 b.j["accessors"][0].erase("max");
             }),
             "accessors[0]: a POSITION accessor without min and max"}),
    [](const auto& row) { return std::string(row.param.name); });
