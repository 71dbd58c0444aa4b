// The glTF-Validator's data errors in the parts Penumbra draws, beyond byte ranges: non-finite
// attribute values (ACCESSOR_INVALID_FLOAT), normals that are not unit length
// (ACCESSOR_NON_UNIT), sparse indices that do not increase, accessors misaligned in their buffer
// (ACCESSOR_TOTAL_OFFSET_ALIGNMENT), views shared by vertex accessors without a byteStride and
// index views with one, a texture set no TEXCOORD provides (MESH_PRIMITIVE_TOO_FEW_TEXCOORDS),
// node transforms of the wrong length and matrices that are not TRS (NODE_MATRIX_NON_TRS).
// Called after validateModel's range checks: every read here is in bounds.
#include "penumbra/error.h"
#include "scene/gltf_accessors.h"
#include "scene/gltf_validate.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <map>
#include <set>

namespace penumbra::gltf {
namespace {

// |n| - 1 past which a normal is not unit length (the validator's, for three components).
constexpr double kUnitNormal = 0.00674;

struct MeshChecker {
    const std::filesystem::path& file;
    const tinygltf::Model& m;

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw InputError(file.string(), path + ": " + what);
    }

    // Streamed, element by element (an accessor without a bufferView: its sparse values).
    void finiteValues(const std::string& path, int accessor, bool unitVectors) const {
        const auto& a = m.accessors[accessor];
        if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            return;
        const size_t n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
        double squares = 0.0;
        visitRawComponents(m, accessor, [&](size_t element, size_t c, double v) {
            if (!std::isfinite(v))
                fail(path, fmt::format("element {} is NaN or infinite", element));
            squares = (c == 0 ? 0.0 : squares) + v * v;
            if (unitVectors && n == 3 && c == 2 && std::abs(std::sqrt(squares) - 1.0) > kUnitNormal)
                fail(path, fmt::format("normal {} has length {:.6g}, not 1", element,
                                       std::sqrt(squares)));
        });
    }

    void primitives() const {
        std::map<int, std::set<int>> vertexAccessorsOfView;
        for (size_t i = 0; i < m.meshes.size(); ++i)
            for (size_t p = 0; p < m.meshes[i].primitives.size(); ++p) {
                const auto& prim = m.meshes[i].primitives[p];
                const std::string path = fmt::format("meshes[{}].primitives[{}]", i, p);
                if (!hasPositions(prim))
                    continue;
                for (const auto& [name, accessor] : prim.attributes) {
                    finiteValues(path + ".attributes." + name, accessor, name == "NORMAL");
                    if (m.accessors[accessor].bufferView >= 0)
                        vertexAccessorsOfView[m.accessors[accessor].bufferView].insert(accessor);
                }
                if (prim.indices >= 0 && m.accessors[prim.indices].bufferView >= 0 &&
                    m.bufferViews[m.accessors[prim.indices].bufferView].byteStride != 0)
                    fail(path + ".indices", "its bufferView must not have a byteStride");
                if (prim.material >= 0)
                    texCoordSets(path, prim, m.materials[prim.material],
                                 fmt::format("materials[{}]", prim.material));
            }
        for (const auto& [view, accessors] : vertexAccessorsOfView)
            if (accessors.size() > 1 && m.bufferViews[view].byteStride == 0)
                fail(fmt::format("bufferViews[{}].byteStride", view),
                     fmt::format("required: {} vertex accessors share the view", accessors.size()));
    }

    void texCoordSets(const std::string& path, const tinygltf::Primitive& prim,
                      const tinygltf::Material& mat, const std::string& matPath) const {
        const std::pair<const char*, int> textures[] = {
            {"pbrMetallicRoughness.baseColorTexture",
             mat.pbrMetallicRoughness.baseColorTexture.index >= 0
                 ? mat.pbrMetallicRoughness.baseColorTexture.texCoord
                 : -1},
            {"pbrMetallicRoughness.metallicRoughnessTexture",
             mat.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0
                 ? mat.pbrMetallicRoughness.metallicRoughnessTexture.texCoord
                 : -1},
            {"normalTexture", mat.normalTexture.index >= 0 ? mat.normalTexture.texCoord : -1},
            {"occlusionTexture",
             mat.occlusionTexture.index >= 0 ? mat.occlusionTexture.texCoord : -1},
            {"emissiveTexture",
             mat.emissiveTexture.index >= 0 ? mat.emissiveTexture.texCoord : -1}};
        for (const auto& [key, set] : textures)
            if (set >= 0 && !prim.attributes.contains(fmt::format("TEXCOORD_{}", set)))
                fail(path + ".attributes",
                     fmt::format("no TEXCOORD_{} for {}.{}", set, matPath, key));
    }

    void accessorAlignment() const {
        for (size_t i = 0; i < m.accessors.size(); ++i) {
            const auto& a = m.accessors[i];
            if (a.bufferView < 0)
                continue;
            const uint64_t size =
                tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
            const uint64_t total = m.bufferViews[a.bufferView].byteOffset + a.byteOffset;
            if (size > 0 && total % size)
                fail(fmt::format("accessors[{}]", i),
                     fmt::format("starts at buffer byte {}, not a multiple of its component "
                                 "size {}",
                                 total, size));
        }
    }

    void sparseIndicesIncrease() const {
        for (size_t i = 0; i < m.accessors.size(); ++i) {
            const auto& s = m.accessors[i].sparse;
            if (!s.isSparse)
                continue;
            const auto& view = m.bufferViews[s.indices.bufferView];
            const uint8_t* data =
                m.buffers[view.buffer].data.data() + view.byteOffset + s.indices.byteOffset;
            const size_t bytes =
                tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(s.indices.componentType));
            uint64_t previous = 0;
            for (int k = 0; k < s.count; ++k) {
                uint64_t value = 0;
                std::memcpy(&value, data + k * bytes, bytes);
                if (k > 0 && value <= previous)
                    fail(fmt::format("accessors[{}].sparse.indices[{}]", i, k),
                         fmt::format("{} does not follow {}: sparse indices must increase", value,
                                     previous));
                previous = value;
            }
        }
    }

    void nodeTransforms() const {
        for (size_t i = 0; i < m.nodes.size(); ++i) {
            const auto& n = m.nodes[i];
            const std::string path = fmt::format("nodes[{}]", i);
            if (!n.translation.empty() && n.translation.size() != 3)
                fail(path + ".translation", "needs 3 numbers");
            if (!n.rotation.empty() && n.rotation.size() != 4)
                fail(path + ".rotation", "needs 4 numbers");
            if (!n.scale.empty() && n.scale.size() != 3)
                fail(path + ".scale", "needs 3 numbers");
            // Column-major: the last row (elements 3, 7, 11, 15) of an affine TRS is 0 0 0 1.
            if (n.matrix.size() == 16 && (n.matrix[3] != 0.0 || n.matrix[7] != 0.0 ||
                                          n.matrix[11] != 0.0 || n.matrix[15] != 1.0))
                fail(path + ".matrix", "is not a translation, rotation and scale (its last row "
                                       "is not 0 0 0 1)");
        }
    }
};

} // namespace

void checkMeshData(const std::filesystem::path& file, const tinygltf::Model& model) {
    const MeshChecker c{file, model};
    c.nodeTransforms();
    c.accessorAlignment();
    c.sparseIndicesIncrease();
    c.primitives();
}

} // namespace penumbra::gltf
