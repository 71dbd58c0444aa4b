// glTF materials: base-colour textures (PNG from a bufferView, a data URI or a file), samplers,
// texture coordinate sets, vertex colours, alpha modes, doubleSided, and the refusals of bad
// images and references. Scene::coverage is the CPU alpha test the ground truth uses.
#include "core/image_io.h"
#include "expect_refused.h"
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <functional>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

fs::path dir(const std::string& name) {
    return scratchDir("materials", name);
}

// 2x2 RGBA: alpha 255, 0 on the top row; 64, 192 on the bottom.
const std::vector<uint8_t> kPixels = {255, 0, 0,   255, 0,   255, 0,   0,
                                      0,   0, 255, 64,  255, 255, 255, 192};

std::vector<uint8_t> png() {
    return encodePng(2, 2, 4, kPixels);
}

// A quad at y = 2 with TEXCOORD_0 (normalized ubyte), TEXCOORD_1 (float) and COLOR_0
// (normalized ushort VEC3), material 0 textured and alpha-tested, over a ground without a
// material. The image comes from a bufferView.
GltfBuilder texturedQuad() {
    GltfBuilder b;
    b.ground();
    const int p = b.positions({-1, 2, -1, 1, 2, -1, 1, 2, 1, -1, 2, 1});
    const int uv0 = b.accessor(b.view(std::vector<uint8_t>{0, 0, 255, 0, 255, 255, 0, 255}), 5121,
                               4, "VEC2", true);
    const int uv1 = b.accessor(
        b.view(std::vector<float>{0.25f, 0.25f, 0.75f, 0.25f, 0.75f, 0.75f, 0.25f, 0.75f}), 5126, 4,
        "VEC2");
    const int color = b.accessor(
        b.view(std::vector<uint16_t>{65535, 0, 0, 0, 65535, 0, 0, 0, 65535, 65535, 65535, 65535}),
        5123, 4, "VEC3", true);
    const int idx = b.accessor(b.view(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}), 5123, 6, "SCALAR");
    const int mesh = b.mesh(p, idx);
    auto& prim = b.j["meshes"][mesh]["primitives"][0];
    prim["attributes"]["TEXCOORD_0"] = uv0;
    prim["attributes"]["TEXCOORD_1"] = uv1;
    prim["attributes"]["COLOR_0"] = color;
    prim["material"] = 0;
    b.node({{"mesh", mesh}});
    const std::vector<uint8_t> image = png();
    b.j["images"] = J::array({{{"bufferView", b.view(image)}, {"mimeType", "image/png"}}});
    b.j["samplers"] = J::array({{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}});
    b.j["textures"] = J::array({{{"source", 0}, {"sampler", 0}}});
    b.j["materials"] = J::array(
        {{{"name", "leaf"},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {1.0, 0.5, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}},
          {"alphaMode", "MASK"},
          {"alphaCutoff", 0.3},
          {"doubleSided", true}}});
    return b;
}

Scene load(const fs::path& f, std::vector<std::string>* warnings = nullptr) {
    return loadScene(f.string(), {.warnings = warnings});
}

const Vertex* vertexAt(const Scene& s, glm::vec3 p) {
    for (const Vertex& v : s.vertices)
        if (glm::length(v.position - p) < 1e-5f)
            return &v;
    return nullptr;
}

} // namespace

