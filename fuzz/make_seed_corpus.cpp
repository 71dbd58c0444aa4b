// Writes the glTF fuzzer's seed corpus into the folder given on the command line: valid assets
// from the unit tests' builder (tests/gltf_builder.h), each as one self-contained file (.gltf
// with a data URI, or .glb), and a few malformed ones. Every asset is loaded once here too: a
// valid seed the loader refuses, or a malformed one it accepts, is reported and fails the run.
#include "../tests/gltf_builder.h"
#include "../tests/gltf_compressed.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"

#include <stb/stb_image_write.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using namespace penumbra;
using penumbra::test::bumpyGridAndSlab;
using penumbra::test::componentTypes;
using penumbra::test::dracoMesh;
using penumbra::test::floatingQuad;
using penumbra::test::GltfBuilder;
using penumbra::test::meshoptMesh;
using J = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Small PNG (4x4 RGBA, alpha from 0 to 255: alpha-test cut-outs) and JPEG (8x8 RGB) images,
// encoded by stb_image_write.
std::vector<uint8_t> encodeImage(bool jpeg) {
    const int side = jpeg ? 8 : 4, channels = jpeg ? 3 : 4;
    std::vector<uint8_t> pixels;
    for (int i = 0; i < side * side; ++i)
        for (int c = 0; c < channels; ++c)
            pixels.push_back(static_cast<uint8_t>(c == 3 ? i * 17 : (i * 37 + c * 91) % 256));
    std::vector<uint8_t> out;
    auto append = [](void* context, void* data, int size) {
        auto& bytes = *static_cast<std::vector<uint8_t>*>(context);
        bytes.insert(bytes.end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    const int ok =
        jpeg ? stbi_write_jpg_to_func(append, &out, side, side, channels, pixels.data(), 90)
             : stbi_write_png_to_func(append, &out, side, side, channels, pixels.data(),
                                      side * channels);
    if (!ok || out.empty()) {
        std::fprintf(stderr, "make_seed_corpus: cannot encode the %s image\n",
                     jpeg ? "JPEG" : "PNG");
        std::exit(1);
    }
    return out;
}

// Strips, fans, lists without indices, and points and lines (skipped with a warning).
GltfBuilder primitiveModes() {
    GltfBuilder b;
    std::vector<float> xyz;
    for (int i = 0; i < 6; ++i)
        xyz.insert(xyz.end(), {float(i / 2), 0.0f, float(i % 2)});
    const int p = b.positions(xyz);
    for (int mode : {5, 6, 4, 1, 0, 3, 2})
        b.node({{"mesh", b.mesh(p, -1, mode)}});
    const int strip =
        b.accessor(b.view(std::vector<uint16_t>{0, 1, 2, 3, 4, 5}), 5123, 6, "SCALAR");
    b.node({{"mesh", b.mesh(p, strip, 5)}});
    return b;
}

// Materials: factors, alpha modes, PNG and JPEG base colour textures (as data URIs, or from
// bufferViews in the GLB form), samplers, two texture coordinate sets, vertex colours, normals.
GltfBuilder materials(bool imagesInBuffer) {
    GltfBuilder b;
    b.ground();
    const int p = b.positions({0, 1, 0, 1, 1, 0, 0, 1, 1, 1, 1, 1});
    const int idx = b.accessor(b.view(std::vector<uint16_t>{0, 2, 1, 1, 2, 3}), 5123, 6, "SCALAR");
    const int normals =
        b.accessor(b.view(std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}), 5126, 4, "VEC3");
    const int uvFloat =
        b.accessor(b.view(std::vector<float>{0, 0, 1, 0, 0, 1, 1, 1}), 5126, 4, "VEC2");
    const int uvU16 =
        b.accessor(b.view(std::vector<uint16_t>{0, 0, 65535, 0, 0, 65535, 65535, 65535}), 5123, 4,
                   "VEC2", true);
    const int uvU8 = b.accessor(b.view(std::vector<uint8_t>{0, 0, 255, 0, 0, 255, 255, 255}), 5121,
                                4, "VEC2", true);
    const int colorU8 = b.accessor(
        b.view(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 64, 9, 9, 9, 0}),
        5121, 4, "VEC4", true);
    const int colorF =
        b.accessor(b.view(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), 5126, 4, "VEC3");
    struct Prim {
        int material;
        std::vector<std::pair<const char*, int>> attributes;
    };
    const std::vector<Prim> prims = {
        {1, {{"NORMAL", normals}, {"TEXCOORD_0", uvFloat}, {"TEXCOORD_1", uvU16}}},
        {2, {{"TEXCOORD_0", uvU8}, {"COLOR_0", colorU8}}},
        {0, {{"COLOR_0", colorF}}},
        {3, {{"NORMAL", normals}}}};
    float y = 0;
    for (const Prim& prim : prims) {
        const int mesh = b.mesh(p, idx);
        auto& json = b.j["meshes"][mesh]["primitives"][0];
        json["material"] = prim.material;
        for (const auto& [name, accessor] : prim.attributes)
            json["attributes"][name] = accessor;
        b.node({{"mesh", mesh}, {"translation", {0.0, y += 0.5f, 0.0}}});
    }
    for (bool jpeg : {false, true}) {
        const std::vector<uint8_t> bytes = encodeImage(jpeg);
        const char* mime = jpeg ? "image/jpeg" : "image/png";
        b.j["images"].push_back(imagesInBuffer
                                    ? J{{"bufferView", b.view(bytes)}, {"mimeType", mime}}
                                    : J{{"uri", std::string("data:") + mime + ";base64," +
                                                    GltfBuilder::base64(bytes)}});
    }
    b.j["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}},
                       {{"minFilter", 9987}, {"magFilter", 9729}}};
    b.j["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}, {"sampler", 1}}};
    b.j["materials"] = {
        {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}},
        {{"name", "leaf"},
         {"alphaMode", "MASK"},
         {"alphaCutoff", 0.5},
         {"doubleSided", true},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 1, 0.5, 0.9}},
           {"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}},
        {{"name", "photo"},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}},
         {"normalTexture", {{"index", 0}}}},
        {{"name", "glass"}, {"alphaMode", "BLEND"}}};
    return b;
}

