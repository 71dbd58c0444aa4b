#pragma once
// glTF 2.0 in: .gltf (external or data-URI buffers) and .glb. Assets are hostile until proven
// otherwise: the container, the JSON and every index, count and byte range are checked (64-bit
// arithmetic) before anything reaches the GPU or Embree, and a refusal names the file and the
// JSON path: InputError("scene.gltf", "meshes[0].primitives[0].indices: ...").
#include "penumbra/scene.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct GltfOptions {
    uint64_t maxFileSize = uint64_t{1} << 30;     // the asset and each file it references
    uint64_t maxTriangles = 100'000'000;          // after flattening instanced meshes
    uint64_t maxImageBytes = uint64_t{4} << 30;   // decoded RGBA8 bytes of all images
    std::vector<std::string>* warnings = nullptr; // skipped content (points, lines, ...)
    // The pose: none (the nodes at rest) or seconds into `animation` ("" the first, a name or an
    // index).
    std::optional<double> time;
    std::string animation;
};

Scene loadGltf(const std::filesystem::path& file, const GltfOptions& options = {});

} // namespace penumbra
