// KHR_draco_mesh_compression: each compressed primitive's Draco stream decoded with libdraco into
// a buffer of its own, its accessors rewritten to read it (attributes as floats, normalized
// integers converted by Draco, indices as 32-bit). The accessors' counts must be the decoded
// ones; their min and max become the decoded values', since quantization moves those off the
// original bounds the asset states.
#include "penumbra/error.h"
#include "scene/gltf_compression.h"

#include <draco/compression/decode.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

namespace penumbra::gltf {
namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

struct Decoding {
    const std::filesystem::path& file;
    tinygltf::Model& model;
    uint64_t maxDecodedBytes;
    uint64_t decodedTotal = 0;
    std::set<int> rewritten; // accessors already given decoded data

    [[noreturn]] void refuse(const std::string& what) const {
        throw InputError(file.string(), what);
    }

    // A view over a new buffer holding `bytes`.
    int appendView(std::vector<unsigned char> bytes) {
        tinygltf::Buffer buffer;
        buffer.data = std::move(bytes);
        tinygltf::BufferView view;
        view.buffer = static_cast<int>(model.buffers.size());
        view.byteLength = buffer.data.size();
        model.buffers.push_back(std::move(buffer));
        model.bufferViews.push_back(view);
        return static_cast<int>(model.bufferViews.size() - 1);
    }

    void reserve(const std::string& path, uint64_t elements, uint64_t bytesEach) {
        if (elements > maxDecodedBytes / bytesEach ||
            decodedTotal + elements * bytesEach > maxDecodedBytes)
            refuse(fmt::format("{}: {} decoded elements pass the cap of {} bytes", path, elements,
                               maxDecodedBytes));
        decodedTotal += elements * bytesEach;
    }

    tinygltf::Accessor& accessorFor(const std::string& path, int index) {
        if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
            refuse(fmt::format("{}: accessor {} is out of range", path, index));
        if (!rewritten.insert(index).second)
            refuse(fmt::format("{}: accessor {} is shared with another compressed primitive", path,
                               index));
        return model.accessors[index];
    }

    void primitive(const std::string& path, tinygltf::Primitive& prim, const tinygltf::Value& ext) {
        if (!ext.IsObject() || !ext.Has("bufferView") || !ext.Get("bufferView").IsInt() ||
            !ext.Has("attributes") || !ext.Get("attributes").IsObject())
            refuse(path + ": needs a bufferView and an attributes object");
        const int viewIndex = ext.Get("bufferView").GetNumberAsInt();
        if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model.bufferViews.size())
            refuse(fmt::format("{}.bufferView: {} is out of range", path, viewIndex));
        const tinygltf::BufferView& view = model.bufferViews[viewIndex];
        const auto& source = model.buffers[view.buffer].data;
        if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset)
            refuse(path + ".bufferView: its bytes run past their buffer");
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
            refuse(path + ": compresses only triangles and triangle strips");

