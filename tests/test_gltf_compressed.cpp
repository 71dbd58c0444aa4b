// Compressed geometry (issue 16): EXT_meshopt_compression and KHR_draco_mesh_compression load
// the same triangles as their uncompressed original, and a broken stream or layout is refused
// with its JSON path.
#include "expect_refused.h"
#include "gltf_compressed.h"
#include "penumbra/scene.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <array>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path dir(const std::string& name) {
    return scratchDir("compressed", name);
}

using Triangle = std::array<glm::vec3, 3>;

std::vector<Triangle> trianglesOf(const Scene& s) {
    std::vector<Triangle> out;
    for (size_t t = 0; t < s.indices.size(); t += 3)
        out.push_back({s.vertices[s.indices[t]].position, s.vertices[s.indices[t + 1]].position,
                       s.vertices[s.indices[t + 2]].position});
    return out;
}

// Whether `a` is `b` up to a rotation of its corners (the same face, the same winding), each
// corner within `tolerance`.
bool sameTriangle(const Triangle& a, const Triangle& b, float tolerance) {
    for (int r = 0; r < 3; ++r) {
        bool all = true;
        for (int k = 0; k < 3 && all; ++k)
            all = glm::length(a[k] - b[(k + r) % 3]) <= tolerance;
        if (all)
            return true;
    }
    return false;
}

// Every triangle of `original` in `loaded` (and as many of them): a matching set of faces.
void expectSameTriangles(const Scene& original, const Scene& loaded, float tolerance,
                         const std::string& what) {
    const auto a = trianglesOf(original), b = trianglesOf(loaded);
    ASSERT_EQ(a.size(), b.size()) << what;
    std::vector<bool> used(b.size(), false);
    size_t missing = 0;
    for (const Triangle& t : a) {
        bool found = false;
        for (size_t k = 0; k < b.size() && !found; ++k)
            if (!used[k] && sameTriangle(t, b[k], tolerance))
                used[k] = found = true;
        missing += !found;
    }
    EXPECT_EQ(missing, 0u) << what << ": triangles of the original without a twin";
}

Scene loadWritten(GltfBuilder b, const std::string& name, bool binary,
                  std::vector<std::string>* warnings = nullptr) {
    const fs::path d = dir(name);
    const fs::path f = binary ? b.writeGlb(d / "a.glb") : b.writeGltf(d / "a.gltf");
    return loadScene(f.string(), {.warnings = warnings});
}

} // namespace

TEST(GltfCompressed, MeshoptLoadsTheOriginalsTrianglesExactly) {
    const TestMesh mesh = bumpyGridAndSlab();
    const Scene original = loadWritten(plainMesh(mesh), "plain", false);
    for (const bool binary : {false, true}) {
        std::vector<std::string> warnings;
        const Scene s = loadWritten(meshoptMesh(mesh), "meshopt", binary, &warnings);
        EXPECT_TRUE(warnings.empty()) << warnings.front();
        ASSERT_EQ(s.indices.size(), original.indices.size());
        // The codecs are lossless and keep the order: the same positions, triangle by triangle.
        for (size_t i = 0; i < s.indices.size(); ++i)
            ASSERT_EQ(s.vertices[s.indices[i]].position,
                      original.vertices[original.indices[i]].position)
                << "index " << i << (binary ? " (glb)" : " (gltf)");
        // Normals through 8-bit octahedral: within a couple of degrees.
        for (size_t v = 0; v < s.vertices.size(); ++v)
            ASSERT_GT(glm::dot(s.vertices[v].normal, original.vertices[v].normal), 0.999f) << v;
    }
}

TEST(GltfCompressed, DracoLoadsTheOriginalsTrianglesWithinItsQuantization) {
    const TestMesh mesh = bumpyGridAndSlab();
    const Scene original = loadWritten(plainMesh(mesh), "plain", false);
    for (const bool binary : {false, true}) {
        std::vector<std::string> warnings;
        const Scene s = loadWritten(dracoMesh(mesh, 16), "draco", binary, &warnings);
        EXPECT_TRUE(warnings.empty()) << warnings.front();
        // 16 bits over the 12-unit extent: steps of 2e-4.
        expectSameTriangles(original, s, 4e-4f, binary ? "draco glb" : "draco gltf");
        EXPECT_NEAR(s.bounds().max.y, 2.0f, 4e-4f);
    }
    // A coarse quantization moves the corners further: the comparison is not vacuous.
    const Scene coarse = loadWritten(dracoMesh(mesh, 6), "draco-coarse", false);
    const auto a = trianglesOf(original), b = trianglesOf(coarse);
    size_t exact = 0;
    for (const Triangle& t : a)
        for (const Triangle& u : b)
            exact += sameTriangle(t, u, 4e-4f);
    EXPECT_LT(exact, a.size() / 2);
}

TEST(GltfCompressed, BrokenStreamsAndLayoutsAreRefusedWithTheirPath) {
    const TestMesh mesh = bumpyGridAndSlab();
    {
        GltfBuilder b = meshoptMesh(mesh);
        const size_t at =
            b.j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"]
                .get<size_t>();
        b.bin[at] ^= 0xff; // the vertex codec's header byte
        expectRefused(b.writeGltf(dir("meshopt-header") / "a.gltf"),
                      "bufferViews[0].extensions.EXT_meshopt_compression: the ATTRIBUTES stream "
                      "does not decode");
    }
    {
        GltfBuilder b = meshoptMesh(mesh);
        b.j["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 3;
        expectRefused(b.writeGltf(dir("meshopt-stride") / "a.gltf"),
                      "bufferViews[2].extensions.EXT_meshopt_compression.byteStride: 3 is not "
                      "allowed in mode TRIANGLES");
    }
    {
        GltfBuilder b = meshoptMesh(mesh);
        b.j["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["filter"] = "QUATERNION";
        expectRefused(b.writeGltf(dir("meshopt-filter") / "a.gltf"),
                      "filter: 'QUATERNION' does not apply to mode ATTRIBUTES with byteStride 4");
    }
    {
        GltfBuilder b = meshoptMesh(mesh);
        b.j["bufferViews"][0].erase("extensions"); // a plain view over the fallback buffer
        expectRefused(b.writeGltf(dir("meshopt-fallback") / "a.gltf"),
                      "bufferViews[0].buffer: buffer 1 is a meshopt fallback and holds no data");
    }
    {
        GltfBuilder b = meshoptMesh(mesh);
        b.j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1u << 31;
        expectRefused(b.writeGltf(dir("meshopt-count") / "a.gltf"), "pass the cap",
                      {.maxImageBytes = uint64_t{1} << 30});
    }
    {
        GltfBuilder b = dracoMesh(mesh);
        for (size_t k = 16; k < 48 && k < b.bin.size(); ++k)
            b.bin[k] ^= 0x5a;
        expectRefused(b.writeGltf(dir("draco-stream") / "a.gltf"),
                      "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: the Draco "
                      "stream does not decode");
    }
    {
        GltfBuilder b = dracoMesh(mesh);
        b.j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]
           ["NORMAL"] = 7;
        expectRefused(b.writeGltf(dir("draco-id") / "a.gltf"),
                      "KHR_draco_mesh_compression.attributes.NORMAL: the stream has no attribute "
                      "7");
    }
    {
        GltfBuilder b = dracoMesh(mesh);
        b.j["accessors"][0]["count"] = 5;
        expectRefused(b.writeGltf(dir("draco-count") / "a.gltf"),
                      "attributes.POSITION: the accessor is 5 x 3 components, the stream");
    }
}
