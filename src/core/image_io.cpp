#include "core/image_io.h"

#include "penumbra/error.h"

#include <stb/stb_image_write.h>

#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>

namespace penumbra {
namespace {

// Returns the product of factors, or nullopt if it does not fit in 64 bits; sizes derived from
// untrusted headers must never wrap around into small, "valid-looking" buffer sizes.
std::optional<uint64_t> checkedProduct(std::initializer_list<uint64_t> factors) {
    uint64_t product = 1;
    for (uint64_t factor : factors) {
        if (factor != 0 && product > std::numeric_limits<uint64_t>::max() / factor)
            return std::nullopt;
        product *= factor;
    }
    return product;
}

// Returns width * height * channels, aborting on overflow (callers pass in-memory images).
uint64_t checkedPixelCount(uint32_t width, uint32_t height, uint32_t channels) {
    std::optional<uint64_t> count = checkedProduct({width, height, channels});
    PENUMBRA_CHECK(count.has_value(), "image dimensions overflow 64 bits");
    return *count;
}

// Formats the OS error in errno for InputError messages.
std::string errnoText(int err) {
    return std::strerror(err);
}

bool isPfmSpace(uint8_t c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// Walks the PFM text header; every failure is a malformed file, reported against subject.
class PfmHeaderReader {
public:
    PfmHeaderReader(std::span<const uint8_t> bytes, const std::string& subject)
        : mBytes(bytes), mSubject(subject) {}

    size_t position() const { return mPos; }

    [[noreturn]] void fail(const std::string& reason) const { throw InputError(mSubject, reason); }

    // Consumes exactly one whitespace byte: the separator before binary data must be one byte.
    void expectOneSpace(const char* what) {
        if (mPos >= mBytes.size())
            fail(std::string("truncated header: missing ") + what);
        if (!isPfmSpace(mBytes[mPos]))
            fail(std::string("malformed header before ") + what);
        ++mPos;
    }

    // Consumes one or more whitespace bytes between header fields.
    void skipSpaces(const char* what) {
        expectOneSpace(what);
        while (mPos < mBytes.size() && isPfmSpace(mBytes[mPos]))
            ++mPos;
    }

    // Returns the next run of non-whitespace bytes, failing if the header ends first.
    std::string_view token(const char* what) {
        size_t begin = mPos;
        while (mPos < mBytes.size() && !isPfmSpace(mBytes[mPos]))
            ++mPos;
        if (begin == mPos)
            fail(std::string("truncated header: missing ") + what);
        return {reinterpret_cast<const char*>(mBytes.data()) + begin, mPos - begin};
    }

    uint32_t dimension(const char* what) {
        std::string_view text = token(what);
        uint32_t value = 0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size())
            fail(std::string("invalid ") + what + " '" + std::string(text) + "'");
        if (value == 0)
            fail(std::string(what) + " must be positive");
        return value;
    }

    double scale() {
        std::string_view text = token("scale");
        double value = 0.0;
        auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
            fail("invalid scale '" + std::string(text) + "'");
        if (value == 0.0)
            fail("scale must be non-zero");
        return value;
    }

private:
    std::span<const uint8_t> mBytes;
    const std::string& mSubject;
    size_t mPos = 0;
};

// Appends stb's encoded chunks to the std::vector passed as context.
void appendToVector(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* begin = static_cast<const uint8_t*>(data);
    out->insert(out->end(), begin, begin + size);
}

} // namespace

std::vector<uint8_t> encodePng(uint32_t width, uint32_t height, uint32_t channels,
                               std::span<const uint8_t> pixels) {
    PENUMBRA_CHECK(channels >= 1 && channels <= 4, "png needs 1 to 4 channels");
    PENUMBRA_CHECK(width > 0 && height > 0, "png dimensions must be positive");
    PENUMBRA_CHECK(pixels.size() == checkedPixelCount(width, height, channels),
                   "png pixel buffer size does not match its dimensions");
    // stb takes int dimensions and row stride.
    PENUMBRA_CHECK(uint64_t{width} * channels <= INT_MAX && height <= INT_MAX,
                   "png too large for the encoder");
    std::vector<uint8_t> out;
    int stride = static_cast<int>(width * channels);
    int ok = stbi_write_png_to_func(appendToVector, &out, static_cast<int>(width),
                                    static_cast<int>(height), static_cast<int>(channels),
                                    pixels.data(), stride);
    PENUMBRA_CHECK(ok != 0, "png encoding failed");
    return out;
}

std::vector<uint8_t> encodePfm(uint32_t width, uint32_t height, uint32_t channels,
                               std::span<const float> pixels) {
    PENUMBRA_CHECK(channels == 1 || channels == 3, "pfm needs 1 or 3 channels");
    PENUMBRA_CHECK(width > 0 && height > 0, "pfm dimensions must be positive");
    PENUMBRA_CHECK(pixels.size() == checkedPixelCount(width, height, channels),
                   "pfm pixel buffer size does not match its dimensions");
    // A negative scale declares little-endian data.
    std::string header = std::string(channels == 3 ? "PF\n" : "Pf\n") + std::to_string(width) +
                         " " + std::to_string(height) + "\n-1.0\n";
    std::vector<uint8_t> out(header.begin(), header.end());
    out.reserve(out.size() + pixels.size() * 4);
    size_t rowFloats = size_t{width} * channels;
    // PFM stores the bottom row first.
    for (size_t row = height; row-- > 0;) {
        for (float value : pixels.subspan(row * rowFloats, rowFloats)) {
            uint32_t bits = 0;
            std::memcpy(&bits, &value, sizeof bits);
            for (int shift = 0; shift < 32; shift += 8)
                out.push_back(static_cast<uint8_t>(bits >> shift));
        }
    }
    return out;
}

FloatImage decodePfm(std::span<const uint8_t> bytes, const std::string& subject) {
    if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f'))
        throw InputError(subject, "not a pfm file (bad magic)");
    FloatImage image;
    image.channels = bytes[1] == 'F' ? 3 : 1;

    PfmHeaderReader reader(bytes.subspan(2), subject);
    reader.skipSpaces("width");
    image.width = reader.dimension("width");
    reader.skipSpaces("height");
    image.height = reader.dimension("height");
    reader.skipSpaces("scale");
    bool bigEndian = reader.scale() > 0.0;
    reader.expectOneSpace("pixel data");
    size_t dataStart = 2 + reader.position();

    std::optional<uint64_t> count = checkedProduct({image.width, image.height, image.channels});
    std::optional<uint64_t> byteCount = checkedProduct({count.value_or(0), 4});
    if (!count || !byteCount)
        throw InputError(subject, "image dimensions too large");
    uint64_t available = bytes.size() - dataStart;
    if (available < *byteCount)
        throw InputError(subject, "truncated pixel data (expected " + std::to_string(*byteCount) +
                                      " bytes, found " + std::to_string(available) + ")");

    image.pixels.resize(*count);
    size_t rowFloats = size_t{image.width} * image.channels;
    const uint8_t* src = bytes.data() + dataStart;
    // File rows run bottom to top; FloatImage rows run top to bottom.
    for (size_t fileRow = 0; fileRow < image.height; ++fileRow) {
        float* dst = image.pixels.data() + (image.height - 1 - fileRow) * rowFloats;
        for (size_t i = 0; i < rowFloats; ++i, src += 4) {
            uint32_t bits = 0;
            for (int b = 0; b < 4; ++b) {
                int shift = bigEndian ? 8 * (3 - b) : 8 * b;
                bits |= uint32_t{src[b]} << shift;
            }
            std::memcpy(&dst[i], &bits, sizeof bits);
        }
    }
    return image;
}

FloatImage readPfm(const std::filesystem::path& path) {
    return decodePfm(readFileBytes(path), path.string());
}

std::vector<uint8_t> readFileBytes(const std::filesystem::path& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                         &std::fclose);
    if (!file)
        throw InputError(path.string(), "cannot open: " + errnoText(errno));
    std::vector<uint8_t> bytes;
    uint8_t chunk[64 * 1024];
    // Reading in chunks rather than trusting the size from stat also handles pipes and /proc.
    for (;;) {
        size_t got = std::fread(chunk, 1, sizeof chunk, file.get());
        int err = errno; // before insert() can allocate and clobber it
        if (got < sizeof chunk && std::ferror(file.get()))
            throw InputError(path.string(), "cannot read: " + errnoText(err));
        bytes.insert(bytes.end(), chunk, chunk + got);
        if (got < sizeof chunk)
            return bytes;
    }
}

} // namespace penumbra
