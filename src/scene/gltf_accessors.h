#pragma once
// Reads validated accessors into plain arrays: every component type the spec allows
// (normalized integers scaled to [0,1] or [-1,1]), byte strides, accessors without a
// bufferView (zeros), and sparse substitution. Call only after validateModel.
#include <tiny_gltf.h>

#include <cstdint>
#include <vector>

namespace penumbra::gltf {

// count x components floats.
std::vector<float> readFloats(const tinygltf::Model& model, int accessor);
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor);
// count x components values as stored (normalized integers not scaled): what min and max bound.
std::vector<double> readRawComponents(const tinygltf::Model& model, int accessor);

} // namespace penumbra::gltf
