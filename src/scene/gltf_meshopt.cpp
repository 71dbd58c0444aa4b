// EXT_meshopt_compression: the JSON stage checks and redirects the compressed views, the model
// stage decodes them with libmeshoptimizer (whose decoders bound-check their input and return an
// error on a malformed stream; the preconditions they assert are checked here first).
#include "penumbra/error.h"
#include "scene/gltf_compression.h"

#include <fmt/format.h>
#include <meshoptimizer.h>

#include <limits>
#include <optional>

namespace penumbra::gltf {
namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& what) {
    throw InputError(file.string(), what);
}

const nlohmann::json* extensionOf(const nlohmann::json& owner) {
    if (!owner.is_object() || !owner.contains("extensions") || !owner["extensions"].is_object() ||
        !owner["extensions"].contains(kMeshopt))
        return nullptr;
    return &owner["extensions"][kMeshopt];
}

std::optional<uint64_t> unsignedField(const std::filesystem::path& file, const std::string& path,
                                      const nlohmann::json& o, const char* key, bool required) {
    if (!o.contains(key)) {
        if (required)
            refuse(file, fmt::format("{}.{}: missing", path, key));
        return std::nullopt;
    }
    if (!o[key].is_number_unsigned())
        refuse(file, fmt::format("{}.{}: not a non-negative integer", path, key));
    return o[key].get<uint64_t>();
}

// The stride rules of the extension, which are also the decoders' preconditions.
void checkLayout(const std::filesystem::path& file, const std::string& path, const MeshoptView& v) {
    const bool attributes = v.mode == "ATTRIBUTES";
    if (attributes ? (v.stride == 0 || v.stride > 256 || v.stride % 4)
                   : (v.stride != 2 && v.stride != 4))
        refuse(file,
               fmt::format("{}.byteStride: {} is not allowed in mode {}", path, v.stride, v.mode));
    if (!attributes && v.mode != "TRIANGLES" && v.mode != "INDICES")
        refuse(file,
               fmt::format("{}.mode: '{}' is not ATTRIBUTES, TRIANGLES or INDICES", path, v.mode));
    if (v.mode == "TRIANGLES" && v.count % 3)
        refuse(file,
               fmt::format("{}.count: {} triangle indices are not a multiple of 3", path, v.count));
    const bool filterOk =
        v.filter == "NONE" ||
        (attributes && v.filter == "OCTAHEDRAL" && (v.stride == 4 || v.stride == 8)) ||
        (attributes && v.filter == "QUATERNION" && v.stride == 8) ||
        (attributes && v.filter == "EXPONENTIAL");
    if (!filterOk)
        refuse(file, fmt::format("{}.filter: '{}' does not apply to mode {} with byteStride {}",
                                 path, v.filter, v.mode, v.stride));
}

} // namespace

bool isMeshoptFallback(const nlohmann::json& buffer) {
    const nlohmann::json* e = extensionOf(buffer);
    return e && e->is_object() && e->contains("fallback") && (*e)["fallback"] == true;
}

