// OpenEXR outputs: bit-exact round trips through Penumbra's own reader, and the channel names,
// row order and values as OpenEXR's own RGBA reader (an independent path) sees them.
#include "core/exr_io.h"

#include "penumbra/error.h"

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>

namespace penumbra {
namespace {

uint32_t bitsOf(float value) {
    uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

std::filesystem::path writeTemp(const std::vector<uint8_t>& bytes, const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("penumbra-exr-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
}

TEST(ImageIoExr, RoundTripsEveryBitPatternInOneAndThreeChannels) {
    float payloadNan = 0.0f;
    const uint32_t payloadBits = 0x7fc01234u;
    std::memcpy(&payloadNan, &payloadBits, sizeof payloadNan);
    for (uint32_t channels : {1u, 3u}) {
        const uint32_t width = 7, height = 5; // odd sizes: no row or channel padding hides
        std::vector<float> pixels(width * height * channels);
        for (size_t i = 0; i < pixels.size(); ++i)
            pixels[i] = -1.5f * float(i) + 2.25f;
        pixels[0] = std::numeric_limits<float>::quiet_NaN();
        pixels[1] = -0.0f;
        pixels[2] = -std::numeric_limits<float>::infinity();
        pixels[3] = std::numeric_limits<float>::denorm_min();
        pixels[4] = 1.0f + std::numeric_limits<float>::epsilon(); // no half rounding
        pixels.back() = payloadNan;
        const FloatImage image = decodeExr(encodeExr(width, height, channels, pixels), "rt.exr");
        EXPECT_EQ(image.width, width);
        EXPECT_EQ(image.height, height);
        EXPECT_EQ(image.channels, channels);
        ASSERT_EQ(image.pixels.size(), pixels.size());
        for (size_t i = 0; i < pixels.size(); ++i)
            EXPECT_EQ(bitsOf(image.pixels[i]), bitsOf(pixels[i])) << channels << " ch, " << i;
    }
}

TEST(ImageIoExr, ChannelsAndRowsAreWhatOpenExrsRgbaReaderSees) {
    // Small integers, exact in half precision: pixel (x, y) has R = x, G = y, B = 10 + x + y,
    // rows top to bottom, so a swapped channel, a flipped row order or a wrong stride shows.
    const uint32_t width = 5, height = 3;
    std::vector<float> rgb, grey;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            rgb.insert(rgb.end(), {float(x), float(y), float(10 + x + y)});
            grey.push_back(float(4 * y + x));
        }
    Imf::RgbaInputFile colour(writeTemp(encodeExr(width, height, 3, rgb), "rgb.exr").c_str());
    EXPECT_EQ(colour.channels(), Imf::WRITE_RGB);
    Imf::Array2D<Imf::Rgba> read(height, width);
    const Imath::Box2i window = colour.dataWindow();
    ASSERT_EQ(window.min.x, 0);
    ASSERT_EQ(window.min.y, 0);
    colour.setFrameBuffer(&read[0][0], 1, width);
    colour.readPixels(window.min.y, window.max.y);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            EXPECT_EQ(float(read[y][x].r), float(x)) << x << "," << y;
            EXPECT_EQ(float(read[y][x].g), float(y)) << x << "," << y;
            EXPECT_EQ(float(read[y][x].b), float(10 + x + y)) << x << "," << y;
        }
    // One channel is luminance, "Y": image tools show it grey.
    Imf::RgbaInputFile luminance(writeTemp(encodeExr(width, height, 1, grey), "y.exr").c_str());
    EXPECT_EQ(luminance.channels(), Imf::WRITE_Y);
    luminance.setFrameBuffer(&read[0][0], 1, width);
    luminance.readPixels(0, int(height) - 1);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            EXPECT_EQ(float(read[y][x].r), float(4 * y + x)) << x << "," << y;
    std::filesystem::remove_all(writeTemp({}, "x").parent_path());
}

TEST(ImageIoExr, MalformedFilesAreInputErrorsNamingTheFile) {
    const std::vector<uint8_t> good = encodeExr(3, 2, 1, std::vector<float>(6, 0.5f));
    // Every truncation of a valid file, and a few corruptions of its header.
    for (size_t size = 0; size < good.size(); ++size) {
        const std::vector<uint8_t> cut(good.begin(), good.begin() + ptrdiff_t(size));
        try {
            decodeExr(cut, "cut.exr");
            ADD_FAILURE() << "a file cut to " << size << " bytes decoded";
        } catch (const InputError& e) {
            EXPECT_EQ(e.subject(), "cut.exr");
        }
    }
    std::vector<uint8_t> otherChannel = good;
    const std::string chlist = "chlist";
    const auto at =
        std::search(otherChannel.begin(), otherChannel.end(), chlist.begin(), chlist.end());
    ASSERT_NE(at, otherChannel.end());
    // "chlist\0", the attribute's 4-byte size, then the first channel's name: "Y" becomes "Z".
    auto name = at + ptrdiff_t(chlist.size() + 1 + 4);
    ASSERT_EQ(*name, 'Y');
    *name = 'Z';
    EXPECT_THROW(decodeExr(otherChannel, "z.exr"), InputError);
    EXPECT_THROW(decodeExr(std::vector<uint8_t>{'v', '/', '1', 1, 0, 0, 0}, "x.exr"), InputError);
    try {
        readExr("/nonexistent/penumbra.exr");
        ADD_FAILURE() << "a missing file read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), "/nonexistent/penumbra.exr");
    }
}

} // namespace
} // namespace penumbra
