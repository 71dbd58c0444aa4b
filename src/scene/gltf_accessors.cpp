#include "scene/gltf_accessors.h"

#include "scene/gltf_validate.h"

#include <algorithm>
#include <cstring>

namespace penumbra::gltf {
namespace {

// One component at `p` as a float, normalized integers mapped as the spec says.
float component(const uint8_t* p, int componentType, bool normalized) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float v = static_cast<float>(static_cast<int8_t>(*p));
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? static_cast<float>(*p) / 255.0f : static_cast<float>(*p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f)
                          : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? static_cast<float>(v) / 65535.0f : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return static_cast<float>(v);
    }
    default:
        return 0.0f;
    }
}

template <typename Visit>
void forEachElement(const tinygltf::Model& m, int index, Visit visit) {
    const tinygltf::Accessor& a = m.accessors[index];
    const uint64_t bytes = elementBytes(a.componentType, a.type);
    if (a.bufferView >= 0) {
        const auto& view = m.bufferViews[a.bufferView];
        const uint64_t stride = view.byteStride ? view.byteStride : bytes;
        const uint8_t* base = m.buffers[view.buffer].data.data() + view.byteOffset + a.byteOffset;
        for (size_t i = 0; i < a.count; ++i)
            visit(i, base + i * stride);
    }
    if (!a.sparse.isSparse)
        return;
    const auto& s = a.sparse;
    const auto& iv = m.bufferViews[s.indices.bufferView];
    const auto& vv = m.bufferViews[s.values.bufferView];
    const uint8_t* indices =
        m.buffers[iv.buffer].data.data() + iv.byteOffset + s.indices.byteOffset;
    const uint8_t* values = m.buffers[vv.buffer].data.data() + vv.byteOffset + s.values.byteOffset;
    const uint64_t indexBytes = elementBytes(s.indices.componentType, TINYGLTF_TYPE_SCALAR);
    for (int k = 0; k < s.count; ++k) {
        uint64_t target = 0;
        std::memcpy(&target, indices + k * indexBytes, indexBytes);
        visit(static_cast<size_t>(target), values + k * bytes);
    }
}

} // namespace

std::vector<float> readFloats(const tinygltf::Model& m, int index) {
    const tinygltf::Accessor& a = m.accessors[index];
    const int n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    std::vector<float> out(a.count * static_cast<size_t>(n), 0.0f); // no bufferView: zeros
    forEachElement(m, index, [&](size_t i, const uint8_t* p) {
        for (int c = 0; c < n; ++c)
            out[i * n + c] = component(p + c * size, a.componentType, a.normalized);
    });
    return out;
}

void visitRawComponents(const tinygltf::Model& m, int index,
                        const std::function<void(size_t, size_t, double)>& visit) {
    const tinygltf::Accessor& a = m.accessors[index];
    const int n = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    forEachElement(m, index, [&](size_t i, const uint8_t* p) {
        for (int c = 0; c < n; ++c)
            visit(i, static_cast<size_t>(c), component(p + c * size, a.componentType, false));
    });
}

std::vector<uint32_t> readIndices(const tinygltf::Model& m, int index) {
    const tinygltf::Accessor& a = m.accessors[index];
    std::vector<uint32_t> out(a.count, 0);
    forEachElement(m, index, [&](size_t i, const uint8_t* p) {
        uint32_t v = 0; // 1, 2 or 4 bytes (gltf_validate.cpp refused other index types)
        const int bytes = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
        std::memcpy(&v, p, static_cast<size_t>(std::clamp(bytes, 0, 4)));
        out[i] = v;
    });
    return out;
}

} // namespace penumbra::gltf
