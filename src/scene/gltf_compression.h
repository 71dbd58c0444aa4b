#pragma once
// Compressed glTF geometry, decoded into plain buffers before the model validator sees it, so
// that every decoded byte passes the same checks as an uncompressed asset's:
// - EXT_meshopt_compression (libmeshoptimizer): bufferViews whose bytes are a meshopt stream
//   (vertex attributes, triangle indices or index sequences, with the octahedral, quaternion and
//   exponential filters). The JSON is prepared before the parser reads it (the views point at
//   their compressed bytes, fallback buffers, which hold no data, become empty stand-ins), then
//   the parsed model's views are decoded into a buffer of their own.
// - KHR_draco_mesh_compression (libdraco): a primitive's attributes and indices from one Draco
//   stream; its accessors get the decoded data (floats, 32-bit indices).
// Decoded sizes are checked (64-bit) against the cap before anything is allocated; a stream
// that does not decode is refused with its JSON path.
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::gltf {

struct MeshoptView {
    size_t view = 0;
    uint64_t count = 0, stride = 0;
    std::string mode, filter; // "ATTRIBUTES", "TRIANGLES", "INDICES"; "NONE", "OCTAHEDRAL", ...
};

// A buffer marked as EXT_meshopt_compression's fallback: it holds no data (and needs no URI).
bool isMeshoptFallback(const nlohmann::json& buffer);

// JSON stage (after checkJson): checks each EXT_meshopt_compression view's fields by JSON path
// and points the view at its compressed bytes; empties fallback buffers (no view may read them).
std::vector<MeshoptView> prepareMeshopt(const std::filesystem::path& file, nlohmann::json& json,
                                        uint64_t maxDecodedBytes);

// JSON stage: the parser refuses an indices accessor without a bufferView (valid glTF: zeros,
// and how every Draco primitive's indices come); such primitives lose their `indices` while it
// parses, and restoreIndices gives them back.
struct DetachedIndices {
    size_t mesh = 0, primitive = 0;
    int accessor = -1;
};
std::vector<DetachedIndices> detachViewlessIndices(nlohmann::json& json);
void restoreIndices(tinygltf::Model& model, const std::vector<DetachedIndices>& detached);

// Model stage (after parsing, before validateModel).
void decodeMeshopt(const std::filesystem::path& file, tinygltf::Model& model,
                   const std::vector<MeshoptView>& views);
void decodeDraco(const std::filesystem::path& file, tinygltf::Model& model,
                 uint64_t maxDecodedBytes);

} // namespace penumbra::gltf
