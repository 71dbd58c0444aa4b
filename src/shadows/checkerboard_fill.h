#pragma once
// The CPU mirror of checkerboard tracing's fill (shaders/visibility_fill.comp, its rules in
// shaders/include/checkerboard.h): the parity test runs it on a render's own exported positions,
// normals and visibility.
#include "shadows/technique.h"

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::shadows {

// What became of a pixel.
enum class CheckerboardPixel : uint8_t {
    Background, // left NaN
    Traced,     // an even pixel (x + y even): the visibility pass's own
    Filled,     // the mean of its traced neighbours on its surface
    Listed,     // on the trace list: traced after the fill
};

struct CheckerboardFill {
    std::vector<float> visibility; // the even pixels as given, the filled ones' means, NaN else
    std::vector<CheckerboardPixel> pixels;
    // Pixels whose fate a rounding could change: a neighbour within 1e-4 (relative) of the
    // same-surface bounds. (The span against the range is exact: a maximum, a minimum and one
    // subtraction of the very values the shader reads.)
    std::vector<bool> close;
};

// One visibility layer's fill. position and normal: xyz per pixel, NaN for the background;
// visibility: the even pixels' (the others are not read).
CheckerboardFill fillCheckerboard(uint32_t width, uint32_t height, std::span<const float> position,
                                  std::span<const float> normal, std::span<const float> visibility,
                                  float range);

} // namespace penumbra::shadows
