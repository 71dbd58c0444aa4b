#include "scene/gltf_images.h"

#include "penumbra/error.h"

#include <fmt/format.h>
#include <stb/stb_image.h>

#include <cstring>
#include <map>

namespace penumbra::gltf {
namespace {

bool isPng(const unsigned char* b, int size) {
    static constexpr unsigned char kMagic[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    return size >= 8 && std::memcmp(b, kMagic, 8) == 0;
}

// Every chunk's declared length fits in the bytes, up to IEND: stb reserves a chunk's declared
// length before reading it, so a 95-byte file could otherwise ask for gigabytes.
bool pngChunksFit(const unsigned char* b, int size) {
    const auto end = static_cast<uint64_t>(size);
    for (uint64_t at = 8; at + 12 <= end;) {
        const uint64_t length = uint64_t{b[at]} << 24 | uint64_t{b[at + 1]} << 16 |
                                uint64_t{b[at + 2]} << 8 | uint64_t{b[at + 3]};
        if (length > end - at - 12)
            return false;
        if (std::memcmp(b + at + 4, "IEND", 4) == 0)
            return true;
        at += 12 + length;
    }
    return false; // no IEND: truncated
}

bool isJpeg(const unsigned char* b, int size) {
    return size >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff;
}

// Image formats glTF extensions bring that we recognise but do not decode (shadows do not depend
// on them): the format's name, or nullptr.
const char* otherImageFormat(const unsigned char* b, int size) {
    static constexpr unsigned char kKtx2[12] = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                                '0',  0xBB, '\r', '\n', 0x1A, '\n'};
    if (size >= 12 && std::memcmp(b, kKtx2, 12) == 0)
        return "KTX2 (KHR_texture_basisu)";
    if (size >= 12 && std::memcmp(b, "RIFF", 4) == 0 && std::memcmp(b + 8, "WEBP", 4) == 0)
        return "WebP (EXT_texture_webp)";
    return nullptr;
}

TextureWrap wrapOf(int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE)
        return TextureWrap::ClampToEdge;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
        return TextureWrap::MirroredRepeat;
    return TextureWrap::Repeat;
}

} // namespace

ImageDecodePolicy baseColorImages(const nlohmann::json& j) {
    ImageDecodePolicy policy;
    if (!j.contains("materials") || !j.contains("textures"))
        return policy;
    const auto& textures = j["textures"];
    const auto want = [&](const nlohmann::json& info) {
        const auto& t = textures[info["index"].get<size_t>()];
        if (t.contains("source"))
            policy.wanted.insert(t["source"].get<int>());
    };
    for (const auto& m : j["materials"]) {
        if (m.contains("pbrMetallicRoughness") &&
            m["pbrMetallicRoughness"].contains("baseColorTexture"))
            want(m["pbrMetallicRoughness"]["baseColorTexture"]);
        // The transmission's texture too: the truth reads light through it.
        if (m.contains("extensions") && m["extensions"].contains("KHR_materials_transmission") &&
            m["extensions"]["KHR_materials_transmission"].contains("transmissionTexture"))
            want(m["extensions"]["KHR_materials_transmission"]["transmissionTexture"]);
    }
    return policy;
}

