#pragma once
// Image encoding for Penumbra's outputs: PNG for viewing, PFM for exact float data (shadow maps,
// reference comparisons). Decoding exists for PFM only, so tests and tools can read results back.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace penumbra {

// Encodes 8-bit pixels (rows top to bottom, 1..4 interleaved channels) as a PNG file image;
// a size mismatch between pixels and width * height * channels is a programmer error.
std::vector<uint8_t> encodePng(uint32_t width, uint32_t height, uint32_t channels,
                               std::span<const uint8_t> pixels);

// Encodes float pixels (rows top to bottom, 1 or 3 channels) as a little-endian PFM file image;
// every bit pattern, NaN payloads included, is stored unchanged.
std::vector<uint8_t> encodePfm(uint32_t width, uint32_t height, uint32_t channels,
                               std::span<const float> pixels);

// A decoded float image (PFM or OpenEXR): pixels holds width * height * channels floats, rows top
// to bottom.
struct FloatImage {
    uint32_t width = 0, height = 0, channels = 0;
    std::vector<float> pixels; // rows top to bottom
};

// Decodes a PFM file image of either byte order; throws InputError(subject, ...) if malformed.
FloatImage decodePfm(std::span<const uint8_t> bytes, const std::string& subject);

// Reads and decodes a PFM file; throws InputError(path, ...) if unreadable or malformed.
FloatImage readPfm(const std::filesystem::path& path);

// Reads a whole file into memory; throws InputError(path, ...) if it cannot be read.
std::vector<uint8_t> readFileBytes(const std::filesystem::path& path);

} // namespace penumbra
