#pragma once
// Reads validated accessors into plain arrays: every component type the spec allows
// (normalized integers scaled to [0,1] or [-1,1]), byte strides, accessors without a
// bufferView (zeros), and sparse substitution. Call only after validateModel.
#include <tiny_gltf.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace penumbra::gltf {

// count x components floats.
std::vector<float> readFloats(const tinygltf::Model& model, int accessor);
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor);
// The values as stored (normalized integers not scaled: what min and max bound), one by one
// without allocating: (element, component, value) for the elements that have data (an accessor
// without a bufferView: only its sparse ones; the rest are zeros).
void visitRawComponents(const tinygltf::Model& model, int accessor,
                        const std::function<void(size_t, size_t, double)>& visit);

} // namespace penumbra::gltf
