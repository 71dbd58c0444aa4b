// glTF loading: valid assets the tests generate, and a table of malformed ones, one per refusal
// class, each refused by name (file and JSON path) without a crash.
#include "expect_refused.h"
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path dir() {
    return scratchDir("gltf");
}

Scene load(const fs::path& f, std::vector<std::string>* warnings = nullptr) {
    return loadScene(f.string(), {.warnings = warnings});
}

} // namespace

TEST(Gltf, LoadsMeshesLightsAndCamerasFromDataUriExternalBinAndGlb) {
    for (int form = 0; form < 3; ++form) {
        GltfBuilder b = floatingQuad();
        const fs::path f = form == 2 ? b.writeGlb(dir() / "quad.glb")
                                     : b.writeGltf(dir() / "quad.gltf", form == 1);
        const Scene s = load(f);
        EXPECT_EQ(s.triangleCount(), 2u + 2u) << form; // ground + fan of 4 = 2 triangles
        ASSERT_EQ(s.lights.size(), 1u);
        EXPECT_EQ(s.lights[0].type, LightType::Directional);
        EXPECT_NEAR(s.lights[0].direction.y, -1.0f, 1e-3f); // -Z rotated down
        EXPECT_FLOAT_EQ(s.lights[0].angularDiameter, 2.5f);
        ASSERT_EQ(s.cameras.size(), 1u);
        EXPECT_EQ(s.camera("eye").position, glm::vec3(0, 6, 9));
        EXPECT_NEAR(s.bounds().max.y, 2.0f, 1e-6f);
    }
}

TEST(Gltf, StripsAndFansBecomeTriangleLists) {
    GltfBuilder b;
    std::vector<float> xyz;
    for (int i = 0; i < 6; ++i)
        xyz.insert(xyz.end(), {float(i / 2), 0.0f, float(i % 2)});
    const int p = b.positions(xyz);
    b.node({{"mesh", b.mesh(p, -1, 5)}}); // strip of 6 vertices: 4 triangles
    b.node({{"mesh", b.mesh(p, -1, 6)}}); // fan of 6: 4 triangles
    b.node({{"mesh", b.mesh(p, -1, 1)}}); // lines: skipped with a warning
    std::vector<std::string> warnings;
    const Scene s = load(b.writeGltf(dir() / "strips.gltf"), &warnings);
    EXPECT_EQ(s.triangleCount(), 8u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("points or lines"), std::string::npos);
    // Strip winding alternates so every triangle faces the same side (+y here or -y, all alike).
    float first = 0;
    for (size_t t = 0; t < 4; ++t) {
        const auto& v = s.vertices;
        const glm::vec3 n =
            glm::cross(v[s.indices[3 * t + 1]].position - v[s.indices[3 * t]].position,
                       v[s.indices[3 * t + 2]].position - v[s.indices[3 * t]].position);
        if (t == 0)
            first = n.y;
        EXPECT_GT(n.y * first, 0.0f) << t;
    }
}

