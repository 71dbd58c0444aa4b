#pragma once
// The outer layers of a glTF asset, checked before any parser sees them: file size, the GLB
// container (magic, version, lengths, chunks), and the JSON's shape where a parser would trust
// it blindly: asset.version, extensionsRequired, and every URI (relative, inside the asset's
// folder, no shell syntax, data URIs with strict base64 of the declared length).
#include <nlohmann/json.hpp>

#include <optional>
#include <string_view>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace penumbra::gltf {

struct Container {
    std::vector<uint8_t> bytes; // the whole file
    bool binary = false;        // GLB
    std::string json;           // the JSON text (the JSON chunk for GLB)
    uint64_t binChunkLength = 0;
};

// Reads and checks the container; throws InputError(file, ...).
Container readContainer(const std::filesystem::path& file, uint64_t maxFileSize);

// Checks asset.version, extensionsRequired and URIs; returns the parsed JSON.
// RFC 3986 percent-decoding; nullopt when a '%' is not followed by two hex digits.
std::optional<std::string> percentDecode(std::string_view text);

nlohmann::json checkJson(const std::filesystem::path& file, const std::string& json);

// Decodes a data URI's base64 payload strictly (alphabet, padding, length); false if malformed.
bool decodeBase64(std::string_view text, std::vector<uint8_t>& out);

} // namespace penumbra::gltf
