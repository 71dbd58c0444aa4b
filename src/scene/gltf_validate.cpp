#include "scene/gltf_validate.h"

#include "penumbra/error.h"
#include "scene/gltf_accessors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <vector>

namespace penumbra::gltf {
namespace {

// |q| - 1 of a node's rotation past which it is not a unit quaternion (the glTF-Validator's).
constexpr double kUnitTolerance = 0.00769;
constexpr double kHalfPi = 1.5707963267948966;

struct Checker {
    const std::filesystem::path& file;
    const tinygltf::Model& m;
    OnceWarnings& warnings;

    void warnOnce(const std::string& cls, const std::string& path, const std::string& what) const {
        warnings.add(cls, path, what);
    }
    bool uses(const char* extension) const {
        return std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), extension) !=
               m.extensionsUsed.end();
    }

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw InputError(file.string(), path + ": " + what);
    }
    void index(const std::string& path, int i, size_t count, const char* what) const {
        if (i < 0 || static_cast<size_t>(i) >= count)
            fail(path, fmt::format("{} index {} is out of range ({} {}s)", what, i, count, what));
    }
    // a + b, refusing overflow past 64 bits.
    uint64_t add(const std::string& path, uint64_t a, uint64_t b) const {
        if (a > std::numeric_limits<uint64_t>::max() - b)
            fail(path, "byte range overflows");
        return a + b;
    }
    uint64_t mul(const std::string& path, uint64_t a, uint64_t b) const {
        if (b != 0 && a > std::numeric_limits<uint64_t>::max() / b)
            fail(path, "byte range overflows");
        return a * b;
    }
    void finite(const std::string& path, const std::vector<double>& v) const {
        for (double x : v)
            if (!std::isfinite(x))
                fail(path, "contains NaN or infinity");
    }

    void bufferViews() const {
        for (size_t i = 0; i < m.bufferViews.size(); ++i) {
            const auto& v = m.bufferViews[i];
            const std::string path = fmt::format("bufferViews[{}]", i);
            index(path + ".buffer", v.buffer, m.buffers.size(), "buffer");
            if (v.byteLength == 0)
                fail(path + ".byteLength", "must be at least 1");
            const uint64_t end = add(path, v.byteOffset, v.byteLength);
            if (end > m.buffers[v.buffer].data.size())
                fail(path, fmt::format("bytes {}..{} run past buffer {} ({} bytes)", v.byteOffset,
                                       end, v.buffer, m.buffers[v.buffer].data.size()));
            if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252 || v.byteStride % 4))
                fail(path + ".byteStride",
                     fmt::format("{} is not a multiple of 4 in [4, 252]", v.byteStride));
        }
    }

    // `count` elements of `bytes` each, `stride` apart, from `offset` inside view `viewIndex`.
    void range(const std::string& path, int viewIndex, uint64_t offset, uint64_t count,
               uint64_t bytes, uint64_t stride) const {
        index(path + ".bufferView", viewIndex, m.bufferViews.size(), "bufferView");
        const auto& view = m.bufferViews[viewIndex];
        const uint64_t last = add(path, mul(path, count - 1, stride), bytes);
        const uint64_t end = add(path, offset, last);
        if (end > view.byteLength)
            fail(path, fmt::format("{} elements need bytes {}..{} but bufferView {} has {}", count,
                                   offset, end, viewIndex, view.byteLength));
    }

    void accessors() const {
        for (size_t i = 0; i < m.accessors.size(); ++i) {
            const auto& a = m.accessors[i];
            const std::string path = fmt::format("accessors[{}]", i);
            const uint64_t bytes = elementBytes(a.componentType, a.type);
            if (bytes == 0)
                fail(path, "invalid componentType or type");
            if (a.count == 0)
                fail(path + ".count", "must be at least 1");
            // The decoded elements' size fits 64 bits: the one bound of an accessor without a
            // bufferView (zeros plus sparse values), whose count readFloats multiplies.
            mul(path, a.count, bytes);
            const uint64_t component =
                tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
            if (a.byteOffset % component)
                fail(path + ".byteOffset", "not a multiple of the component size");
            if (a.bufferView >= 0) {
                index(path + ".bufferView", a.bufferView, m.bufferViews.size(), "bufferView");
                const uint64_t stride = m.bufferViews[a.bufferView].byteStride
                                            ? m.bufferViews[a.bufferView].byteStride
                                            : bytes;
                if (stride < bytes)
                    fail(path, "byteStride is smaller than one element");
                if (stride % component)
                    fail(path, "byteStride is not a multiple of the component size");
                range(path, a.bufferView, a.byteOffset, a.count, bytes, stride);
            }
            if (a.sparse.isSparse)
                sparse(path + ".sparse", a);
        }
    }

    void sparse(const std::string& path, const tinygltf::Accessor& a) const {
        const auto& s = a.sparse;
        if (s.count <= 0 || static_cast<size_t>(s.count) > a.count)
            fail(path + ".count", fmt::format("{} is outside 1..{}", s.count, a.count));
        const uint64_t indexBytes = elementBytes(s.indices.componentType, TINYGLTF_TYPE_SCALAR);
        if (s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(path + ".indices.componentType", "must be an unsigned integer type");
        range(path + ".indices", s.indices.bufferView, s.indices.byteOffset, s.count, indexBytes,
              indexBytes);
        range(path + ".values", s.values.bufferView, s.values.byteOffset, s.count,
              elementBytes(a.componentType, a.type), elementBytes(a.componentType, a.type));
        const auto& view = m.bufferViews[s.indices.bufferView];
        const uint8_t* data =
            m.buffers[view.buffer].data.data() + view.byteOffset + s.indices.byteOffset;
        for (int k = 0; k < s.count; ++k) {
            uint64_t value = 0;
            std::memcpy(&value, data + k * indexBytes, indexBytes);
            if (value >= a.count)
                fail(fmt::format("{}.indices[{}]", path, k),
                     fmt::format("{} is out of range ({} elements)", value, a.count));
        }
    }

    void accessorOfType(const std::string& path, int i, int type, bool floatOnly) const {
        index(path, i, m.accessors.size(), "accessor");
        const auto& a = m.accessors[i];
        if (a.type != type || (floatOnly && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT))
            fail(path, "wrong accessor type or componentType");
    }

    void meshes() const {
        for (size_t i = 0; i < m.meshes.size(); ++i)
            for (size_t p = 0; p < m.meshes[i].primitives.size(); ++p) {
                const auto& prim = m.meshes[i].primitives[p];
                const std::string path = fmt::format("meshes[{}].primitives[{}]", i, p);
                const auto pos = prim.attributes.find("POSITION");
                if (pos == prim.attributes.end()) {
                    warnOnce("no POSITION", path + ".attributes",
                             "POSITION is missing; such primitives are skipped");
                    continue;
                }
                const bool quantized = uses("KHR_mesh_quantization");
                vertexAttribute(path + ".attributes.POSITION", pos->second,
                                quantized ? kQuantizedPosition : kFloatOnly);
                if (const auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end())
                    vertexAttribute(path + ".attributes.NORMAL", n->second,
                                    quantized ? kQuantizedNormal : kFloatOnly);
                for (const auto& [name, accessor] : prim.attributes) {
                    const std::string at = path + ".attributes." + name;
                    index(at, accessor, m.accessors.size(), "accessor");
                    if (name.rfind("TEXCOORD_", 0) == 0)
                        attributeOf(at, accessor, {TINYGLTF_TYPE_VEC2}, quantized);
                    else if (name.rfind("COLOR_", 0) == 0)
                        attributeOf(at, accessor, {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, false);
                    if (m.accessors[accessor].count != m.accessors[pos->second].count)
                        fail(at, fmt::format("has {} elements but POSITION has {}",
                                             m.accessors[accessor].count,
                                             m.accessors[pos->second].count));
                }
                if (prim.indices >= 0) {
                    accessorOfType(path + ".indices", prim.indices, TINYGLTF_TYPE_SCALAR, false);
                    const int ct = m.accessors[prim.indices].componentType;
                    if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                        fail(path + ".indices", "must be unsigned byte, short or int");
                }
                if (prim.material >= 0)
                    index(path + ".material", prim.material, m.materials.size(), "material");
                if (prim.mode < 0 || prim.mode > 6)
                    fail(path + ".mode", "not a glTF mode");
                morphTargets(path, prim, m.accessors[pos->second].count);
            }
    }

    // Morph targets (applied by the flattener): each attribute a VEC3 accessor of the
    // primitive's vertex count. The flattener reads POSITION and NORMAL; other attributes are
    // checked and left.
    void morphTargets(const std::string& path, const tinygltf::Primitive& prim,
                      size_t vertices) const {
        for (size_t t = 0; t < prim.targets.size(); ++t)
            for (const auto& [name, accessor] : prim.targets[t]) {
                const std::string at = fmt::format("{}.targets[{}].{}", path, t, name);
                index(at, accessor, m.accessors.size(), "accessor");
                const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(accessor)];
                if (a.count != vertices)
                    fail(at, fmt::format("accessors[{}] has {} elements for the primitive's {} "
                                         "vertices",
                                         accessor, a.count, vertices));
                if ((name == "POSITION" || name == "NORMAL") && a.type != TINYGLTF_TYPE_VEC3)
                    fail(at, fmt::format("accessors[{}] is not VEC3", accessor));
            }
    }

    // Every primitive of a mesh has as many morph targets, and the mesh's default weights are
    // one per target.
    void morphWeights() const {
        for (size_t i = 0; i < m.meshes.size(); ++i) {
            const auto& mesh = m.meshes[i];
            const size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
            for (size_t p = 1; p < mesh.primitives.size(); ++p)
                if (mesh.primitives[p].targets.size() != targets)
                    fail(fmt::format("meshes[{}].primitives[{}].targets", i, p),
                         fmt::format("{} morph targets; primitives[0] has {}",
                                     mesh.primitives[p].targets.size(), targets));
            if (!mesh.weights.empty() && mesh.weights.size() != targets)
                fail(fmt::format("meshes[{}].weights", i),
                     fmt::format("{} weights for {} morph targets", mesh.weights.size(), targets));
        }
    }

    // POSITION and NORMAL: float, or the integer types KHR_mesh_quantization allows.
    enum class Quantization { FloatOnly, Position, Normal };
    static constexpr Quantization kFloatOnly = Quantization::FloatOnly;
    static constexpr Quantization kQuantizedPosition = Quantization::Position;
    static constexpr Quantization kQuantizedNormal = Quantization::Normal;
    void vertexAttribute(const std::string& path, int i, Quantization q) const {
        index(path, i, m.accessors.size(), "accessor");
        const auto& a = m.accessors[i];
        const int ct = a.componentType;
        const bool isFloat = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
        const bool signedSmall =
            ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
        const bool unsignedSmall = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                   ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        const bool ok = isFloat ||
                        (q == Quantization::Position && (signedSmall || unsignedSmall)) ||
                        (q == Quantization::Normal && signedSmall && a.normalized);
        if (a.type != TINYGLTF_TYPE_VEC3 || !ok)
            fail(path, q == Quantization::FloatOnly
                           ? "wrong accessor type or componentType (VEC3 of floats; integer "
                             "types need KHR_mesh_quantization)"
                           : "wrong accessor type or componentType for KHR_mesh_quantization");
    }

    // TEXCOORD_n and COLOR_n: float, or normalized unsigned byte / short; with
    // KHR_mesh_quantization, texture coordinates of any byte or short type.
    void attributeOf(const std::string& path, int i, std::initializer_list<int> types,
                     bool quantized) const {
        const auto& a = m.accessors[i];
        const bool typeOk = std::find(types.begin(), types.end(), a.type) != types.end();
        const int ct = a.componentType;
        const bool small = ct == TINYGLTF_COMPONENT_TYPE_BYTE ||
                           ct == TINYGLTF_COMPONENT_TYPE_SHORT ||
                           ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        const bool componentOk = ct == TINYGLTF_COMPONENT_TYPE_FLOAT || (quantized && small) ||
                                 (a.normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                   ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
        if (!typeOk || !componentOk)
            fail(path, "wrong accessor type or componentType");
    }

    void materials() const {
        for (size_t i = 0; i < m.materials.size(); ++i) {
            const auto& mat = m.materials[i];
            const std::string path = fmt::format("materials[{}]", i);
            const auto& factor = mat.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() != 4)
                fail(path + ".pbrMetallicRoughness.baseColorFactor", "needs 4 numbers");
            for (double f : factor)
                if (!(f >= 0.0 && f <= 1.0))
                    fail(path + ".pbrMetallicRoughness.baseColorFactor",
                         "values must be in [0, 1]");
            if (mat.alphaMode != "OPAQUE" && mat.alphaMode != "MASK" && mat.alphaMode != "BLEND")
                fail(path + ".alphaMode",
                     fmt::format("'{}' is not OPAQUE, MASK or BLEND", mat.alphaMode));
            if (!(mat.alphaCutoff >= 0.0) || !std::isfinite(mat.alphaCutoff))
                fail(path + ".alphaCutoff", "must be a finite number >= 0");
        }
    }

    void nodes() const {
        std::vector<int> parent(m.nodes.size(), -1);
        for (size_t i = 0; i < m.nodes.size(); ++i) {
            const auto& n = m.nodes[i];
            const std::string path = fmt::format("nodes[{}]", i);
            if (n.mesh >= 0)
                index(path + ".mesh", n.mesh, m.meshes.size(), "mesh");
            if (n.camera >= 0)
                index(path + ".camera", n.camera, m.cameras.size(), "camera");
            if (!n.matrix.empty() && n.matrix.size() != 16)
                fail(path + ".matrix", "needs 16 numbers");
            finite(path + ".matrix", n.matrix);
            finite(path + ".translation", n.translation);
            finite(path + ".rotation", n.rotation);
            finite(path + ".scale", n.scale);
            if (n.rotation.size() == 4) {
                const double length =
                    std::sqrt(n.rotation[0] * n.rotation[0] + n.rotation[1] * n.rotation[1] +
                              n.rotation[2] * n.rotation[2] + n.rotation[3] * n.rotation[3]);
                if (std::abs(length - 1.0) > kUnitTolerance)
                    fail(path + ".rotation",
                         fmt::format("not a unit quaternion (length {:.6g})", length));
            }
            if (n.skin >= 0)
                index(path + ".skin", n.skin, m.skins.size(), "skin");
            if (n.skin >= 0 && n.mesh < 0)
                fail(path + ".skin", "a skin without a mesh to deform");
            if (!n.weights.empty()) {
                const size_t targets =
                    n.mesh < 0 || m.meshes[static_cast<size_t>(n.mesh)].primitives.empty()
                        ? 0
                        : m.meshes[static_cast<size_t>(n.mesh)].primitives[0].targets.size();
                if (n.weights.size() != targets)
                    fail(path + ".weights",
                         fmt::format("{} weights for {} morph targets", n.weights.size(), targets));
                finite(path + ".weights", n.weights);
            }
            for (size_t c = 0; c < n.children.size(); ++c) {
                const std::string childPath = fmt::format("{}.children[{}]", path, c);
                index(childPath, n.children[c], m.nodes.size(), "node");
                if (parent[n.children[c]] >= 0)
                    fail(childPath, fmt::format("node {} already has parent {}", n.children[c],
                                                parent[n.children[c]]));
                parent[n.children[c]] = static_cast<int>(i);
            }
        }
        // With one parent each, a cycle is a walk up the parents that comes back: mark each
        // chain once (iterative; deep hierarchies are fine).
        std::vector<uint8_t> state(m.nodes.size(), 0); // 0 new, 1 on this walk, 2 done
        std::vector<size_t> walk;
        for (size_t start = 0; start < m.nodes.size(); ++start) {
            walk.clear();
            for (size_t at = start; state[at] != 2;) {
                if (state[at] == 1)
                    fail(fmt::format("nodes[{}]", at), "is its own ancestor (a cycle)");
                state[at] = 1;
                walk.push_back(at);
                if (parent[at] < 0)
                    break;
                at = static_cast<size_t>(parent[at]);
            }
            for (size_t w : walk)
                state[w] = 2;
        }
        for (size_t s = 0; s < m.scenes.size(); ++s)
            for (size_t k = 0; k < m.scenes[s].nodes.size(); ++k)
                index(fmt::format("scenes[{}].nodes[{}]", s, k), m.scenes[s].nodes[k],
                      m.nodes.size(), "node");
        if (m.defaultScene >= 0)
            index("scene", m.defaultScene, m.scenes.size(), "scene");
    }

    void lights() const {
        for (size_t i = 0; i < m.lights.size(); ++i) {
            const auto& l = m.lights[i];
            if (l.type != "spot")
                continue;
            const std::string path =
                fmt::format("extensions.KHR_lights_punctual.lights[{}].spot", i);
            const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            if (!(outer > 0.0 && outer <= kHalfPi + 1e-6))
                fail(path + ".outerConeAngle", fmt::format("{} is outside (0, pi/2]", outer));
            if (!(inner >= 0.0 && inner < outer))
                fail(path + ".innerConeAngle",
                     fmt::format("{} must be at least 0 and less than outerConeAngle {}", inner,
                                 outer));
        }
    }

    // An accessor's min and max, where given, are its data's (the spec: exactly, in its
    // component type); POSITION must give them.
    void bounds() const {
        for (size_t i = 0; i < m.accessors.size(); ++i) {
            const auto& a = m.accessors[i];
            const std::string path = fmt::format("accessors[{}]", i);
            const size_t n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
            if (a.minValues.empty() && a.maxValues.empty())
                continue;
            if ((!a.minValues.empty() && a.minValues.size() != n) ||
                (!a.maxValues.empty() && a.maxValues.size() != n))
                fail(path, fmt::format("min and max need {} numbers each", n));
            finite(path + ".min", a.minValues);
            finite(path + ".max", a.maxValues);
            // Without a bufferView or sparse values the data is the spec's zeros, a placeholder
            // an application may fill: the validator does not hold the bounds to it.
            if (a.bufferView < 0 && !a.sparse.isSparse)
                continue;
            // Streamed: an accessor without a bufferView costs a few bytes whatever its count.
            std::vector<double> lo(n, std::numeric_limits<double>::infinity()), hi(n, -lo[0]);
            visitRawComponents(m, static_cast<int>(i), [&](size_t, size_t c, double v) {
                lo[c] = std::min(lo[c], v), hi[c] = std::max(hi[c], v);
            });
            if (a.bufferView < 0 && (!a.sparse.isSparse || a.count > size_t(a.sparse.count)))
                for (size_t c = 0; c < n; ++c) // the elements no sparse value replaces are zeros
                    lo[c] = std::min(lo[c], 0.0), hi[c] = std::max(hi[c], 0.0);
            const auto differs = [](double declared, double actual) {
                return std::abs(declared - actual) > 1e-6 + 1e-5 * std::abs(actual);
            };
            for (size_t c = 0; c < n; ++c) {
                if (!a.minValues.empty() && differs(a.minValues[c], lo[c]))
                    fail(fmt::format("{}.min[{}]", path, c),
                         fmt::format("{} but the data's minimum is {}", a.minValues[c], lo[c]));
                if (!a.maxValues.empty() && differs(a.maxValues[c], hi[c]))
                    fail(fmt::format("{}.max[{}]", path, c),
                         fmt::format("{} but the data's maximum is {}", a.maxValues[c], hi[c]));
            }
        }
        for (size_t i = 0; i < m.meshes.size(); ++i)
            for (size_t p = 0; p < m.meshes[i].primitives.size(); ++p) {
                const auto& prim = m.meshes[i].primitives[p];
                const auto pos = prim.attributes.find("POSITION");
                if (pos != prim.attributes.end() && (m.accessors[pos->second].minValues.empty() ||
                                                     m.accessors[pos->second].maxValues.empty()))
                    warnOnce("POSITION bounds", fmt::format("accessors[{}]", pos->second),
                             "a POSITION accessor without min and max (the spec requires them)");
            }
    }
};

} // namespace

bool hasPositions(const tinygltf::Primitive& primitive) {
    return primitive.attributes.contains("POSITION");
}

uint64_t elementBytes(int componentType, int type) {
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(componentType));
    const int count = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type));
    return size > 0 && count > 0 ? uint64_t(size) * uint64_t(count) : 0;
}

void validateModel(const std::filesystem::path& file, const tinygltf::Model& model,
                   std::vector<std::string>* warnings) {
    OnceWarnings once(file, warnings);
    const Checker c{file, model, once};
    c.bufferViews();
    c.accessors();
    c.meshes();
    c.morphWeights();
    checkMeshData(file, model);
    c.bounds();
    c.nodes();
    c.materials();
    c.lights();
    checkSchemaValues(file, model, once);
    reportUnusedParts(model, once);
}

OnceWarnings::OnceWarnings(const std::filesystem::path& file, std::vector<std::string>* out)
    : mFile(file), mOut(out) {}

void OnceWarnings::add(const std::string& cls, const std::string& path, const std::string& what) {
    if (mOut && mClasses.insert(cls).second)
        mOut->push_back(mFile.string() + ": " + path + ": " + what);
}

} // namespace penumbra::gltf