// Triangles without area are dropped with one warning that counts them and names the meshes
// most come from (the three largest, then the rest summed); a scene without any gets none.
TEST(Gltf, TrianglesWithoutAreaAreCountedAndTheirMeshesNamed) {
    GltfBuilder b;
    b.ground();
    // Six vertices on a line: a strip of four triangles, every one without area.
    const int line = b.positions({0, 1, 0, 1, 1, 0, 2, 1, 0, 3, 1, 0, 4, 1, 0, 5, 1, 0});
    // One real triangle and one repeating a corner.
    const int p = b.positions({0, 2, 0, 1, 2, 0, 0, 2, 1});
    const int someFlat =
        b.accessor(b.view(std::vector<uint16_t>{0, 2, 1, 0, 0, 1}), 5123, 6, "SCALAR");
    const int meshes[] = {b.mesh(line, -1, 5), b.mesh(p, someFlat), b.mesh(line, -1, 5),
                          b.mesh(line, -1, 5), b.mesh(p, someFlat)};
    const char* names[] = {"wire", "chip", "", "rail", "chip2"};
    for (int k = 0; k < 5; ++k) {
        if (*names[k])
            b.j["meshes"][meshes[k]]["name"] = names[k];
        b.node({{"mesh", meshes[k]}});
    }
    std::vector<std::string> warnings;
    const Scene s = load(b.writeGltf(dir() / "flat.gltf"), &warnings);
    EXPECT_EQ(s.triangleCount(), 2u + 2u) << "the ground and the two real triangles";
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("flat.gltf: 14 triangles without area"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[0].find("dropped: 4 in meshes[1] 'wire', 4 in meshes[3], 4 in meshes[4] "
                               "'rail', 2 in 2 other meshes"),
              std::string::npos)
        << warnings[0];

    // One: "1 triangle", singular.
    GltfBuilder one;
    one.ground();
    const int chip = one.positions({0, 2, 0, 1, 2, 0, 0, 2, 1});
    one.node(
        {{"mesh", one.mesh(chip, one.accessor(one.view(std::vector<uint16_t>{0, 2, 1, 0, 0, 1}),
                                              5123, 6, "SCALAR"))}});
    warnings.clear();
    load(one.writeGltf(dir() / "one-flat.gltf"), &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("one-flat.gltf: 1 triangle without area"), std::string::npos)
        << warnings[0];

    GltfBuilder clean = floatingQuad();
    warnings.clear();
    load(clean.writeGltf(dir() / "clean.gltf"), &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

TEST(Gltf, EveryIndexComponentTypeAndStridedSparsePositions) {
    GltfBuilder b = componentTypes();
    const Scene s = load(b.writeGltf(dir() / "types.gltf"));
    // Two triangles per index type, one strided, one from a sparse accessor without a view.
    EXPECT_EQ(s.triangleCount(), 3u * 2u + 1u + 1u);
    EXPECT_FLOAT_EQ(s.bounds().max.x, 1.0f) << "the sparse value replaced (9, 9, 9)";
    EXPECT_FLOAT_EQ(s.bounds().max.z, 3.0f) << "the strided accessor";
}

TEST(Gltf, NodeTransformsComposeThroughTheHierarchy) {
    GltfBuilder b;
    const int p = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int mesh = b.mesh(p);
    const int leaf = b.node({{"mesh", mesh}, {"scale", {2, 2, 2}}}, false);
    const int mid =
        b.node({{"children", {leaf}}, {"rotation", {0, 0, 0.7071068, 0.7071068}}}, false);
    b.node({{"children", {mid}}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}}});
    const Scene s = load(b.writeGltf(dir() / "tree.gltf"));
    // (1,0,0) -> scale 2 -> rotate 90 deg about z -> (0,2,0) -> translate x by 10.
    EXPECT_NEAR(s.vertices[1].position.x, 10.0f, 1e-5f);
    EXPECT_NEAR(s.vertices[1].position.y, 2.0f, 1e-5f);
    // Missing normals were computed and point along the rotated face normal (+z).
    EXPECT_NEAR(std::abs(s.vertices[0].normal.z), 1.0f, 1e-5f);
}

TEST(Gltf, DeepHierarchiesAreWalkedWithoutRecursion) {
    GltfBuilder b;
    const int mesh = b.mesh(b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0}));
    const int depth = 100000;
    b.j["nodes"] = nlohmann::json::array();
    for (int i = 0; i < depth; ++i) {
        nlohmann::json n = {{"translation", {0.0, 0.0001, 0.0}}};
        if (i + 1 < depth)
            n["children"] = {i + 1};
        else
            n["mesh"] = mesh;
        b.j["nodes"].push_back(n);
    }
    b.j["scenes"][0]["nodes"] = {0};
    const Scene s = load(b.writeGltf(dir() / "deep.gltf"));
    EXPECT_NEAR(s.vertices[0].position.y, 10.0f, 1e-2f);
}

// JSON nested as deep as the loader allows (the root object, then 511 arrays in its extras) loads;
// one level more is refused (test_gltf_conformance.cpp).
TEST(Gltf, JsonNestedToTheLimitLoads) {
    GltfBuilder b;
    b.ground();
    nlohmann::json deep = nlohmann::json::array();
    for (int level = 1; level < 511; ++level)
        deep = nlohmann::json::array({deep});
    b.j["extras"] = deep;
    EXPECT_GT(load(b.writeGltf(dir() / "deepest.gltf")).triangleCount(), 0u);
}

