#include "core/exr_io.h"

#include "penumbra/error.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>

#include <array>
#include <cstring>
#include <exception>
#include <string_view>

namespace penumbra {
namespace {

constexpr std::array<const char*, 1> kGreyChannel{"Y"};
constexpr std::array<const char*, 3> kColourChannels{"R", "G", "B"};

std::span<const char* const> channelNames(uint32_t channels) {
    if (channels == 1)
        return kGreyChannel;
    return kColourChannels;
}

// A read-only OpenEXR stream over bytes already in memory (no copy into a string stream).
class ByteStream final : public Imf::IStream {
public:
    ByteStream(std::span<const uint8_t> bytes, const std::string& name)
        : Imf::IStream(name.c_str()), mBytes(bytes) {}

    bool read(char out[], int count) override {
        if (count < 0 || uint64_t(count) > mBytes.size() - mPosition)
            throw std::runtime_error("truncated file");
        std::memcpy(out, mBytes.data() + mPosition, size_t(count));
        mPosition += uint64_t(count);
        return mPosition < mBytes.size();
    }
    uint64_t tellg() override { return mPosition; }
    void seekg(uint64_t position) override {
        if (position > mBytes.size())
            throw std::runtime_error("seek past the end of the file");
        mPosition = position;
    }

private:
    std::span<const uint8_t> mBytes;
    uint64_t mPosition = 0;
};

// Larger images are not ones Penumbra writes (16384 x 16384, the largest render target).
constexpr uint64_t kMaxPixels = uint64_t{16384} * 16384;

} // namespace

std::vector<uint8_t> encodeExr(uint32_t width, uint32_t height, uint32_t channels,
                               std::span<const float> pixels) {
    PENUMBRA_CHECK(channels == 1 || channels == 3, "exr images have 1 or 3 channels");
    PENUMBRA_CHECK(width > 0 && height > 0 && uint64_t{width} * height <= kMaxPixels,
                   "exr image size out of range");
    PENUMBRA_CHECK(pixels.size() == uint64_t{width} * height * channels,
                   "exr pixel count does not match the size");
    Imf::Header header{static_cast<int>(width), static_cast<int>(height)};
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const size_t xStride = sizeof(float) * channels;
    // OpenEXR's Slice takes a mutable pointer for reading and writing alike; writing only reads.
    char* base = reinterpret_cast<char*>(const_cast<float*>(pixels.data()));
    const std::span<const char* const> names = channelNames(channels);
    for (size_t c = 0; c < names.size(); ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c],
                     Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, xStride * width));
    }
    Imf::StdOSStream stream;
    {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame);
        file.writePixels(int(height));
    } // the file's destructor writes the line offset table
    const std::string bytes = stream.str();
    return {bytes.begin(), bytes.end()};
}

FloatImage decodeExr(std::span<const uint8_t> bytes, const std::string& subject) {
    try {
        ByteStream stream(bytes, subject);
        Imf::InputFile file(stream);
        const Imath::Box2i window = file.header().dataWindow();
        const int64_t width = int64_t{window.max.x} - window.min.x + 1;
        const int64_t height = int64_t{window.max.y} - window.min.y + 1;
        if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxPixels)
            throw InputError(subject, "image size out of range");
        const Imf::ChannelList& list = file.header().channels();
        size_t listed = 0;
        for (auto it = list.begin(); it != list.end(); ++it)
            ++listed;
        FloatImage image{.width = uint32_t(width), .height = uint32_t(height)};
        if (listed == 1 && list.findChannel("Y"))
            image.channels = 1;
        else if (listed == 3 && list.findChannel("R") && list.findChannel("G") &&
                 list.findChannel("B"))
            image.channels = 3;
        else
            throw InputError(subject, "expected one channel Y or three channels R, G, B");
        image.pixels.resize(size_t(width) * size_t(height) * image.channels);
        Imf::FrameBuffer frame;
        const size_t xStride = sizeof(float) * image.channels;
        const std::span<const char* const> names = channelNames(image.channels);
        for (size_t c = 0; c < names.size(); ++c)
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window,
                                                    xStride, xStride * size_t(width)));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        // OpenEXR's messages already say what is wrong with the file ("Cannot read ...").
        throw InputError(subject, std::string("not a readable OpenEXR file: ") + e.what());
    }
}

FloatImage readExr(const std::filesystem::path& path) {
    return decodeExr(readFileBytes(path), path.string());
}

} // namespace penumbra
