#pragma once
// Checks a parsed tinygltf::Model the way the Khronos glTF-Validator's error classes do, before
// anything reads through its indices: every index in range, every byte range inside its
// buffer (checked 64-bit arithmetic), strides, component types and accessor types, counts,
// sparse indices, the node graph (one parent, no cycles), finite transforms. Throws
// InputError(file, "<JSON path>: <what>").
#include <tiny_gltf.h>

#include <filesystem>

namespace penumbra::gltf {

void validateModel(const std::filesystem::path& file, const tinygltf::Model& model);

// Bytes of one element of an accessor (component size x component count); 0 if invalid.
uint64_t elementBytes(int componentType, int type);

} // namespace penumbra::gltf