TEST(Gltf, SpotAndPointLightsCamerasAndDefaults) {
    GltfBuilder b;
    b.ground();
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
            {"translation", {0, 5, 0}},
            {"rotation", {-0.7071, 0, 0, 0.7071}}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}, {"translation", {1, 3, 0}}});
    b.node({{"camera", 0}, {"translation", {0, 10, 0}}, {"rotation", {-0.7071, 0, 0, 0.7071}}});
    b.j["cameras"] = {{{"type", "orthographic"},
                       {"orthographic", {{"xmag", 6}, {"ymag", 6}, {"znear", 0.1}, {"zfar", 50}}}}};
    b.j["extensions"] = {{"KHR_lights_punctual",
                          {{"lights",
                            {{{"type", "spot"},
                              {"intensity", 20},
                              {"range", 30},
                              {"spot", {{"innerConeAngle", 0.3}, {"outerConeAngle", 0.6}}},
                              {"extras", {{"radius", 0.25}}}},
                             {{"type", "point"}, {"intensity", 5}}}}}}};
    const Scene s = load(b.writeGltf(dir() / "lights.gltf"));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    EXPECT_FLOAT_EQ(s.lights[0].outerConeAngle, 0.6f);
    EXPECT_FLOAT_EQ(s.lights[0].radius, 0.25f);
    EXPECT_EQ(s.lights[1].type, LightType::Point);
    EXPECT_TRUE(s.cameras.at(0).orthographic);
    EXPECT_FLOAT_EQ(s.cameras[0].ymag, 6.0f);

    GltfBuilder bare; // no light, no camera: a default sun and an automatic framing
    bare.ground();
    const Scene d = load(bare.writeGltf(dir() / "bare.gltf"));
    ASSERT_EQ(d.lights.size(), 1u);
    EXPECT_EQ(d.lights[0].type, LightType::Directional);
    ASSERT_EQ(d.cameras.size(), 1u) << "the loader adds the measured automatic camera";
    EXPECT_EQ(d.camera("").name, "auto (exterior)");
}

