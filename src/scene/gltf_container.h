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
    uint64_t binChunkOffset = 0; // of the BIN chunk's data; 0: no BIN chunk
    uint64_t trailingBytes = 0;  // GLB: bytes after the header's length (ignored, a warning)
};

// Reads and checks the container; throws InputError(file, ...).
Container readContainer(const std::filesystem::path& file, uint64_t maxFileSize);

// Checks asset.version, extensionsRequired and URIs; returns the parsed JSON.
// RFC 3986 percent-decoding; nullopt when a '%' is not followed by two hex digits.
std::optional<std::string> percentDecode(std::string_view text);

// Also makes the JSON say what the spec means before a parser reads it: an integer written as a
// float (`"mesh": 1.0`, valid JSON Schema) becomes an integer, and a GLB buffer declared longer
// than its BIN chunk is read as the chunk (a warning). A byte-order mark is refused.
nlohmann::json checkJson(const std::filesystem::path& file, const Container& container,
                         std::vector<std::string>* warnings);

// Buffers without data (no uri outside a GLB's first) that no drawn primitive or image reads:
// left out with a warning each, a one-byte stand-in for the parser, their views emptied and
// the accessors on those views detached (zeros). Runs after checkReferences.
void leaveOutUnreadBuffers(const std::filesystem::path& file, bool binary, nlohmann::json& json,
                           std::vector<std::string>* warnings);

// The schema's required properties and their JSON types (accessors, views, buffers, cameras,
// animations, skins, nodes, samplers, materials, lights), by JSON path (gltf_schema.cpp).
void checkRequiredProperties(const std::filesystem::path& file, const nlohmann::json& json);

// The bytes the parser reads: `json` (checkJson's, serialised) and, for a GLB, the original BIN
// chunk in a new container.
std::vector<uint8_t> parserInput(const Container& container, const std::string& json);

// A data URI's media type ("" when it gives none) and bytes, base64 or percent-encoded
// (gltf_data_uri.cpp); nullopt with `error` set when malformed.
struct DataUri {
    std::string mediaType;
    std::vector<uint8_t> bytes;
};
std::optional<DataUri> parseDataUri(std::string_view uri, std::string* error);
// The same bytes as the parser reads them: base64 under a media type it knows.
std::string canonicalDataUri(const DataUri& uri, bool image);

// Decodes a data URI's base64 payload strictly (alphabet, padding, length); false if malformed.
bool decodeBase64(std::string_view text, std::vector<uint8_t>& out);

} // namespace penumbra::gltf
