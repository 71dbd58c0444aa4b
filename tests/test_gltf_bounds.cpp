// The glTF loader's bounds at their exact boundaries (gltf_bounds.h says how a row works):
// accessors, sparse accessors, primitives, materials, nodes, cameras and lights, caps and images;
// the container's rows are in test_gltf_bounds_container.cpp. Also: image views far past their
// buffer, and the coverage lookups at their edges.
#include "gltf_bounds.h"

using namespace penumbra;
using namespace penumbra::test;
using namespace penumbra::test::bounds;

namespace {

std::vector<Boundary> contentBoundaries() {
    const uint64_t u64max = std::numeric_limits<uint64_t>::max();
    return {
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
        {"component_type_above_float",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<float>{1}), past ? 5127 : 5126, 1, "SCALAR");
              }),
         "accessors[4].componentType: 5127 is not a glTF component type"},
        {"component_type_below_byte",
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.accessor(b.view(std::vector<uint8_t>{1}), past ? 5119 : 5120, 1, "SCALAR");
              }),
         "accessors[4].componentType: 5119 is not a glTF component type"},
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
         "accessors[1].componentType: 5124 is not a glTF component type"},
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
         "cameras[0]: perspective: yfov and znear must be positive"},
        {"camera_zfar_above_znear", // znear 0.1 (as a float)
         gltf(floatingQuad, cameraValue("zfar", floatAbove(0.1f), double(0.1f))),
         "cameras: 'eye' has invalid parameters"},
        {"camera_zfar_zero_is_infinite", // 0 means absent (infinite); any positive one is used
         gltf(floatingQuad, cameraValue("zfar", 0.0, kTinyPositive)),
         "cameras[0]: perspective: yfov and znear must be positive, zfar past znear"},
        {"camera_yfov_positive", gltf(floatingQuad, cameraValue("yfov", kTinyPositive, 0.0)),
         "cameras[0]: perspective: yfov and znear must be positive"},
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
         "cameras[0]: orthographic: xmag and ymag must not be 0"},
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
        {"light_radius_maximum",
         gltf(floatingQuad, lightValue([](J& l) -> J& { return l["extras"]["radius"]; },
                                       double(kMaxCoordinate), floatAbove(kMaxCoordinate))),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},
        {"light_angular_diameter_past_32_bits", // the integer 2^32 + 30: 30 in 32 bits
         gltf(floatingQuad,
              [](GltfBuilder& b, bool past) {
                  b.j["extensions"]["KHR_lights_punctual"]["lights"][0]["extras"]
                     ["angularDiameter"] = past ? J(int64_t{4294967326}) : J(30);
              }),
         "KHR_lights_punctual.lights[0]: invalid intensity or size"},
        {"light_range_positive", // 0: absent, as tinygltf reads it
         gltf(floatingQuad, lightValue([](J& l) -> J& { return l["range"]; }, 0.0, -kTinyPositive)),
         "KHR_lights_punctual.lights[0]: range -"},
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
    };
}

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

INSTANTIATE_TEST_SUITE_P(Content, GltfBounds, ::testing::ValuesIn(contentBoundaries()),
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