namespace {

struct Malformed {
    const char* name;
    std::function<fs::path(GltfBuilder&, const fs::path&)> make; // returns the file to load
    const char* expected;                                        // in the message
};

std::vector<Malformed> malformedAssets() {
    auto edit = [](std::function<void(GltfBuilder&)> change) {
        return [change](GltfBuilder& b, const fs::path& d) {
            b.ground();
            change(b);
            return b.writeGltf(d / "bad.gltf");
        };
    };
    auto raw = [](std::string text) {
        return [text](GltfBuilder&, const fs::path& d) {
            std::ofstream(d / "raw.gltf") << text;
            return d / "raw.gltf";
        };
    };
    auto glb = [](std::function<void(std::vector<uint8_t>&)> change) {
        return [change](GltfBuilder& b, const fs::path& d) {
            b.ground();
            const fs::path f = b.writeGlb(d / "bad.glb");
            std::ifstream in(f, std::ios::binary);
            std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
            change(bytes);
            std::ofstream(f, std::ios::binary)
                .write(reinterpret_cast<const char*>(bytes.data()),
                       static_cast<std::streamsize>(bytes.size()));
            return f;
        };
    };
    using J = nlohmann::json;
    return {
        {"not_json", raw("{ this is not json"), "not valid JSON"},
        {"glTF_1", raw(R"({"asset":{"version":"1.0"}})"), "asset.version: '1.0' is not supported"},
        {"no_asset", raw(R"({"scenes":[]})"), "asset.version: missing"},
        {"instancing_required",
         edit([](GltfBuilder& b) { b.j["extensionsRequired"] = {"EXT_mesh_gpu_instancing"}; }),
         "extensionsRequired: 'EXT_mesh_gpu_instancing' is not supported"},
        // (buffers[0] is the builder's; the hostile URI is a second buffer)
        {"uri_parent", edit([](GltfBuilder& b) {
             b.j["buffers"] =
                 J::array({J::object(), {{"uri", "../secret.bin"}, {"byteLength", 4}}});
         }),
         "buffers[1].uri: URIs may not leave the asset's folder"},
        {"uri_absolute", edit([](GltfBuilder& b) {
             b.j["buffers"] = J::array({J::object(), {{"uri", "/etc/passwd"}, {"byteLength", 4}}});
         }),
         "buffers[1].uri: absolute URIs are not supported"},
        {"uri_shell", edit([](GltfBuilder& b) {
             b.j["buffers"] = J::array({J::object(), {{"uri", "$HOME.bin"}, {"byteLength", 4}}});
         }),
         "refused character '$'"},
        {"uri_bad_base64", edit([](GltfBuilder& b) {
             b.j["buffers"] = J::array(
                 {J::object(),
                  {{"uri", "data:application/octet-stream;base64,@@@@"}, {"byteLength", 3}}});
         }),
         "buffers[1].uri: data URI has malformed base64"},
        {"wrong_json_type", edit([](GltfBuilder& b) { b.j["nodes"][0]["mesh"] = "zero"; }),
         "nodes[0].mesh: wrong JSON type"},
        {"view_past_buffer",
         edit([](GltfBuilder& b) { b.j["bufferViews"][0]["byteLength"] = 100000; }),
         "bufferViews[0]: bytes 0..100000 run past buffer 0"},
        {"bad_stride", edit([](GltfBuilder& b) { b.j["bufferViews"][0]["byteStride"] = 6; }),
         "bufferViews[0].byteStride: 6 is not a multiple of 4"},
        {"accessor_past_view", edit([](GltfBuilder& b) { b.j["accessors"][0]["count"] = 40; }),
         "accessors[0]: 40 elements need bytes"},
        {"count_zero", edit([](GltfBuilder& b) { b.j["accessors"][0]["count"] = 0; }),
         "accessors[0].count: must be at least 1"},
        {"count_overflow",
         edit([](GltfBuilder& b) { b.j["accessors"][0]["count"] = 4611686018427387904ull; }),
         "byte range overflows"},
        {"indices_out_of_range",
         edit([](GltfBuilder& b) { b.j["meshes"][0]["primitives"][0]["indices"] = 99; }),
         "meshes[0].primitives[0].indices: index 99 is out of range (2 accessors)"},
        {"index_value_past_vertices", edit([](GltfBuilder& b) {
             b.j["accessors"][1]["bufferView"] = b.view(std::vector<uint16_t>{0, 2, 77, 0, 3, 2});
         }),
         "index 77 is past the 4 vertices"},
        {"child_out_of_range", edit([](GltfBuilder& b) { b.j["nodes"][0]["children"] = {5}; }),
         "nodes[0].children[0]: index 5 is out of range"},
        {"node_cycle", edit([](GltfBuilder& b) {
             b.j["nodes"].push_back({{"children", {2}}});
             b.j["nodes"].push_back({{"children", {1}}});
         }),
         "is its own ancestor"},
        {"two_parents", edit([](GltfBuilder& b) {
             b.j["nodes"].push_back({{"children", {0}}});
             b.j["nodes"].push_back({{"children", {0}}});
         }),
         "already has parent"},
        {"mesh_out_of_range", edit([](GltfBuilder& b) { b.j["nodes"][0]["mesh"] = 3; }),
         "nodes[0].mesh: index 3 is out of range (1 meshes)"},
        {"material_out_of_range",
         edit([](GltfBuilder& b) { b.j["meshes"][0]["primitives"][0]["material"] = 2; }),
         "primitives[0].material: index 2 is out of range"},
        {"scene_out_of_range", edit([](GltfBuilder& b) { b.j["scene"] = 4; }),
         "scene: index 4 is out of range (1 scenes)"},
        {"infinite_scale",
         [](GltfBuilder& b, const fs::path& d) { // JSON cannot hold infinity
             b.ground();
             b.j["nodes"][0]["scale"] = {1.0, 12345.5, 1.0};
             const fs::path f = b.writeGltf(d / "bad.gltf");
             std::ifstream in(f);
             std::string text((std::istreambuf_iterator<char>(in)), {});
             text.replace(text.find("12345.5"), 7, "1e999");
             std::ofstream(f) << text;
             return f;
         },
         "not valid JSON"}, // nlohmann refuses the overflowing literal; NaN has no JSON spelling
        {"nan_position", edit([](GltfBuilder& b) {
             const float nan = std::numeric_limits<float>::quiet_NaN();
             b.j["accessors"][0]["bufferView"] =
                 b.view(std::vector<float>{-5, 0, -5, nan, 0, -5, 5, 0, 5, -5, 0, 5});
         }),
         "attributes.POSITION: element 1 is NaN or infinite"},
        {"degenerate_only", // every corner on one line: triangles without area, all dropped
         edit([](GltfBuilder& b) {
             b.j["accessors"][0]["bufferView"] =
                 b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0});
             b.j["accessors"][0]["min"] = {0, 0, 0};
             b.j["accessors"][0]["max"] = {3, 0, 0};
         }),
         "its 2 triangles are without area or past the coordinate limit"},
        {"missing_position", // the spec: skip the primitive; it was the only one
         edit([](GltfBuilder& b) {
             b.j["meshes"][0]["primitives"][0]["attributes"] = {{"NORMAL", 0}};
         }),
         "the default scene has no triangles"},
        {"position_vec2", edit([](GltfBuilder& b) { b.j["accessors"][0]["type"] = "VEC2"; }),
         "attributes.POSITION: wrong accessor type"},
        {"float_indices", edit([](GltfBuilder& b) {
             b.j["accessors"][1]["componentType"] = 5126;
             b.j["accessors"][1]["bufferView"] = b.view(std::vector<float>{0, 2, 1, 0, 3, 2});
         }),
         "indices: must be unsigned byte, short or int"},
        {"sparse_index_out_of_range", edit([](GltfBuilder& b) {
             b.j["accessors"][0]["sparse"] = {
                 {"count", 1},
                 {"indices",
                  {{"bufferView", b.view(std::vector<uint16_t>{9, 0})}, {"componentType", 5123}}},
                 {"values", {{"bufferView", b.view(std::vector<float>{0, 0, 0})}}}};
         }),
         "sparse.indices[0]: 9 is out of range"},
        {"glb_version", glb([](std::vector<uint8_t>& v) { v[4] = 1; }),
         "GLB: version 1 is not supported"},
        {"glb_length", glb([](std::vector<uint8_t>& v) { v[8] += 4; }), "GLB: header length"},
        {"glb_chunk_type", glb([](std::vector<uint8_t>& v) { v[16] = 'X'; }),
         "GLB: the first chunk is not JSON"},
        {"glb_bin_past_end", glb([](std::vector<uint8_t>& v) {
             const uint32_t json = v[12] | v[13] << 8 | v[14] << 16 | uint32_t(v[15]) << 24;
             v[20 + json + 1] = 0x7F;
         }),
         "GLB: BIN chunk length"},
        {"light_type", edit([](GltfBuilder& b) {
             b.j["extensionsUsed"] = {"KHR_lights_punctual"};
             b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
             b.j["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "laser"}}}}}}};
         }),
         "lights[0].type: 'laser' is not a light type"},
        {"missing_file", [](GltfBuilder&, const fs::path& d) { return d / "nowhere.gltf"; },
         "cannot read"},
    };
}

class GltfRefuses : public ::testing::TestWithParam<Malformed> {};

} // namespace

TEST_P(GltfRefuses, WithTheFileAndWhatIsWrong) {
    GltfBuilder b;
    const fs::path d = dir() / GetParam().name;
    fs::create_directories(d);
    expectRefused(GetParam().make(b, d), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(Assets, GltfRefuses, ::testing::ValuesIn(malformedAssets()),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(Gltf, FilesPastTheSizeCapAreRefused) {
    GltfBuilder b;
    b.ground();
    const fs::path f = b.writeGltf(dir() / "big.gltf");
    EXPECT_THROW(loadScene(f.string(), {.maxFileSize = 64}), InputError);
    GltfBuilder e;
    e.ground();
    e.view(std::vector<float>(4096, 0.0f)); // a 16 KiB .bin beside a small .gltf
    const fs::path external = e.writeGltf(dir() / "ext.gltf", true);
    EXPECT_NO_THROW(loadScene(external.string()));
    EXPECT_THROW(loadScene(external.string(), {.maxFileSize = 4096}), InputError)
        << "the external .bin is capped too";
}
