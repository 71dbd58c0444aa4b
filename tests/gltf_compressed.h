#pragma once
// Compressed twins of one test mesh, for the loader's tests and the fuzzer's seeds: the same
// triangles as a plain glTF, through EXT_meshopt_compression (libmeshoptimizer's encoders,
// lossless; normals through the octahedral filter) and through KHR_draco_mesh_compression
// (libdraco's encoder, positions quantized to `positionBits`).
#include "gltf_builder.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace penumbra::test {

// A bumpy 12 x 12 grid of 2 x 2 units (a receiver with slopes) and a slab floating over it
// (a caster): positions, unit normals and triangle indices.
struct TestMesh {
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    size_t vertices() const { return positions.size() / 3; }
};

inline TestMesh bumpyGridAndSlab() {
    TestMesh m;
    const int n = 12;
    auto height = [](float x, float z) { return 0.3f * std::sin(0.9f * x) * std::cos(0.7f * z); };
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = -6.0f + float(i), z = -6.0f + float(j);
            m.positions.insert(m.positions.end(), {x, height(x, z), z});
            const float dx = 0.27f * std::cos(0.9f * x) * std::cos(0.7f * z);
            const float dz = -0.21f * std::sin(0.9f * x) * std::sin(0.7f * z);
            const float len = std::sqrt(dx * dx + 1.0f + dz * dz);
            m.normals.insert(m.normals.end(), {-dx / len, 1.0f / len, -dz / len});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1),
                           d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d}); // counter-clockwise from above
        }
    const uint32_t base = uint32_t(m.vertices());
    for (const float s : {-1.0f, 1.0f})
        for (const float t : {-1.0f, 1.0f}) {
            m.positions.insert(m.positions.end(), {1.5f * s, 2.0f, 1.0f * t});
            m.normals.insert(m.normals.end(), {0.0f, 1.0f, 0.0f});
        }
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base + 2, base + 1, base + 3});
    return m;
}

// The plain asset: float positions and normals, 32-bit indices, one node.
inline GltfBuilder plainMesh(const TestMesh& m) {
    GltfBuilder b;
    const int p = b.positions(m.positions);
    const int n = b.accessor(b.view(m.normals), 5126, m.vertices(), "VEC3");
    const int i = b.accessor(b.view(m.indices), 5125, m.indices.size(), "SCALAR");
    const int mesh = b.mesh(p, i);
    b.j["meshes"][mesh]["primitives"][0]["attributes"]["NORMAL"] = n;
    b.node({{"mesh", mesh}});
    return b;
}