// TRS and matrix nodes, a hierarchy, a deep chain, and a second scene that is not the default.
GltfBuilder hierarchy() {
    GltfBuilder b;
    const int p = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int mesh = b.mesh(p);
    const int leaf = b.node({{"mesh", mesh}, {"scale", {2, 2, 2}}}, false);
    const int mid =
        b.node({{"children", {leaf}}, {"rotation", {0, 0, 0.7071068, 0.7071068}}}, false);
    b.node({{"children", {mid}}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}}});
    int child = b.node({{"mesh", mesh}}, false);
    for (int i = 0; i < 200; ++i)
        child = b.node({{"children", {child}}, {"translation", {0.0, 0.01, 0.0}}}, i == 199);
    const int other = b.node({{"mesh", mesh}}, false);
    b.j["scenes"].push_back({{"nodes", {other}}});
    return b;
}

// Spot and point lights, an orthographic camera.
GltfBuilder lightsAndCameras() {
    GltfBuilder b;
    b.ground();
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
            {"translation", {0, 5, 0}},
            {"rotation", {-0.7071, 0, 0, 0.7071}}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}, {"translation", {1, 3, 0}}});
    b.node({{"camera", 0}, {"translation", {0, 10, 0}}, {"rotation", {-0.7071, 0, 0, 0.7071}}});
    b.node({{"camera", 1}, {"translation", {0, 2, 8}}});
    b.j["cameras"] = {{{"type", "orthographic"},
                       {"orthographic", {{"xmag", 6}, {"ymag", 6}, {"znear", 0.1}, {"zfar", 50}}}},
                      {{"type", "perspective"},
                       {"name", "infinite"},
                       {"perspective", {{"aspectRatio", 1.5}, {"yfov", 0.6}, {"znear", 0.05}}}}};
    b.j["extensions"] = {{"KHR_lights_punctual",
                          {{"lights",
                            {{{"type", "spot"},
                              {"name", "spot"},
                              {"color", {1, 0.9, 0.8}},
                              {"intensity", 20},
                              {"range", 30},
                              {"spot", {{"innerConeAngle", 0.3}, {"outerConeAngle", 0.6}}},
                              {"extras", {{"radius", 0.25}}}},
                             {{"type", "point"}, {"intensity", 5}, {"range", 10}}}}}}};
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    return b;
}