        draco::DecoderBuffer stream;
        stream.Init(reinterpret_cast<const char*>(source.data() + view.byteOffset),
                    view.byteLength);
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&stream);
        if (!decoded.ok())
            refuse(fmt::format("{}: the Draco stream does not decode ({})", path,
                               decoded.status().error_msg_string()));
        const draco::Mesh& mesh = *decoded.value();
        const uint64_t points = mesh.num_points(), faces = mesh.num_faces();

        const tinygltf::Value& ids = ext.Get("attributes");
        for (const std::string& name : ids.Keys()) {
            const std::string at = path + ".attributes." + name;
            if (!ids.Get(name).IsInt() || !prim.attributes.contains(name))
                refuse(at + ": not an attribute id of one of the primitive's attributes");
            const draco::PointAttribute* attribute =
                ids.Get(name).GetNumberAsInt() < 0
                    ? nullptr
                    : mesh.GetAttributeByUniqueId(
                          static_cast<uint32_t>(ids.Get(name).GetNumberAsInt()));
            if (!attribute)
                refuse(fmt::format("{}: the stream has no attribute {}", at,
                                   ids.Get(name).GetNumberAsInt()));
            tinygltf::Accessor& a = accessorFor(at, prim.attributes.at(name));
            const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
            if (components != attribute->num_components() || a.count != points)
                refuse(fmt::format("{}: the accessor is {} x {} components, the stream {} x {}", at,
                                   a.count, components, points, attribute->num_components()));
            reserve(at, points * static_cast<uint64_t>(components), 4);
            std::vector<float> values(points * static_cast<size_t>(components));
            for (uint32_t p = 0; p < points; ++p)
                if (!attribute->ConvertValue<float>(attribute->mapped_index(draco::PointIndex(p)),
                                                    static_cast<int8_t>(components),
                                                    values.data() + size_t{p} * components))
                    refuse(at + ": a value does not convert to float");
            std::vector<unsigned char> bytes(values.size() * 4);
            std::memcpy(bytes.data(), values.data(), bytes.size());
            rewrite(a, appendView(std::move(bytes)), TINYGLTF_COMPONENT_TYPE_FLOAT);
            a.minValues.assign(static_cast<size_t>(components), HUGE_VAL);
            a.maxValues.assign(static_cast<size_t>(components), -HUGE_VAL);
            for (size_t k = 0; k < values.size(); ++k) {
                a.minValues[k % components] =
                    std::min<double>(a.minValues[k % components], values[k]);
                a.maxValues[k % components] =
                    std::max<double>(a.maxValues[k % components], values[k]);
            }
        }

        reserve(path, faces * 3, 4);
        std::vector<uint32_t> indices;
        indices.reserve(faces * 3);
        for (uint32_t f = 0; f < faces; ++f)
            for (const draco::PointIndex& p : mesh.face(draco::FaceIndex(f)))
                indices.push_back(p.value());
        std::vector<unsigned char> bytes(indices.size() * 4);
        std::memcpy(bytes.data(), indices.data(), bytes.size());
        const int indexView = appendView(std::move(bytes));
        if (prim.indices >= 0) {
            tinygltf::Accessor& a = accessorFor(path + " (indices)", prim.indices);
            if (a.count != indices.size())
                refuse(fmt::format("{}: the indices accessor has {} elements, the stream {}", path,
                                   a.count, indices.size()));
            rewrite(a, indexView, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
        } else {
            tinygltf::Accessor a;
            a.type = TINYGLTF_TYPE_SCALAR;
            a.count = indices.size();
            rewrite(a, indexView, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
            model.accessors.push_back(a);
            prim.indices = static_cast<int>(model.accessors.size() - 1);
        }
        prim.mode = TINYGLTF_MODE_TRIANGLES; // Draco decodes a strip as its triangles
    }

    static void rewrite(tinygltf::Accessor& a, int view, int componentType) {
        a.bufferView = view;
        a.byteOffset = 0;
        a.componentType = componentType;
        a.normalized = false;
        a.sparse.isSparse = false;
        a.minValues.clear();
        a.maxValues.clear();
    }
};

} // namespace

std::vector<DetachedIndices> detachViewlessIndices(nlohmann::json& j) {
    std::vector<DetachedIndices> out;
    if (!j.contains("meshes") || !j.contains("accessors"))
        return out;
    auto& accessors = j["accessors"];
    for (size_t m = 0; m < j["meshes"].size(); ++m) {
        auto& primitives = j["meshes"][m]["primitives"];
        for (size_t p = 0; p < primitives.size(); ++p) {
            auto& prim = primitives[p];
            if (!prim.contains("indices")) // checkReferences: an index in range when present
                continue;
            const int accessor = prim["indices"].get<int>();
            if (accessors[accessor].is_object() && !accessors[accessor].contains("bufferView")) {
                out.push_back({m, p, accessor});
                prim.erase("indices");
            }
        }
    }
    return out;
}

void restoreIndices(tinygltf::Model& model, const std::vector<DetachedIndices>& detached) {
    for (const DetachedIndices& d : detached)
        model.meshes[d.mesh].primitives[d.primitive].indices = d.accessor;
}

void decodeDraco(const std::filesystem::path& file, tinygltf::Model& model,
                 uint64_t maxDecodedBytes) {
    Decoding d{file, model, maxDecodedBytes};
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& prim = model.meshes[m].primitives[p];
            const auto e = prim.extensions.find(kDraco);
            if (e != prim.extensions.end())
                d.primitive(fmt::format("meshes[{}].primitives[{}].extensions.{}", m, p, kDraco),
                            prim, e->second);
        }
}

} // namespace penumbra::gltf
