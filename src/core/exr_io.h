#pragma once
// OpenEXR for the float outputs: what tev, Blender, Nuke, OpenImageIO and Python's imaging
// libraries open. Scanline files of 32-bit float channels, ZIP-compressed (lossless: every bit
// pattern, NaN payloads included, reads back unchanged), rows top to bottom like PFM's decoder.
#include "core/image_io.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace penumbra {

// Encodes float pixels (rows top to bottom, 1 channel named "Y" or 3 named "R", "G", "B") as
// an OpenEXR file image.
std::vector<uint8_t> encodeExr(uint32_t width, uint32_t height, uint32_t channels,
                               std::span<const float> pixels);

// Decodes an OpenEXR file image written by encodeExr (a "Y" or "R", "G", "B" float channel
// set; half channels are widened); throws InputError(subject, ...) if it is malformed or holds
// other channels.
FloatImage decodeExr(std::span<const uint8_t> bytes, const std::string& subject);

// Reads and decodes an OpenEXR file; throws InputError(path, ...) if unreadable or malformed.
FloatImage readExr(const std::filesystem::path& path);

} // namespace penumbra