// EXT_meshopt_compression: each view's compressed bytes appended to the builder's buffer, the
// view itself over a fallback buffer that holds no data. Normals as octahedral int8 (VEC4,
// normalized, stride 4: KHR_mesh_quantization).
inline GltfBuilder meshoptMesh(const TestMesh& m) {
    GltfBuilder b = plainMesh(m);
    const size_t count = m.vertices();
    std::vector<int8_t> octahedral(count * 4);
    std::vector<float> normals4;
    for (size_t v = 0; v < count; ++v)
        normals4.insert(normals4.end(),
                        {m.normals[3 * v], m.normals[3 * v + 1], m.normals[3 * v + 2], 0.0f});
    meshopt_encodeFilterOct(octahedral.data(), count, 4, 8, normals4.data());
    // VEC3 over a stride of 4: the filter's fourth byte is padding.
    b.j["accessors"][1] = {{"bufferView", 1},
                           {"componentType", 5120},
                           {"normalized", true},
                           {"count", count},
                           {"type", "VEC3"}};
    b.j["bufferViews"][1]["byteLength"] = count * 4;
    b.j["bufferViews"][1]["byteStride"] = 4;
    b.j["bufferViews"][0]["byteStride"] = 12;
    std::vector<std::vector<uint8_t>> encoded(3);
    encoded[0].resize(meshopt_encodeVertexBufferBound(count, 12));
    encoded[0].resize(meshopt_encodeVertexBuffer(encoded[0].data(), encoded[0].size(),
                                                 m.positions.data(), count, 12));
    encoded[1].resize(meshopt_encodeVertexBufferBound(count, 4));
    encoded[1].resize(meshopt_encodeVertexBuffer(encoded[1].data(), encoded[1].size(),
                                                 octahedral.data(), count, 4));
    encoded[2].resize(meshopt_encodeIndexBufferBound(m.indices.size(), count));
    encoded[2].resize(meshopt_encodeIndexBuffer(encoded[2].data(), encoded[2].size(),
                                                m.indices.data(), m.indices.size()));
    b.bin.clear(); // the plain bytes go; only the compressed ones stay
    const char* modes[] = {"ATTRIBUTES", "ATTRIBUTES", "TRIANGLES"};
    const size_t strides[] = {12, 4, 4}, counts[] = {count, count, m.indices.size()};
    size_t fallbackLength = 0;
    for (int v = 0; v < 3; ++v) {
        while (b.bin.size() % 4)
            b.bin.push_back(0);
        nlohmann::json e = {{"buffer", 0},
                            {"byteOffset", b.bin.size()},
                            {"byteLength", encoded[v].size()},
                            {"byteStride", strides[v]},
                            {"count", counts[v]},
                            {"mode", modes[v]}};
        if (v == 1)
            e["filter"] = "OCTAHEDRAL";
        b.bin.insert(b.bin.end(), encoded[v].begin(), encoded[v].end());
        auto& view = b.j["bufferViews"][v];
        view["buffer"] = 1;
        view["byteOffset"] = fallbackLength;
        view["byteLength"] = counts[v] * strides[v];
        view["extensions"] = {{"EXT_meshopt_compression", e}};
        fallbackLength += counts[v] * strides[v];
    }
    b.j["buffers"] = {nlohmann::json::object(),
                      {{"byteLength", fallbackLength},
                       {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    b.j["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    b.j["extensionsRequired"] = b.j["extensionsUsed"];
    return b;
}

// KHR_draco_mesh_compression: positions and normals from one Draco stream; the accessors keep
// their type and count (the decoded ones) and lose their bufferViews.
inline GltfBuilder dracoMesh(const TestMesh& m, int positionBits = 16) {
    draco::TriangleSoupMeshBuilder soup;
    const size_t faces = m.indices.size() / 3;
    soup.Start(static_cast<int>(faces));
    const int pos = soup.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int nor = soup.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    for (size_t f = 0; f < faces; ++f) {
        const uint32_t* t = &m.indices[3 * f];
        soup.SetAttributeValuesForFace(pos, draco::FaceIndex(uint32_t(f)), &m.positions[3 * t[0]],
                                       &m.positions[3 * t[1]], &m.positions[3 * t[2]]);
        soup.SetAttributeValuesForFace(nor, draco::FaceIndex(uint32_t(f)), &m.normals[3 * t[0]],
                                       &m.normals[3 * t[1]], &m.normals[3 * t[2]]);
    }
    const std::unique_ptr<draco::Mesh> mesh = soup.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, positionBits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    draco::EncoderBuffer stream;
    if (!mesh || !encoder.EncodeMeshToBuffer(*mesh, &stream).ok())
        throw std::runtime_error("draco: cannot encode the test mesh");
    // The decoded point count, which the accessors must state.
    draco::DecoderBuffer check;
    check.Init(stream.data(), stream.size());
    const auto decoded = draco::Decoder().DecodeMeshFromBuffer(&check);
    if (!decoded.ok())
        throw std::runtime_error("draco: cannot decode the test mesh");
    const size_t points = decoded.value()->num_points();

    GltfBuilder b;
    const std::vector<uint8_t> bytes(stream.data(), stream.data() + stream.size());
    const int view = b.view(bytes);
    const auto noView = [&](const char* type, int componentType, size_t count) {
        b.j["accessors"].push_back(
            {{"componentType", componentType}, {"count", count}, {"type", type}});
        return int(b.j["accessors"].size() - 1);
    };
    const int p = noView("VEC3", 5126, points), n = noView("VEC3", 5126, points),
              i = noView("SCALAR", 5125, m.indices.size());
    std::vector<float> lo(m.positions.begin(), m.positions.begin() + 3), hi = lo;
    for (size_t k = 0; k < m.positions.size(); ++k)
        lo[k % 3] = std::min(lo[k % 3], m.positions[k]),
               hi[k % 3] = std::max(hi[k % 3], m.positions[k]);
    b.j["accessors"][p]["min"] = lo; // the original's, as an exporter writes them
    b.j["accessors"][p]["max"] = hi;
    const int meshIndex = b.mesh(p, i);
    auto& prim = b.j["meshes"][meshIndex]["primitives"][0];
    prim["attributes"]["NORMAL"] = n;
    prim["extensions"] = {{"KHR_draco_mesh_compression",
                           {{"bufferView", view},
                            {"attributes",
                             {{"POSITION", mesh->attribute(pos)->unique_id()},
                              {"NORMAL", mesh->attribute(nor)->unique_id()}}}}}};
    b.node({{"mesh", meshIndex}});
    b.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    b.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    return b;
}

} // namespace penumbra::test