std::vector<MeshoptView> prepareMeshopt(const std::filesystem::path& file, nlohmann::json& j,
                                        uint64_t maxDecodedBytes) {
    std::vector<MeshoptView> out;
    if (!j.contains("bufferViews") || !j.contains("buffers"))
        return out;
    auto& buffers = j["buffers"];
    uint64_t decodedTotal = 0;
    for (size_t i = 0; i < j["bufferViews"].size(); ++i) {
        auto& view = j["bufferViews"][i];
        const std::string viewPath = fmt::format("bufferViews[{}]", i);
        const nlohmann::json* e = extensionOf(view);
        if (!e) {
            // checkReferences has checked view.buffer's index.
            if (isMeshoptFallback(buffers[view["buffer"].get<size_t>()]))
                refuse(file, fmt::format("{}.buffer: buffer {} is a meshopt fallback and holds "
                                         "no data",
                                         viewPath, view["buffer"].dump()));
            continue;
        }
        const std::string path = viewPath + ".extensions." + kMeshopt;
        if (!e->is_object())
            refuse(file, path + ": not an object");
        const uint64_t buffer = *unsignedField(file, path, *e, "buffer", true);
        if (buffer >= buffers.size() || isMeshoptFallback(buffers[buffer]))
            refuse(file, fmt::format("{}.buffer: {} is not a buffer with data", path, buffer));
        const uint64_t offset = unsignedField(file, path, *e, "byteOffset", false).value_or(0);
        const uint64_t length = *unsignedField(file, path, *e, "byteLength", true);
        const auto declared = unsignedField(file, fmt::format("buffers[{}]", buffer),
                                            buffers[buffer], "byteLength", true);
        if (length == 0 || offset > *declared || length > *declared - offset)
            refuse(file, fmt::format("{}: bytes {}..{} are not inside buffer {} ({} bytes)", path,
                                     offset, offset + length, buffer, *declared));
        MeshoptView v{.view = i,
                      .count = *unsignedField(file, path, *e, "count", true),
                      .stride = *unsignedField(file, path, *e, "byteStride", true)};
        if (!e->contains("mode") || !(*e)["mode"].is_string())
            refuse(file, path + ".mode: missing or not a string");
        v.mode = (*e)["mode"];
        v.filter = e->contains("filter") && (*e)["filter"].is_string()
                       ? (*e)["filter"].get<std::string>()
                       : "NONE";
        checkLayout(file, path, v);
        if (v.count == 0 || v.count > maxDecodedBytes / v.stride ||
            decodedTotal + v.count * v.stride > maxDecodedBytes)
            refuse(file, fmt::format("{}.count: {} elements of {} bytes pass the cap of {} bytes "
                                     "decoded",
                                     path, v.count, v.stride, maxDecodedBytes));
        decodedTotal += v.count * v.stride;
        // The parser reads the compressed bytes into the view; decodeMeshopt replaces them.
        view["buffer"] = buffer;
        view["byteOffset"] = offset;
        view["byteLength"] = length;
        out.push_back(std::move(v));
    }
    for (auto& buffer : buffers)
        if (isMeshoptFallback(buffer)) // no view reads it now: a one-byte stand-in for the parser
            buffer = {{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
    return out;
}

void decodeMeshopt(const std::filesystem::path& file, tinygltf::Model& model,
                   const std::vector<MeshoptView>& views) {
    for (const MeshoptView& v : views) {
        tinygltf::BufferView& view = model.bufferViews[v.view];
        const std::string path = fmt::format("bufferViews[{}].extensions.{}", v.view, kMeshopt);
        const std::vector<unsigned char>& source = model.buffers[view.buffer].data;
        if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset)
            refuse(file, path + ": the compressed bytes run past their buffer");
        const unsigned char* bytes = source.data() + view.byteOffset;
        std::vector<unsigned char> decoded(v.count * v.stride);
        const int rc =
            v.mode == "ATTRIBUTES"  ? meshopt_decodeVertexBuffer(decoded.data(), v.count, v.stride,
                                                                 bytes, view.byteLength)
            : v.mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), v.count, v.stride,
                                                                bytes, view.byteLength)
                                    : meshopt_decodeIndexSequence(decoded.data(), v.count, v.stride,
                                                                  bytes, view.byteLength);
        if (rc != 0)
            refuse(file, fmt::format("{}: the {} stream does not decode (meshopt error {})", path,
                                     v.mode, rc));
        if (v.filter == "OCTAHEDRAL")
            meshopt_decodeFilterOct(decoded.data(), v.count, v.stride);
        else if (v.filter == "QUATERNION")
            meshopt_decodeFilterQuat(decoded.data(), v.count, v.stride);
        else if (v.filter == "EXPONENTIAL")
            meshopt_decodeFilterExp(decoded.data(), v.count, v.stride);
        tinygltf::Buffer out;
        out.data = std::move(decoded);
        model.buffers.push_back(std::move(out));
        view.buffer = static_cast<int>(model.buffers.size() - 1);
        view.byteOffset = 0;
        view.byteLength = v.count * v.stride;
    }
}

} // namespace penumbra::gltf