bool decodeImage(tinygltf::Image* image, int index, std::string* err, std::string*, int, int,
                 const unsigned char* bytes, int size, void* user) {
    auto& policy = *static_cast<ImageDecodePolicy*>(user);
    if (!policy.wanted.contains(index))
        return true;
    // Past a cap: an error (the caps guard the machine). Damaged or unknown: the factor.
    auto refuse = [&](const std::string& why) {
        if (err)
            *err += fmt::format("images[{}]: {}\n", index, why);
        return false;
    };
    auto fallBack = [&](const std::string& why) {
        policy.undecodable[index] = why;
        return true;
    };
    if (!bytes || size <= 0)
        return fallBack("no image bytes");
    if (const char* format = otherImageFormat(bytes, size))
        return fallBack(fmt::format("{} is not decoded here", format));
    if (!isPng(bytes, size) && !isJpeg(bytes, size))
        return fallBack("not a PNG, JPEG, KTX2 or WebP image");
    if (isPng(bytes, size) && !pngChunksFit(bytes, size))
        return fallBack("damaged: a PNG chunk runs past the end of the image (truncated?)");
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, size, &width, &height, &channels))
        return fallBack(fmt::format("damaged: cannot read its header ({})", stbi_failure_reason()));
    if (width < 1 || height < 1 || width > static_cast<int>(kMaxImageSide) ||
        height > static_cast<int>(kMaxImageSide))
        return refuse(
            fmt::format("{}x{} pixels is outside 1..{} per side", width, height, kMaxImageSide));
    const uint64_t bytesNeeded = uint64_t(width) * uint64_t(height) * 4;
    if (policy.decodedBytes + bytesNeeded > policy.maxDecodedBytes)
        return refuse(
            fmt::format("the images need more than {} bytes decoded", policy.maxDecodedBytes));
    policy.decodedBytes += bytesNeeded;
    int w = 0, h = 0;
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &channels, 4);
    if (!pixels) {
        policy.decodedBytes -= bytesNeeded;
        return fallBack(fmt::format("damaged: cannot decode it ({})", stbi_failure_reason()));
    }
    if (w != width || h != height) {
        stbi_image_free(pixels);
        policy.decodedBytes -= bytesNeeded;
        return fallBack("damaged: the decoded size differs from the header's");
    }
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
    stbi_image_free(pixels);
    return true;
}

namespace {
// A texture whose only image comes through KHR_texture_basisu or EXT_texture_webp.
bool usesOtherSource(const tinygltf::Texture& texture) {
    return texture.extensions.contains("KHR_texture_basisu") ||
           texture.extensions.contains("EXT_texture_webp");
}
} // namespace

std::vector<int32_t> readTextures(const std::filesystem::path& file, tinygltf::Model& model,
                                  const ImageDecodePolicy& policy, Scene& scene,
                                  std::vector<std::string>* warnings) {
    std::vector<int32_t> textureOf(model.textures.size(), -1);
    std::map<int, uint32_t> sceneImage;
    for (int i : policy.wanted) {
        tinygltf::Image& image = model.images[static_cast<size_t>(i)];
        const std::string named = image.uri.empty() || image.uri.starts_with("data:")
                                      ? fmt::format("images[{}]", i)
                                      : fmt::format("images[{}] '{}'", i, image.uri);
        const auto fallBack = [&](const std::string& why) {
            if (warnings)
                warnings->push_back(fmt::format("{}: {}: {}; its materials use their base colour "
                                                "factor (and alpha-tested ones cast no holes)",
                                                file.string(), named, why));
        };
        if (const auto other = policy.undecodable.find(i); other != policy.undecodable.end()) {
            fallBack(other->second);
            continue;
        }
        const size_t expected = static_cast<size_t>(image.width) * image.height * 4;
        if (image.image.empty() || image.width <= 0 || image.height <= 0 ||
            image.image.size() != expected) { // a file that is missing or cannot be read
            fallBack("cannot read the image (a missing file?)");
            continue;
        }
        sceneImage[i] = static_cast<uint32_t>(scene.images.size());
        scene.images.push_back({.name = image.name.empty() ? fmt::format("image{}", i) : image.name,
                                .width = static_cast<uint32_t>(image.width),
                                .height = static_cast<uint32_t>(image.height),
                                .rgba = std::move(image.image)});
    }
    for (size_t t = 0; t < model.textures.size(); ++t) {
        const tinygltf::Texture& texture = model.textures[t];
        const auto image = sceneImage.find(texture.source);
        if (image == sceneImage.end()) {
            if (texture.source < 0 && warnings)
                warnings->push_back(fmt::format(
                    "{}: textures[{}] has no PNG or JPEG source{}; "
                    "its materials use their colour factor",
                    file.string(), t,
                    usesOtherSource(texture) ? " (KTX2 and WebP are not decoded here)" : ""));
            continue;
        }
        Texture out{.image = image->second};
        if (texture.sampler >= 0) {
            const tinygltf::Sampler& s = model.samplers[static_cast<size_t>(texture.sampler)];
            out.wrapS = wrapOf(s.wrapS);
            out.wrapT = wrapOf(s.wrapT);
            out.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        }
        textureOf[t] = static_cast<int32_t>(scene.textures.size());
        scene.textures.push_back(out);
    }
    return textureOf;
}

} // namespace penumbra::gltf
