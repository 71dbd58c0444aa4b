#pragma once
// Checks a parsed tinygltf::Model the way the Khronos glTF-Validator's error classes do, before
// anything reads through its indices: every index in range, every byte range inside its
// buffer (checked 64-bit arithmetic), strides, component types and accessor types, counts,
// sparse indices, the node graph (one parent, no cycles), finite and unit transforms, accessor
// bounds against the data, spot cones. Throws
// InputError(file, "<JSON path>: <what>").
//
// Parts Penumbra does not use (camera aspect ratios, material
// extensions) are checked as far as their references go and reported in `warnings`, one line per
// class with the first JSON path: "<path>: <what>; <part> ignored".
#include <tiny_gltf.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace penumbra::gltf {

void validateModel(const std::filesystem::path& file, const tinygltf::Model& model,
                   std::vector<std::string>* warnings);

// Warnings, one per class: "<file>: <first JSON path>: <what>".
class OnceWarnings {
public:
    OnceWarnings(const std::filesystem::path& file, std::vector<std::string>* out);
    void add(const std::string& cls, const std::string& path, const std::string& what);

private:
    const std::filesystem::path& mFile;
    std::vector<std::string>* mOut;
    std::set<std::string> mClasses;
};

// The schema's enumerations and ranges: samplers, material factors, normalized accessors, light
// colours, cameras, scene roots (gltf_values.cpp).
void checkSchemaValues(const std::filesystem::path& file, const tinygltf::Model& model,
                       OnceWarnings& once);

// Data errors in what is drawn: non-finite attributes, non-unit normals, sparse index order,
// accessor alignment, strides of shared and index views, missing TEXCOORD sets, node transform
// shapes (gltf_mesh_checks.cpp).
void checkMeshData(const std::filesystem::path& file, const tinygltf::Model& model);

// Camera aspect ratios, material extensions (gltf_unused.cpp).
void reportUnusedParts(const tinygltf::Model& model, OnceWarnings& once);

// Whether the primitive has positions to draw (the spec: skip it when it has none).
bool hasPositions(const tinygltf::Primitive& primitive);

// Bytes of one element of an accessor (component size x component count); 0 if invalid.
uint64_t elementBytes(int componentType, int type);

} // namespace penumbra::gltf
