#include "report/heatmap.h"

#include "core/image_io.h"
#include "penumbra/error.h"

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <stb/stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace penumbra {
namespace {

using Rgb = std::array<uint8_t, 3>;

constexpr Rgb kUncountedGrey = {0x80, 0x80, 0x80};
constexpr Rgb kCheckerDark = {0x2c, 0x2c, 0x2c}, kCheckerLight = {0x44, 0x44, 0x44};
constexpr Rgb kSky = {0x8c, 0xa6, 0xcc};
constexpr Rgb kLegendBackground = {0xff, 0xff, 0xff}, kInk = {0x1a, 0x1a, 0x1a};

// CIE D65 reference white, in the units of the sRGB <-> XYZ matrices below.
constexpr glm::dvec3 kWhite = {0.95047, 1.0, 1.08883};

double toLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double toGamma(double c) {
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double labF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

double labFInverse(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d ? t * t * t : 3 * d * d * (t - 4.0 / 29.0);
}

// sRGB bytes -> Moreland's Msh (polar CIELAB: magnitude, saturation angle, hue angle).
glm::dvec3 rgbToMsh(Rgb rgb) {
    glm::dvec3 c;
    for (int i = 0; i < 3; ++i)
        c[i] = toLinear(rgb[size_t(i)] / 255.0);
    glm::dvec3 xyz = {0.4124564 * c.x + 0.3575761 * c.y + 0.1804375 * c.z,
                      0.2126729 * c.x + 0.7151522 * c.y + 0.0721750 * c.z,
                      0.0193339 * c.x + 0.1191920 * c.y + 0.9503041 * c.z};
    glm::dvec3 f = {labF(xyz.x / kWhite.x), labF(xyz.y / kWhite.y), labF(xyz.z / kWhite.z)};
    glm::dvec3 lab = {116 * f.y - 16, 500 * (f.x - f.y), 200 * (f.y - f.z)};
    double m = glm::length(lab);
    return {m, std::acos(lab.x / m), std::atan2(lab.z, lab.y)};
}

Rgb mshToRgb(glm::dvec3 msh) {
    glm::dvec3 lab = {msh.x * std::cos(msh.y), msh.x * std::sin(msh.y) * std::cos(msh.z),
                      msh.x * std::sin(msh.y) * std::sin(msh.z)};
    double fy = (lab.x + 16) / 116;
    glm::dvec3 xyz = {kWhite.x * labFInverse(fy + lab.y / 500), kWhite.y * labFInverse(fy),
                      kWhite.z * labFInverse(fy - lab.z / 200)};
    glm::dvec3 c = {3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                    -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                    0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z};
    Rgb out;
    for (int i = 0; i < 3; ++i)
        out[size_t(i)] =
            static_cast<uint8_t>(std::lround(std::clamp(toGamma(c[i]), 0.0, 1.0) * 255.0));
    return out;
}

// Moreland's hue spin: an unsaturated end takes a hue that keeps the ramp visually smooth.
double adjustHue(glm::dvec3 saturated, double unsaturatedM) {
    if (saturated.x >= unsaturatedM)
        return saturated.z;
    double spin = saturated.y * std::sqrt(unsaturatedM * unsaturatedM - saturated.x * saturated.x) /
                  (saturated.x * std::sin(saturated.y));
    return saturated.z > -std::numbers::pi / 3 ? saturated.z + spin : saturated.z - spin;
}

// Moreland (2009), "Diverging Color Maps for Scientific Visualization": interpolates in Msh
// through a neutral midpoint, so both halves have matching lightness ramps.
Rgb divergingColour(Rgb low, Rgb high, double t) {
    glm::dvec3 a = rgbToMsh(low), b = rgbToMsh(high);
    double hueGap = std::abs(a.z - b.z);
    hueGap = std::min(hueGap, 2 * std::numbers::pi - hueGap);
    if (a.y > 0.05 && b.y > 0.05 && hueGap > std::numbers::pi / 3) {
        glm::dvec3 mid = {std::max({a.x, b.x, 88.0}), 0.0, 0.0};
        if (t < 0.5) {
            b = mid;
            t *= 2;
        } else {
            a = mid;
            t = 2 * t - 1;
        }
    }
    if (a.y < 0.05 && b.y > 0.05)
        a.z = adjustHue(b, a.x);
    else if (b.y < 0.05 && a.y > 0.05)
        b.z = adjustHue(a, b.x);
    return mshToRgb(glm::mix(a, b, t));
}

// An odd number of entries puts an exact zero error on the neutral centre entry.
constexpr int kLutSize = 257;

// The cool-warm map sampled at t in [0, 1] (0 = cool end).
Rgb coolWarm(double t) {
    static const std::array<Rgb, kLutSize> lut = [] {
        std::array<Rgb, kLutSize> table;
        for (int i = 0; i < kLutSize; ++i)
            table[size_t(i)] = divergingColour({59, 76, 192}, {180, 4, 38}, i / (kLutSize - 1.0));
        return table;
    }();
    return lut[size_t(std::lround(std::clamp(t, 0.0, 1.0) * (kLutSize - 1)))];
}

// Writes opaque colours into an RgbaImage with clipping; text comes from stb_easy_font's quads.
class Canvas {
public:
    explicit Canvas(RgbaImage& image) : mImage(image) {}

    void set(int64_t x, int64_t y, Rgb c) {
        if (x < 0 || y < 0 || x >= int64_t{mImage.width} || y >= int64_t{mImage.height})
            return;
        uint8_t* p = mImage.pixels.data() + (size_t(y) * mImage.width + size_t(x)) * 4;
        p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }

    void fill(int64_t x0, int64_t y0, int64_t x1, int64_t y1, Rgb c) {
        for (int64_t y = y0; y < y1; ++y)
            for (int64_t x = x0; x < x1; ++x)
                set(x, y, c);
    }

    // Text whose glyph cell starts at (x, y), each font unit drawn as scale x scale pixels.
    void text(int64_t x, int64_t y, const std::string& s, int scale, Rgb c) {
        std::string copy = s; // stb_easy_font takes a mutable char*.
        std::vector<char> quads(copy.size() * 2048 + 64);
        int count = stb_easy_font_print(0, 0, copy.data(), nullptr, quads.data(),
                                        static_cast<int>(quads.size()));
        for (int q = 0; q < count; ++q) {
            // Each quad is four vertices of {float x, y, z; uint8 rgba[4]}, axis aligned.
            const float* v0 = reinterpret_cast<const float*>(quads.data() + size_t(q) * 64);
            const float* v2 = reinterpret_cast<const float*>(quads.data() + size_t(q) * 64 + 32);
            fill(x + std::lround(v0[0] * float(scale)), y + std::lround(v0[1] * float(scale)),
                 x + std::lround(v2[0] * float(scale)), y + std::lround(v2[1] * float(scale)), c);
        }
    }

private:
    RgbaImage& mImage;
};

int64_t textWidth(const std::string& s, int scale) {
    std::string copy = s;
    // The last glyph's advance includes one unit of spacing that is not ink.
    return int64_t{std::max(0, stb_easy_font_width(copy.data()) - 1)} * scale;
}

// Legend layout in font units (scale 1); glyph caps are 7 units tall.
constexpr int kPad = 4, kBar = 10, kGlyph = 7,
              kLegendUnits = kPad + kBar + kPad + kGlyph + kPad + 1;

int legendScale(uint32_t width) {
    return int(std::clamp<uint32_t>(width / 320, 1, 6));
}

// Draws the legend strip below row `top`: [too dark][gradient bar][too bright], tick labels under
// the bar's ends and centre. The side words are dropped when the image is too narrow for them.
void drawLegend(RgbaImage& image, uint32_t top, float range) {
    Canvas canvas(image);
    const int s = legendScale(image.width);
    const int64_t width = image.width, y0 = top;
    canvas.fill(0, y0, width, image.height, kLegendBackground);
    const int64_t margin = 6 * s, gap = 6 * s;
    const std::string dark = "too dark", bright = "too bright";
    const int64_t wd = textWidth(dark, s), wb = textWidth(bright, s);
    int64_t barX0 = std::min<int64_t>(margin, width / 8), barX1 = width - barX0;
    const int64_t barY0 = y0 + kPad * s, barY1 = barY0 + kBar * s;
    const int64_t wordY = barY0 + (kBar - kGlyph) * s / 2;
    if (margin + wd + gap + 40 * s + gap + wb + margin <= width) {
        barX0 = margin + wd + gap;
        barX1 = width - margin - wb - gap;
        canvas.text(margin, wordY, dark, s, kInk);
        canvas.text(barX1 + gap, wordY, bright, s, kInk);
    }
    if (barX1 <= barX0)
        return;
    for (int64_t x = barX0; x < barX1; ++x) {
        double t = (double(x - barX0) + 0.5) / double(barX1 - barX0);
        canvas.fill(x, barY0, x + 1, barY1, coolWarm(t));
    }
    const int64_t mid = (barX0 + barX1) / 2, tickY = barY1 + kPad * s;
    const std::string low = fmt::format("-{:g}", range), high = fmt::format("+{:g}", range);
    canvas.fill(barX0, barY1, barX0 + s, barY1 + 2 * s, kInk);
    canvas.fill(mid - s / 2, barY1, mid - s / 2 + s, barY1 + 2 * s, kInk);
    canvas.fill(barX1 - s, barY1, barX1, barY1 + 2 * s, kInk);
    canvas.text(barX0, tickY, low, s, kInk);
    canvas.text(mid - textWidth("0", s) / 2, tickY, "0", s, kInk);
    canvas.text(barX1 - textWidth(high, s), tickY, high, s, kInk);
}

uint64_t pixelCount(uint32_t width, uint32_t height) {
    return uint64_t{width} * height;
}

void put(RgbaImage& image, size_t i, Rgb c) {
    uint8_t* p = image.pixels.data() + i * 4;
    p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
}

} // namespace

std::vector<float> signedError(std::span<const float> visibility, std::span<const float> truth) {
    PENUMBRA_CHECK(visibility.size() == truth.size(), "visibility size != truth size");
    std::vector<float> error(visibility.size());
    for (size_t i = 0; i < error.size(); ++i)
        error[i] = std::isfinite(visibility[i]) && std::isfinite(truth[i])
                       ? visibility[i] - truth[i]
                       : std::numeric_limits<float>::quiet_NaN();
    return error;
}

RgbaImage signedErrorHeatmap(uint32_t width, uint32_t height, std::span<const float> visibility,
                             std::span<const float> truth, std::span<const uint8_t> mask,
                             float range) {
    PENUMBRA_CHECK(std::isfinite(range) && range > 0, "heat map range must be positive");
    const uint64_t count = pixelCount(width, height);
    PENUMBRA_CHECK(visibility.size() == count, "visibility size != width * height");
    PENUMBRA_CHECK(truth.size() == count, "truth size != width * height");
    PENUMBRA_CHECK(mask.size() == count, "mask size != width * height");
    const uint32_t legend = uint32_t(kLegendUnits * legendScale(width));
    RgbaImage image{width, height + legend, {}};
    image.pixels.resize(pixelCount(width, image.height) * 4);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t{y} * width + x;
            const float v = visibility[i], t = truth[i];
            if (!std::isfinite(t) || !std::isfinite(v)) {
                put(image, i, ((x / 8 + y / 8) % 2) ? kCheckerLight : kCheckerDark);
                continue;
            }
            const double error = std::clamp(double{v} - double{t}, -double{range}, double{range});
            Rgb c = coolWarm(0.5 + 0.5 * error / range);
            if (mask[i] == 0)
                for (size_t k = 0; k < 3; ++k)
                    c[k] = uint8_t((c[k] + kUncountedGrey[k] + 1) / 2);
            put(image, i, c);
        }
    }
    drawLegend(image, height, range);
    return image;
}

RgbaImage visibilityImage(uint32_t width, uint32_t height, std::span<const float> visibility) {
    PENUMBRA_CHECK(visibility.size() == pixelCount(width, height),
                   "visibility size != width * height");
    RgbaImage image{width, height, std::vector<uint8_t>(visibility.size() * 4)};
    for (size_t i = 0; i < visibility.size(); ++i) {
        const float v = visibility[i];
        if (std::isnan(v)) {
            put(image, i, kSky);
            continue;
        }
        const auto grey = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
        put(image, i, {grey, grey, grey});
    }
    return image;
}

std::vector<uint8_t> encodePng(const RgbaImage& image) {
    return encodePng(image.width, image.height, 4, image.pixels);
}

} // namespace penumbra