struct Seed {
    const char* name; // file name in the corpus
    std::function<fs::path(const fs::path&)> write;
    bool valid; // the loader must accept it (else refuse it with InputError)
};

// A builder written as one self-contained file (data URI or GLB).
template <typename Make>
std::function<fs::path(const fs::path&)> asset(Make make, bool glb) {
    return [make, glb](const fs::path& file) {
        GltfBuilder b = make();
        return glb ? b.writeGlb(file) : b.writeGltf(file);
    };
}

// The ground with one change: a malformed asset.
std::function<fs::path(const fs::path&)> broken(std::function<void(GltfBuilder&)> change) {
    return [change](const fs::path& file) {
        GltfBuilder b;
        b.ground();
        change(b);
        return b.writeGltf(file);
    };
}

std::function<fs::path(const fs::path&)> raw(std::string text) {
    return [text](const fs::path& file) {
        std::ofstream(file, std::ios::binary) << text;
        return file;
    };
}

std::function<fs::path(const fs::path&)>
brokenGlb(std::function<void(std::vector<uint8_t>&)> change) {
    return [change](const fs::path& file) {
        GltfBuilder b;
        b.ground();
        b.writeGlb(file);
        std::ifstream in(file, std::ios::binary);
        std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
        in.close();
        change(bytes);
        std::ofstream(file, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()),
                   static_cast<std::streamsize>(bytes.size()));
        return file;
    };
}

// The materials asset with one change: a malformed one.
std::function<fs::path(const fs::path&)> brokenMaterials(std::function<void(GltfBuilder&)> change,
                                                         bool glb) {
    return [change, glb](const fs::path& file) {
        GltfBuilder b = materials(glb);
        change(b);
        return glb ? b.writeGlb(file) : b.writeGltf(file);
    };
}

