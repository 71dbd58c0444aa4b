#pragma once
// Images for the HTML report: a signed-error heat map with a legend, and visibility as grey.
#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

// An 8-bit RGBA image; pixels holds width * height * 4 bytes, rows top to bottom.
struct RgbaImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> pixels;
};

// Colours v - truth, clamped to [-range, range], with Moreland's cool-warm diverging map (blue:
// too dark, light neutral: exact, red: too bright). Uncounted pixels (mask == 0, finite truth) are
// blended halfway towards #808080; pixels without a comparison (non-finite truth or visibility)
// show a dark 8-pixel checker. A legend strip (>= 28 px, full width) is appended below, so the
// result is taller than height. range must be positive and finite; span sizes must match.
RgbaImage signedErrorHeatmap(uint32_t width, uint32_t height, std::span<const float> visibility,
                             std::span<const float> truth, std::span<const uint8_t> mask,
                             float range = 1.0f);

// The heat map's data: v - truth per pixel, NaN where either is not finite (no comparison).
std::vector<float> signedError(std::span<const float> visibility, std::span<const float> truth);

// Visibility as grey (0 black, 1 white, clamped); NaN (background) as light sky blue #8CA6CC.
RgbaImage visibilityImage(uint32_t width, uint32_t height, std::span<const float> visibility);

// Encodes the image as a PNG file image (penumbra::encodePng with four channels).
std::vector<uint8_t> encodePng(const RgbaImage& image);

} // namespace penumbra
