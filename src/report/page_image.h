#pragma once
// The report's images at page size: a 1080p comparison of 30 rows would inline 90 full-size PNGs
// (tens of MB, slow to open), so images wider than kPageImageWidth are shown reduced by a whole
// factor and the full-size files beside report.html are linked.
#include "report/heatmap.h"

#include <cstdint>

namespace penumbra {

// Wide enough for the report's 1400-px page; a 1920-px render is halved.
inline constexpr uint32_t kPageImageWidth = 960;

// The whole factor an image of this width is reduced by: ceil(width / maxWidth), at least 1.
uint32_t pageScale(uint32_t width, uint32_t maxWidth = kPageImageWidth);

// The image reduced by `scale` (each output pixel the mean of a scale x scale block, the last
// row and column of blocks cut at the border): colour averaged in linear light (sRGB decoded and
// encoded again, so a fine black-white checker reads as middle grey, 188, not 128), alpha
// averaged as stored. scale 1 returns the image unchanged; scale 0 is a programmer error.
RgbaImage reduceImage(const RgbaImage& image, uint32_t scale);

} // namespace penumbra