TEST(GltfMaterials, TexturedAlphaTestedMaterialFromEveryImageSource) {
    const fs::path d = dir("sources");
    GltfBuilder fromView = texturedQuad();
    GltfBuilder fromUri = texturedQuad();
    const std::vector<uint8_t> image = png();
    fromUri.j["images"][0] = {{"uri", "leaf.png"}};
    std::ofstream(d / "leaf.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(image.data()), std::streamsize(image.size()));
    for (const fs::path& f :
         {fromView.writeGltf(d / "view.gltf"), texturedQuad().writeGlb(d / "v.glb"),
          fromUri.writeGltf(d / "uri.gltf")}) {
        SCOPED_TRACE(f.string());
        const Scene s = load(f);
        ASSERT_EQ(s.images.size(), 1u);
        EXPECT_EQ(s.images[0].width, 2u);
        EXPECT_EQ(s.images[0].rgba, kPixels);
        ASSERT_EQ(s.textures.size(), 1u);
        EXPECT_EQ(s.textures[0].wrapS, TextureWrap::ClampToEdge);
        EXPECT_EQ(s.textures[0].wrapT, TextureWrap::MirroredRepeat);
        EXPECT_TRUE(s.textures[0].nearest);
        const Material& leaf = s.materials[0];
        EXPECT_EQ(leaf.baseColorTexture, 0);
        EXPECT_EQ(leaf.alphaMode, AlphaMode::Mask);
        EXPECT_FLOAT_EQ(leaf.alphaCutoff, 0.3f);
        EXPECT_TRUE(leaf.doubleSided);
        EXPECT_FLOAT_EQ(leaf.baseColor.y, 0.5f);
        // The ground has no material: glTF's default, white and single-sided.
        const Vertex* ground = vertexAt(s, {-5, 0, -5});
        ASSERT_NE(ground, nullptr);
        EXPECT_EQ(s.materials[ground->material].name, "default");
        EXPECT_FALSE(s.materials[ground->material].doubleSided);
        EXPECT_FALSE(s.materials[ground->material].alphaTested());
        // Normalized integers: ubyte 255 -> 1, ushort 65535 -> 1.
        const Vertex* corner = vertexAt(s, {1, 2, 1});
        ASSERT_NE(corner, nullptr);
        EXPECT_EQ(corner->uv, glm::vec2(1.0f, 1.0f));
        EXPECT_EQ(corner->color, glm::vec4(0, 0, 1, 1));
        EXPECT_EQ(vertexAt(s, {-1, 2, -1})->color, glm::vec4(1, 0, 0, 1));
    }
}

TEST(GltfMaterials, TheMaterialsTexCoordSetIsTheOneRead) {
    GltfBuilder b = texturedQuad();
    b.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
    const Scene s = load(b.writeGltf(dir("texcoord") / "a.gltf"));
    EXPECT_EQ(vertexAt(s, {1, 2, 1})->uv, glm::vec2(0.75f, 0.75f));
}

// KHR_texture_transform on the base colour: the coordinates are offset, rotated and scaled as
// the ratified matrix says (the specification's own example: offset (0, 1), a quarter turn, half
// scale reads the lower-left quadrant), from the set the extension names; required, it loads.
TEST(GltfMaterials, TextureTransformMovesTheCoordinatesAsTheSpecificationSays) {
    GltfBuilder b = texturedQuad();
    b.j["extensionsUsed"] = {"KHR_texture_transform"};
    b.j["extensionsRequired"] = {"KHR_texture_transform"};
    auto& info = b.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
    info["extensions"] = {{"KHR_texture_transform",
                           {{"offset", {0, 1}},
                            {"rotation", 1.57079632679},
                            {"scale", {0.5, 0.5}},
                            {"texCoord", 1}}}};
    std::vector<std::string> warnings;
    const Scene s = load(b.writeGltf(dir("transform") / "a.gltf"), &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    // TEXCOORD_1 (u, v) from 0.25 to 0.75 becomes (v / 2, 1 - u / 2).
    const std::pair<glm::vec3, glm::vec2> corners[] = {{{-1, 2, -1}, {0.125f, 0.875f}},
                                                       {{1, 2, -1}, {0.125f, 0.625f}},
                                                       {{1, 2, 1}, {0.375f, 0.625f}},
                                                       {{-1, 2, 1}, {0.375f, 0.875f}}};
    for (const auto& [position, uv] : corners) {
        const Vertex* v = vertexAt(s, position);
        ASSERT_NE(v, nullptr);
        EXPECT_NEAR(v->uv.x, uv.x, 1e-6f) << position.x << " " << position.z;
        EXPECT_NEAR(v->uv.y, uv.y, 1e-6f) << position.x << " " << position.z;
        EXPECT_FALSE(s.covers(v->material, v->uv, 1.0f)) << "the lower-left texel: alpha 64";
    }

    // Offset and scale alone, on the textureInfo's own set (TEXCOORD_0, 0 to 1).
    info["extensions"] = {{"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"scale", {2, -1}}}}};
    const Scene t = load(b.writeGltf(dir("transform") / "b.gltf"));
    EXPECT_EQ(vertexAt(t, {1, 2, 1})->uv, glm::vec2(2.5f, -0.75f));
    EXPECT_EQ(vertexAt(t, {-1, 2, -1})->uv, glm::vec2(0.5f, 0.25f));

    for (const auto& [bad, what] :
         {std::pair{J{{"rotation", "a quarter"}},
                    "rotation: a number of magnitude below 1e15 expected"},
          std::pair{J{{"rotation", -1e16}}, "rotation: a number of magnitude below 1e15 expected"},
          std::pair{J{{"scale", {2}}}, "scale: 2 numbers of magnitude below 1e15 expected"},
          std::pair{J{{"offset", {0, -1e300}}},
                    "offset: 2 numbers of magnitude below 1e15 expected"},
          std::pair{J{{"texCoord", -1}}, "texCoord: a non-negative integer expected"},
          std::pair{J{{"texCoord", 1.5}}, "texCoord: a non-negative integer expected"}}) {
        info["extensions"] = {{"KHR_texture_transform", bad}};
        expectRefused(b.writeGltf(dir("transform") / "bad.gltf"),
                      std::string("materials[0].pbrMetallicRoughness.baseColorTexture.extensions."
                                  "KHR_texture_transform.") +
                          what);
    }
    // A set the primitive lacks, named by the extension rather than the textureInfo.
    info["extensions"] = {{"KHR_texture_transform", {{"texCoord", 3}}}};
    expectRefused(b.writeGltf(dir("transform") / "set.gltf"),
                  "]: no TEXCOORD_3 for materials[0]'s base colour texture (its "
                  "KHR_texture_transform.texCoord)");
}

TEST(GltfMaterials, CoverageIsTheGpuAlphaTest) {
    const Scene s = load(texturedQuad().writeGltf(dir("coverage") / "a.gltf"));
    // Nearest: each quarter of the unit square is one texel; alpha x factor (1) x vertex (1).
    EXPECT_FLOAT_EQ(s.coverage(0, {0.25f, 0.25f}, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(s.coverage(0, {0.75f, 0.25f}, 1.0f), 0.0f);
    EXPECT_NEAR(s.coverage(0, {0.25f, 0.75f}, 1.0f), 64 / 255.0f, 1e-6f);
    EXPECT_NEAR(s.coverage(0, {0.75f, 0.75f}, 0.5f), 0.5f * 192 / 255.0f, 1e-6f);
    // Clamp in s: u = 7 is the right column. Mirrored repeat in t: v = 1.25 mirrors to 0.75.
    EXPECT_FLOAT_EQ(s.coverage(0, {7.0f, 0.25f}, 1.0f), 0.0f);
    EXPECT_NEAR(s.coverage(0, {0.25f, 1.25f}, 1.0f), 64 / 255.0f, 1e-6f);
    EXPECT_TRUE(s.covers(0, {0.25f, 0.25f}, 1.0f));
    EXPECT_FALSE(s.covers(0, {0.25f, 0.75f}, 1.0f)); // 0.25 < cutoff 0.3
    EXPECT_TRUE(s.covers(0, {0.75f, 0.75f}, 1.0f));  // 0.75
    // Linear filtering: halfway between the texel centres of the top row.
    Scene linear = s;
    linear.textures[0].nearest = false;
    EXPECT_NEAR(linear.coverage(0, {0.5f, 0.25f}, 1.0f), 0.5f, 1e-6f);
    // Repeat wraps bilinear taps around the edge: u = 0 mixes the right and left columns.
    linear.textures[0].wrapS = TextureWrap::Repeat;
    EXPECT_NEAR(linear.coverage(0, {0.0f, 0.25f}, 1.0f), 0.5f, 1e-6f);
    EXPECT_FLOAT_EQ(linear.coverage(0, {1e30f, -1e30f}, 1.0f),
                    linear.coverage(0, {1e6f, -1e6f}, 1.0f)); // huge coordinates stay finite
}

TEST(GltfMaterials, CoverageExactlyAtTheCutoffIsSurface) {
    // The GPU discards coverage < cutoff (shaders/include/alpha_test.glsl): equal is surface.
    Scene s;
    s.materials.push_back(
        {.baseColor = {1, 1, 1, 0.5f}, .alphaMode = AlphaMode::Mask, .alphaCutoff = 0.5f});
    EXPECT_TRUE(s.covers(0, {0.3f, 0.3f}, 1.0f));
    EXPECT_FALSE(s.covers(0, {0.3f, 0.3f}, std::nextafter(1.0f, 0.0f)));
    EXPECT_TRUE(s.covers(0, {0.3f, 0.3f}, 0.0f) == false);
    s.materials[0].alphaMode = AlphaMode::Opaque; // only MASK has holes
    EXPECT_TRUE(s.covers(0, {0.3f, 0.3f}, 0.0f));
}

TEST(GltfMaterials, UnusedImagesAreNeverDecodedAndBlendIsDrawnOpaque) {
    GltfBuilder b = texturedQuad();
    const std::vector<uint8_t> junk{'G', 'I', 'F', '8', '9', 'a', 1, 2, 3};
    b.j["images"].push_back({{"bufferView", b.view(junk)}, {"mimeType", "image/png"}});
    b.j["textures"].push_back({{"source", 1}});
    b.j["materials"][0]["normalTexture"] = {{"index", 1}};
    b.j["materials"][0]["alphaMode"] = "BLEND";
    std::vector<std::string> warnings;
    const Scene s = load(b.writeGltf(dir("unused") / "a.gltf"), &warnings);
    EXPECT_EQ(s.images.size(), 1u);
    EXPECT_EQ(s.materials[0].alphaMode, AlphaMode::Blend);
    EXPECT_FALSE(s.materials[0].alphaTested());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("alphaMode BLEND is drawn opaque"), std::string::npos);
}

TEST(GltfMaterials, MirroringTransformsKeepFrontFacesFront) {
    for (const bool mirrored : {false, true}) {
        GltfBuilder b;
        b.ground();
        if (mirrored)
            b.j["nodes"][0]["scale"] = {-1.0, 1.0, 1.0};
        const Scene s = load(b.writeGltf(dir("mirror") / "a.gltf"));
        for (size_t t = 0; t < s.triangleCount(); ++t) {
            const glm::vec3 a = s.vertices[s.indices[3 * t]].position;
            const glm::vec3 n = glm::cross(s.vertices[s.indices[3 * t + 1]].position - a,
                                           s.vertices[s.indices[3 * t + 2]].position - a);
            EXPECT_GT(n.y, 0.0f) << "mirrored " << mirrored << ", triangle " << t;
        }
    }
}

namespace {

struct BadMaterial {
    const char* name;
    std::function<void(GltfBuilder&)> change;
    const char* expected;
};

class GltfMaterialRefuses : public ::testing::TestWithParam<BadMaterial> {};

std::vector<BadMaterial> badMaterials() {
    auto replaceImage = [](std::vector<uint8_t> bytes) {
        return [bytes](GltfBuilder& b) { b.j["images"][0]["bufferView"] = b.view(bytes); };
    };
    std::vector<uint8_t> huge = png(); // the IHDR width (big-endian at byte 16) says 20000
    huge[16] = 0, huge[17] = 0, huge[18] = 0x4e, huge[19] = 0x20;
    return {
        {"huge_image", replaceImage(huge), "images[0]: 20000x2 pixels is outside 1..16384"},
        {"view_without_mime", [](GltfBuilder& b) { b.j["images"][0].erase("mimeType"); },
         "images[0].mimeType: required with a bufferView"},
        {"texture_out_of_range",
         [](GltfBuilder& b) {
             b.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 5;
         },
         "materials[0].pbrMetallicRoughness.baseColorTexture.index: index 5 is out of range "
         "(1 textures)"},
        {"source_out_of_range", [](GltfBuilder& b) { b.j["textures"][0]["source"] = 3; },
         "textures[0].source: index 3 is out of range (1 images)"},
        {"sampler_out_of_range", [](GltfBuilder& b) { b.j["textures"][0]["sampler"] = 2; },
         "textures[0].sampler: index 2 is out of range (1 samplers)"},
        {"normal_texture_out_of_range",
         [](GltfBuilder& b) {
             b.j["materials"][0]["normalTexture"] = {{"index", 9}};
         },
         "materials[0].normalTexture.index: index 9 is out of range"},
        {"alpha_mode", [](GltfBuilder& b) { b.j["materials"][0]["alphaMode"] = "CUTOUT"; },
         "materials[0].alphaMode: 'CUTOUT' is not OPAQUE, MASK or BLEND"},
        {"alpha_cutoff", [](GltfBuilder& b) { b.j["materials"][0]["alphaCutoff"] = -1.0; },
         "materials[0].alphaCutoff: must be a finite number >= 0"},
        {"color_factor",
         [](GltfBuilder& b) {
             b.j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {2.0, 0, 0, 1};
         },
         "baseColorFactor: values must be in [0, 1]"},
        {"texcoord_vec3",
         [](GltfBuilder& b) {
             b.j["meshes"][1]["primitives"][0]["attributes"]["TEXCOORD_1"] =
                 b.accessor(b.view(std::vector<float>(12, 0.0f)), 5126, 4, "VEC3");
         },
         "attributes.TEXCOORD_1: wrong accessor type"},
        {"texcoord_int_not_normalized",
         [](GltfBuilder& b) {
             b.j["meshes"][1]["primitives"][0]["attributes"]["TEXCOORD_0"] =
                 b.accessor(b.view(std::vector<uint8_t>(8, 0)), 5121, 4, "VEC2");
         },
         "attributes.TEXCOORD_0: wrong accessor type"},
        {"color_count",
         [](GltfBuilder& b) {
             b.j["meshes"][1]["primitives"][0]["attributes"]["COLOR_0"] =
                 b.accessor(b.view(std::vector<float>(9, 1.0f)), 5126, 3, "VEC3");
         },
         "attributes.COLOR_0: has 3 elements but POSITION has 4"},
    };
}

} // namespace

// Images that are damaged, missing or in no format we read: the material keeps its colour factor
// and the load warns once, naming the file and the image.
std::vector<BadMaterial> damagedImages() {
    auto replaceImage = [](std::vector<uint8_t> bytes) {
        return [bytes](GltfBuilder& b) { b.j["images"][0]["bufferView"] = b.view(bytes); };
    };
    std::vector<uint8_t> truncated = png();
    truncated.resize(40);
    std::vector<uint8_t> lyingChunk = png(); // the chunk after IHDR claims 1.7 GB (fuzz finding)
    lyingChunk[33] = 0x68, lyingChunk[34] = 0, lyingChunk[35] = 0, lyingChunk[36] = 0x26;
    std::vector<uint8_t> badData = png(); // chunks intact, the compressed pixels garbage
    for (size_t k = 41; k < 45; ++k)
        badData[k] ^= 0xff;
    std::vector<uint8_t> lastByteCut = png(); // IEND's CRC is cut
    lastByteCut.pop_back();
    return {{"not_png_or_jpeg", replaceImage({'G', 'I', 'F', '8', '9', 'a', 0, 0}),
             "images[0]: not a PNG, JPEG, KTX2 or WebP image"},
            {"truncated_png", replaceImage(truncated),
             "images[0]: damaged: a PNG chunk runs past the end of the image"},
            {"png_chunk_length", replaceImage(lyingChunk),
             "images[0]: damaged: a PNG chunk runs past the end of the image"},
            {"png_last_byte_cut", replaceImage(lastByteCut),
             "images[0]: damaged: a PNG chunk runs past the end of the image"},
            {"png_not_decodable", replaceImage(badData), "images[0]: damaged: cannot decode it"},
            {"missing_image_file",
             [](GltfBuilder& b) {
                 b.j["images"][0] = {{"uri", "gone.png"}};
             },
             "images[0] 'gone.png': cannot read the image"}};
}

class GltfImageFallsBack : public ::testing::TestWithParam<BadMaterial> {};

TEST_P(GltfImageFallsBack, ToTheColourFactorWithOneWarning) {
    GltfBuilder b = texturedQuad();
    b.j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.25, 1.0, 1.0};
    const Scene intact =
        load(b.writeGltf(dir(std::string(GetParam().name) + "-intact") / "a.gltf"));
    ASSERT_EQ(intact.images.size(), 1u) << "the intact image decodes";
    GetParam().change(b);
    const fs::path file = b.writeGltf(dir(GetParam().name) / "bad.gltf");
    std::vector<std::string> warnings;
    const Scene s = load(file, &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find(file.string() + ": " + GetParam().expected), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[0].find("base colour factor"), std::string::npos);
    EXPECT_TRUE(s.images.empty());
    EXPECT_EQ(s.materials[0].baseColorTexture, -1);
    EXPECT_EQ(s.materials[0].baseColor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
}

INSTANTIATE_TEST_SUITE_P(Assets, GltfImageFallsBack, ::testing::ValuesIn(damagedImages()),
                         [](const auto& p) { return std::string(p.param.name); });

TEST_P(GltfMaterialRefuses, WithTheFileAndThePath) {
    GltfBuilder b = texturedQuad();
    GetParam().change(b);
    expectRefused(b.writeGltf(dir(GetParam().name) / "bad.gltf"), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(Assets, GltfMaterialRefuses, ::testing::ValuesIn(badMaterials()),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(GltfUris, PercentEncodedNamesAreDecodedAndStillChecked) {
    const fs::path d = dir("percent");
    GltfBuilder b = texturedQuad();
    const std::vector<uint8_t> image = png();
    b.j["images"][0] = {{"uri", "my%20leaf%2Bnew.png"}};
    std::ofstream(d / "my leaf+new.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(image.data()), std::streamsize(image.size()));
    const Scene s = load(b.writeGltf(d / "a.gltf"));
    ASSERT_EQ(s.images.size(), 1u);
    EXPECT_EQ(s.images[0].rgba, kPixels);

    const std::pair<const char*, const char*> refused[] = {
        {"%2e%2e/secret.png", "images[0].uri: URIs may not leave the asset's folder"},
        {"%2Fetc%2Fpasswd", "images[0].uri: absolute URIs are not supported"},
        {"leaf%zz.png", "images[0].uri: malformed percent-encoding"},
        {"leaf%2", "images[0].uri: malformed percent-encoding"},
        {"leaf+new.png", "images[0].uri: '+' in a URI is ambiguous"},
        {"%24HOME.png", "images[0].uri: refused character '$'"},
    };
    for (const auto& [uri, expected] : refused) {
        GltfBuilder bad = texturedQuad();
        bad.j["images"][0] = {{"uri", uri}};
        expectRefused(bad.writeGltf(d / "bad.gltf"), expected);
    }
}

TEST(GltfLimits, InstancingAndImageBytesAreCapped) {
    GltfBuilder b;
    b.ground(); // 2 triangles, then 9 more nodes using the same mesh: 20 after instancing
    for (int i = 0; i < 9; ++i)
        b.node({{"mesh", 0}, {"translation", {0.0, double(i + 1), 0.0}}});
    const fs::path f = b.writeGltf(dir("limits") / "instanced.gltf");
    EXPECT_EQ(loadScene(f.string(), {.maxTriangles = 20}).triangleCount(), 20u);
    expectRefused(f, "more than 19 triangles", {.maxTriangles = 19});
    const fs::path t = texturedQuad().writeGltf(dir("limits") / "textured.gltf");
    EXPECT_EQ(loadScene(t.string(), {.maxImageBytes = 16}).images.size(), 1u); // 2x2x4 bytes
    expectRefused(t, "images[0]: the images need more than 15 bytes", {.maxImageBytes = 15});
}
