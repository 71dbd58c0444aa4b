#pragma once
// Base-colour images of a glTF asset: hostile bytes are decoded only when a material uses them,
// only as PNG or JPEG (the formats glTF 2.0 allows), and only after their header's dimensions
// pass the size checks.
#include "penumbra/scene.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace penumbra::gltf {

inline constexpr uint32_t kMaxImageSide = 16384;

struct ImageDecodePolicy {
    std::set<int> wanted; // images a base-colour texture uses; the others are never decoded
    uint64_t maxDecodedBytes = uint64_t{4} << 30; // RGBA8 bytes of all images together
    uint64_t decodedBytes = 0;
    // Wanted images we do not decode and why: a format we do not read (KTX2 / Basis Universal,
    // WebP), or bytes that are not an image or are damaged. Their textures fall back to the
    // material's colour factor with a warning. (Past the size caps is an error instead.)
    std::map<int, std::string> undecodable;
};

// The images that base-colour and transmission textures use, from the checked JSON.
ImageDecodePolicy baseColorImages(const nlohmann::json& gltf);

// tinygltf's image callback (user data: an ImageDecodePolicy): RGBA8 into image->image.
bool decodeImage(tinygltf::Image* image, int index, std::string* err, std::string* warn,
                 int requestedWidth, int requestedHeight, const unsigned char* bytes, int size,
                 void* policy);

// Scene::images and Scene::textures from the decoded model; returns, per glTF texture, its
// index in Scene::textures (-1 when it has no usable image). Refuses a wanted image that could
// not be read.
std::vector<int32_t> readTextures(const std::filesystem::path& file, tinygltf::Model& model,
                                  const ImageDecodePolicy& policy, Scene& scene,
                                  std::vector<std::string>* warnings);

} // namespace penumbra::gltf