std::vector<Seed> seeds() {
    auto bare = [] {
        GltfBuilder b;
        b.ground();
        return b;
    };
    return {
        {"floating-quad.gltf", asset(floatingQuad, false), true},
        {"floating-quad.glb", asset(floatingQuad, true), true},
        {"primitive-modes.gltf", asset(primitiveModes, false), true},
        {"primitive-modes.glb", asset(primitiveModes, true), true},
        {"component-types.gltf", asset(componentTypes, false), true},
        {"component-types.glb", asset(componentTypes, true), true},
        {"materials.gltf", asset([] { return materials(false); }, false), true},
        {"materials.glb", asset([] { return materials(true); }, true), true},
        {"materials-views.gltf", asset([] { return materials(true); }, false), true},
        {"hierarchy.gltf", asset(hierarchy, false), true},
        {"lights-cameras.gltf", asset(lightsAndCameras, false), true},
        {"lights-cameras.glb", asset(lightsAndCameras, true), true},
        {"meshopt.gltf", asset([] { return meshoptMesh(bumpyGridAndSlab()); }, false), true},
        {"meshopt.glb", asset([] { return meshoptMesh(bumpyGridAndSlab()); }, true), true},
        {"draco.gltf", asset([] { return dracoMesh(bumpyGridAndSlab()); }, false), true},
        {"draco.glb", asset([] { return dracoMesh(bumpyGridAndSlab(), 8); }, true), true},
        {"bare.gltf", asset(bare, false), true},
        {"bare.glb", asset(bare, true), true},
        {"bad-not-json.gltf", raw("{ this is not json"), false},
        {"bad-gltf-1.gltf", raw(R"({"asset":{"version":"1.0"}})"), false},
        {"bad-required.gltf",
         broken([](GltfBuilder& b) { b.j["extensionsRequired"] = {"EXT_mesh_gpu_instancing"}; }),
         false},
        {"bad-uri-parent.gltf", broken([](GltfBuilder& b) {
             b.j["buffers"] =
                 J::array({J::object(), {{"uri", "../secret.bin"}, {"byteLength", 4}}});
         }),
         false},
        {"bad-base64.gltf", broken([](GltfBuilder& b) {
             b.j["buffers"] = J::array(
                 {J::object(),
                  {{"uri", "data:application/octet-stream;base64,@@@@"}, {"byteLength", 3}}});
         }),
         false},
        {"bad-stride.gltf", broken([](GltfBuilder& b) { b.j["bufferViews"][0]["byteStride"] = 6; }),
         false},
        {"bad-count-overflow.gltf",
         broken([](GltfBuilder& b) { b.j["accessors"][0]["count"] = 4611686018427387904ull; }),
         false},
        {"bad-index-value.gltf", broken([](GltfBuilder& b) {
             b.j["accessors"][1]["bufferView"] = b.view(std::vector<uint16_t>{0, 2, 77, 0, 3, 2});
         }),
         false},
        {"bad-node-cycle.gltf", broken([](GltfBuilder& b) {
             b.j["nodes"].push_back({{"children", {2}}});
             b.j["nodes"].push_back({{"children", {1}}});
         }),
         false},
        {"bad-nan-position.gltf", broken([](GltfBuilder& b) {
             const float nan = std::numeric_limits<float>::quiet_NaN();
             b.j["accessors"][0]["bufferView"] =
                 b.view(std::vector<float>{-5, 0, -5, nan, 0, -5, 5, 0, 5, -5, 0, 5});
         }),
         false},
        {"bad-sparse-index.gltf", broken([](GltfBuilder& b) {
             b.j["accessors"][0]["sparse"] = {
                 {"count", 1},
                 {"indices",
                  {{"bufferView", b.view(std::vector<uint16_t>{9, 0})}, {"componentType", 5123}}},
                 {"values", {{"bufferView", b.view(std::vector<float>{0, 0, 0})}}}};
         }),
         false},
        {"bad-image-bytes.gltf", // loads: the colour factor stands in, with a warning
         brokenMaterials(
             [](GltfBuilder& b) {
                 b.j["images"][0]["uri"] = "data:image/png;base64," +
                                           GltfBuilder::base64({'n', 'o', 't', ' ', 'a', 'n', 'y'});
             },
             false),
         true},
        {"bad-image-side.glb",
         brokenMaterials(
             [](GltfBuilder& b) {
                 // The PNG's IHDR width (bytes 16..19, big-endian) past the largest side.
                 const size_t at =
                     b.j["bufferViews"][b.j["images"][0]["bufferView"].get<int>()]["byteOffset"]
                         .get<size_t>() +
                     16;
                 b.bin[at] = 0, b.bin[at + 1] = 0, b.bin[at + 2] = 0x4e, b.bin[at + 3] = 0x20;
             },
             true),
         false},
        {"bad-texture-index.gltf",
         brokenMaterials(
             [](GltfBuilder& b) {
                 b.j["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 7;
             },
             false),
         false},
        // a texCoord set the primitive lacks (the validator's MESH_PRIMITIVE_TOO_FEW_TEXCOORDS)
        {"texcoord-missing-set.gltf",
         brokenMaterials(
             [](GltfBuilder& b) {
                 b.j["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 3;
             },
             false),
         false},
        {"bad-glb-version.glb", brokenGlb([](std::vector<uint8_t>& v) { v[4] = 1; }), false},
        {"bad-glb-length.glb", brokenGlb([](std::vector<uint8_t>& v) { v[8] += 4; }), false},
        {"bad-glb-bin-length.glb", brokenGlb([](std::vector<uint8_t>& v) {
             const uint32_t json = v[12] | v[13] << 8 | v[14] << 16 | uint32_t(v[15]) << 24;
             v[20 + json + 1] = 0x7F;
         }),
         false},
    };
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
        return 2;
    }
    const fs::path dir = argv[1];
    fs::create_directories(dir);
    int failures = 0;
    for (const Seed& seed : seeds()) {
        const fs::path file = seed.write(dir / seed.name);
        bool loaded = true;
        std::string why;
        try {
            loadScene(file.string(), {.maxFileSize = uint64_t{1} << 20});
        } catch (const InputError& e) {
            loaded = false;
            why = e.what();
        }
        if (loaded != seed.valid) {
            std::fprintf(stderr, "make_seed_corpus: %s: expected %s, got %s\n", seed.name,
                         seed.valid ? "it to load" : "a refusal", loaded ? "a scene" : why.c_str());
            ++failures;
        }
    }
    std::printf("make_seed_corpus: %zu seeds in %s\n", seeds().size(), dir.string().c_str());
    return failures ? 1 : 0;
}
