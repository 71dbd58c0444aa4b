#include "report/page_image.h"

#include "penumbra/error.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {
namespace {

// IEC 61966-2-1 transfer functions.
double srgbToLinear(double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}
double linearToSrgb(double v) {
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

const std::array<double, 256>& linearOfByte() {
    static const std::array<double, 256> table = [] {
        std::array<double, 256> t{};
        for (size_t i = 0; i < t.size(); ++i)
            t[i] = srgbToLinear(double(i) / 255.0);
        return t;
    }();
    return table;
}

uint8_t toByte(double unit) {
    return uint8_t(std::lround(std::clamp(unit, 0.0, 1.0) * 255.0));
}

} // namespace

uint32_t pageScale(uint32_t width, uint32_t maxWidth) {
    PENUMBRA_CHECK(maxWidth > 0, "page width must be positive");
    return width <= maxWidth ? 1 : (width + maxWidth - 1) / maxWidth;
}

RgbaImage reduceImage(const RgbaImage& image, uint32_t scale) {
    PENUMBRA_CHECK(scale > 0, "reduction scale must be positive");
    PENUMBRA_CHECK(image.pixels.size() == size_t{image.width} * image.height * 4,
                   "rgba size != width * height * 4");
    if (scale == 1)
        return image;
    const std::array<double, 256>& linear = linearOfByte();
    RgbaImage out{(image.width + scale - 1) / scale, (image.height + scale - 1) / scale, {}};
    out.pixels.resize(size_t{out.width} * out.height * 4);
    for (uint32_t oy = 0; oy < out.height; ++oy)
        for (uint32_t ox = 0; ox < out.width; ++ox) {
            std::array<double, 4> sum{};
            uint32_t count = 0;
            for (uint32_t y = oy * scale; y < std::min(image.height, (oy + 1) * scale); ++y)
                for (uint32_t x = ox * scale; x < std::min(image.width, (ox + 1) * scale); ++x) {
                    const uint8_t* p = &image.pixels[(size_t{y} * image.width + x) * 4];
                    for (size_t c = 0; c < 3; ++c)
                        sum[c] += linear[p[c]];
                    sum[3] += p[3] / 255.0;
                    ++count;
                }
            uint8_t* q = &out.pixels[(size_t{oy} * out.width + ox) * 4];
            for (size_t c = 0; c < 3; ++c)
                q[c] = toByte(linearToSrgb(sum[c] / count));
            q[3] = toByte(sum[3] / count);
        }
    return out;
}

} // namespace penumbra
