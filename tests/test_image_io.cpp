#include "core/image_io.h"

#include "penumbra/error.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>

namespace penumbra {
namespace {

std::vector<uint8_t> toBytes(const std::string& text, size_t zeroBytes = 0) {
    std::vector<uint8_t> bytes(text.begin(), text.end());
    bytes.resize(bytes.size() + zeroBytes);
    return bytes;
}

uint32_t bitsOf(float value) {
    uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// Compares bit patterns, so NaN payloads and -0.0 must survive exactly.
void expectSameBits(const std::vector<float>& expected, const std::vector<float>& actual) {
    ASSERT_EQ(expected.size(), actual.size());
    for (size_t i = 0; i < expected.size(); ++i)
        EXPECT_EQ(bitsOf(expected[i]), bitsOf(actual[i])) << "at index " << i;
}

void expectRejected(const std::vector<uint8_t>& bytes, const std::string& why) {
    EXPECT_THROW(decodePfm(bytes, "bad.pfm"), InputError) << why;
}

TEST(ImageIo, PngRoundTripsExactPixelsForEveryChannelCount) {
    const uint32_t width = 5, height = 3;
    for (uint32_t channels = 1; channels <= 4; ++channels) {
        std::vector<uint8_t> pixels(width * height * channels);
        for (size_t i = 0; i < pixels.size(); ++i)
            pixels[i] = static_cast<uint8_t>(i * 37 + 11);
        std::vector<uint8_t> png = encodePng(width, height, channels, pixels);
        int w = 0, h = 0, c = 0;
        uint8_t* decoded =
            stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &c, 0);
        ASSERT_NE(decoded, nullptr) << "channels " << channels;
        EXPECT_EQ(w, static_cast<int>(width));
        EXPECT_EQ(h, static_cast<int>(height));
        EXPECT_EQ(c, static_cast<int>(channels));
        std::vector<uint8_t> actual(decoded, decoded + pixels.size());
        stbi_image_free(decoded);
        EXPECT_EQ(actual, pixels) << "channels " << channels;
    }
}

TEST(ImageIoDeathTest, PngSizeMismatchIsAProgrammerError) {
    std::vector<uint8_t> pixels(5);
    EXPECT_DEATH(encodePng(2, 2, 1, pixels), "check failed");
}

TEST(ImageIo, PfmRoundTripsOneAndThreeChannelsIncludingNanAndNegatives) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    float payloadNan = 0.0f;
    uint32_t payloadBits = 0x7fc01234u;
    std::memcpy(&payloadNan, &payloadBits, sizeof payloadNan);
    for (uint32_t channels : {1u, 3u}) {
        const uint32_t width = 3, height = 2;
        std::vector<float> pixels(width * height * channels);
        for (size_t i = 0; i < pixels.size(); ++i)
            pixels[i] = -1.5f * static_cast<float>(i) + 2;
        pixels[0] = nan;
        pixels[1] = -0.0f;
        pixels[2] = -inf;
        pixels[pixels.size() - 1] = payloadNan;
        std::vector<uint8_t> file = encodePfm(width, height, channels, pixels);
        FloatImage image = decodePfm(file, "round.pfm");
        EXPECT_EQ(image.width, width);
        EXPECT_EQ(image.height, height);
        EXPECT_EQ(image.channels, channels);
        expectSameBits(pixels, image.pixels);
        EXPECT_TRUE(std::isnan(image.pixels[0]));
    }
}

TEST(ImageIo, PfmWritesExactHeaderAndBottomRowFirst) {
    // 2x3, one channel, rows top to bottom: (0 1) (2 3) (4 5).
    std::vector<float> pixels = {0, 1, 2, 3, 4, 5};
    std::vector<uint8_t> file = encodePfm(2, 3, 1, pixels);
    std::string header = "Pf\n2 3\n-1.0\n";
    ASSERT_EQ(file.size(), header.size() + 6 * 4);
    EXPECT_EQ(std::string(file.begin(), file.begin() + static_cast<ptrdiff_t>(header.size())),
              header);
    // IEEE 754 bits written little-endian, bottom row (4 5) first.
    std::vector<uint8_t> expected = {
        0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0xa0, 0x40, // 4, 5
        0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x40, 0x40, // 2, 3
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, // 0, 1
    };
    EXPECT_EQ(
        std::vector<uint8_t>(file.begin() + static_cast<ptrdiff_t>(header.size()), file.end()),
        expected);
    std::vector<uint8_t> rgb = encodePfm(1, 1, 3, std::vector<float>{0, 0, 0});
    EXPECT_EQ(std::string(rgb.begin(), rgb.begin() + 12), "PF\n1 1\n-1.0\n");
}

TEST(ImageIo, PfmDecodesBigEndianAndFlipsRows) {
    // 2x2 big-endian (positive scale); file rows bottom first: (-2.5 1) then (0.5 3).
    std::vector<uint8_t> file = toBytes("Pf\n2 2\n1.0\n");
    std::vector<uint8_t> data = {0xc0, 0x20, 0x00, 0x00, 0x3f, 0x80, 0x00, 0x00,
                                 0x3f, 0x00, 0x00, 0x00, 0x40, 0x40, 0x00, 0x00};
    file.insert(file.end(), data.begin(), data.end());
    FloatImage image = decodePfm(file, "be.pfm");
    EXPECT_EQ(image.width, 2u);
    EXPECT_EQ(image.height, 2u);
    EXPECT_EQ(image.channels, 1u);
    EXPECT_EQ(image.pixels, (std::vector<float>{0.5f, 3.0f, -2.5f, 1.0f}));
}

TEST(ImageIo, PfmAcceptsAnyWhitespaceBetweenHeaderFields) {
    std::vector<uint8_t> file = toBytes("Pf \t2\r\n\n1   -4.25\t");
    std::vector<uint8_t> data = {0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0xc0};
    file.insert(file.end(), data.begin(), data.end());
    FloatImage image = decodePfm(file, "ws.pfm");
    EXPECT_EQ(image.width, 2u);
    EXPECT_EQ(image.height, 1u);
    EXPECT_EQ(image.pixels, (std::vector<float>{1.0f, -2.0f}));
}

TEST(ImageIo, PfmRejectsMalformedFiles) {
    std::vector<uint8_t> good = encodePfm(2, 3, 1, std::vector<float>(6, 1.0f));
    ASSERT_NO_THROW(decodePfm(good, "good.pfm"));

    std::vector<uint8_t> badMagic = good;
    badMagic[1] = 'G';
    expectRejected(badMagic, "bad magic");
    expectRejected(toBytes("P"), "too short for magic");
    expectRejected(toBytes("Pf\n0 3\n-1.0\n"), "zero width");
    expectRejected(toBytes("Pf\n2 0\n-1.0\n"), "zero height");
    expectRejected(toBytes("Pf\n-2 3\n-1.0\n"), "negative width");
    expectRejected(toBytes("Pf\n4294967296 1\n-1.0\n"), "width beyond 32 bits");
    expectRejected(toBytes("Pf\n4294967295 4294967295\n-1.0\n"), "byte count overflows 64 bits");
    expectRejected(toBytes("PF\n4294967295 4294967295\n-1.0\n"), "float count overflows");
    // 2^31 * 2^31 * 4 bytes wraps to exactly 0: unchecked arithmetic would accept no data.
    expectRejected(toBytes("Pf\n2147483648 2147483648\n-1.0\n"), "byte count wraps to 0");
    expectRejected(toBytes("PF\n2147483648 2147483648\n-1.0\n"), "rgb byte count wraps to 0");
    expectRejected(toBytes("Pf\n2 3\n0.0\n", 24), "zero scale");
    expectRejected(toBytes("Pf\n2 3\nnan\n", 24), "nan scale");
    expectRejected(toBytes("Pf\n2 3\n"), "missing scale");
    expectRejected(toBytes("Pf\n2 3\n-1.0"), "no separator after scale");
    expectRejected(toBytes("Pf2 3\n-1.0\n"), "no space after magic");
    expectRejected(std::vector<uint8_t>(good.begin(), good.end() - 1), "truncated data");
}

TEST(ImageIo, ReadPfmReadsFileAndReportsPathOnErrors) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                ("penumbra-image-io-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::vector<float> pixels = {1, 2, 3, -4, 5, 6};
    std::vector<uint8_t> bytes = encodePfm(1, 2, 3, pixels);
    {
        std::ofstream out(dir / "image.pfm", std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    }
    EXPECT_EQ(readFileBytes(dir / "image.pfm"), bytes);
    FloatImage image = readPfm(dir / "image.pfm");
    EXPECT_EQ(image.pixels, pixels);
    try {
        readPfm(dir / "missing.pfm");
        ADD_FAILURE() << "missing file was read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), (dir / "missing.pfm").string());
    }
    EXPECT_THROW(readFileBytes(dir), InputError); // a directory is not readable as a file
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace penumbra
