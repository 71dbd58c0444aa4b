#pragma once
// `penumbra view` run by the tests under a virtual X server (xvfb-run, which `make deps`
// installs), its screenshots read back, and render's image of the same options beside them.
#include "core/image_io.h"
#include "process.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::test {

inline constexpr const char* kXvfbRun = "/usr/bin/xvfb-run";

struct Rgb {
    int width = 0, height = 0;
    std::vector<uint8_t> pixels; // 3 per pixel, rows top to bottom
    const uint8_t* at(int x, int y) const { return &pixels[3 * (size_t(y) * width + x)]; }
};

inline Rgb readPng(const std::filesystem::path& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    Rgb image;
    int channels = 0;
    uint8_t* data = stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()),
                                          &image.width, &image.height, &channels, 3);
    EXPECT_NE(data, nullptr) << path;
    if (data) {
        image.pixels.assign(data, data + size_t(image.width) * image.height * 3);
        stbi_image_free(data);
    }
    return image;
}

inline std::filesystem::path scratch(const std::string& name) {
    return scratchDir("viewer", name, true);
}

// `penumbra --validation view ARGS` on a fresh virtual X server (24-bit, larger than any window
// here); any validation message fails the test.
inline ProcessResult runViewer(const std::vector<std::string>& args) {
    EXPECT_TRUE(std::filesystem::exists(kXvfbRun)) << "xvfb-run is missing: run `make deps`";
    std::vector<std::string> full{
        kXvfbRun, "-a", "-s", "-screen 0 1280x1024x24", PENUMBRA_CLI_PATH, "--validation", "view"};
    full.insert(full.end(), args.begin(), args.end());
    ProcessResult result = runProcess(std::move(full));
    EXPECT_EQ(result.err.find("vulkan validation"), std::string::npos) << result.err;
    return result;
}

// The mean absolute difference per channel, in 1/255 units, over columns [x0, x1).
inline double meanDifference(const Rgb& a, const Rgb& b, int x0 = 0, int x1 = -1) {
    if (x1 < 0)
        x1 = a.width;
    double sum = 0;
    size_t n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c, ++n)
                sum += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
    return n ? sum / double(n) : 0.0;
}

inline Rgb renderImage(const std::vector<std::string>& options, const std::string& name) {
    const std::filesystem::path out = scratch(name);
    std::vector<std::string> args{"render", "-o", out.string(), "--frames", "1"};
    args.insert(args.end(), options.begin(), options.end());
    const ProcessResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readPng(out / "image.png");
}

inline Rgb viewImage(const std::vector<std::string>& options, const std::string& name,
                     ProcessResult* result = nullptr, const std::string& frames = "4") {
    const std::filesystem::path shot = scratch(name) / "shot.png";
    std::vector<std::string> args{"--frames", frames, "--screenshot", shot.string()};
    args.insert(args.end(), options.begin(), options.end());
    const ProcessResult r = runViewer(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("wrote " + shot.string()), std::string::npos) << r.out;
    if (result)
        *result = r;
    return readPng(shot);
}

} // namespace penumbra::test
