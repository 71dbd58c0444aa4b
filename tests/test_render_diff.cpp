// Cross-device image agreement, in the manner of Filament's renderdiff: every row `compare` shows
// by default (every technique, its variants, the layers' rows) renders builtin:demo with a spot
// and a bulb added (every light type) at 64x48 and must agree with the images stored in
// tests/renderdiff/, made on lavapipe by `make renderdiff-store`. `make renderdiff` runs only these
// on any device.
//
// Two conformant devices may differ in three ways, and the comparison allows each, no more:
// - rasterization and depth ties: Vulkan fixes the coverage rule but not the subpixel precision
//   (4 bits or more) nor the depth rounding, so a silhouette or a shadow edge may move by a
//   pixel. A pixel may take any value its stored 3x3 neighbourhood spans (a silhouette pixel may
//   be background), and a few may fall outside it (the outlier share below).
// - filtering precision: a texture unit weighs bilinear taps with subTexelPrecisionBits of
//   fraction (hardwareFilterTolerance()); techniques that filter in hardware may move by that.
// - moment and field arithmetic: 16-bit moments round to one step, and the Chebyshev and
//   moment bounds magnify a step near a shadow's edge; the distance field is built and traced in
//   floats whose operations Vulkan lets be a few ulps off. These get a stated value per family.
// The stored images are 8-bit, so half a step (0.5/255) is added to every bound.
#include "gpu_fixture.h"
#include "penumbra/settings.h"
#include "scene/builtin_scenes.h"

#include "core/image_io.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 48, kMapSize = 256;

// Where the stored images live: PENUMBRA_RENDERDIFF_DIR, else the source tree's.
fs::path storeDir() {
    const char* dir = std::getenv("PENUMBRA_RENDERDIFF_DIR");
    return dir ? fs::path(dir) : fs::path(PENUMBRA_SOURCE_DIR) / "tests" / "renderdiff";
}

// A file name for a row: "pcf[box7]+contact" -> "pcf-box7-+contact.png".
std::string fileName(const std::string& row) {
    std::string name;
    for (char c : row)
        name += (c == '[' || c == ']') ? '-' : c;
    return name + ".png";
}

// One image per light, stacked top to bottom: gray = visibility, alpha = 255 on the scene,
// 0 on the background.
struct Stack {
    uint32_t lights = 0;
    std::vector<uint8_t> pixels; // 2 per pixel
    bool foreground(uint32_t light, int x, int y) const {
        return pixels[2 * index(light, x, y) + 1] != 0;
    }
    double value(uint32_t light, int x, int y) const {
        return pixels[2 * index(light, x, y)] / 255.0;
    }
    static size_t index(uint32_t light, int x, int y) {
        return (size_t(light) * kHeight + y) * kWidth + x;
    }
};

Stack stackOf(const RenderResult& r) {
    Stack s{.lights = uint32_t(r.visibility.size())};
    s.pixels.resize(2 * size_t(s.lights) * kWidth * kHeight);
    for (uint32_t l = 0; l < s.lights; ++l)
        for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i) {
            const float v = r.visibility[l][i];
            const size_t at = 2 * (l * size_t(kWidth) * kHeight + i);
            s.pixels[at] =
                std::isnan(v) ? 0 : uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
            s.pixels[at + 1] = std::isnan(v) ? 0 : 255;
        }
    return s;
}

std::optional<Stack> readStack(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        return std::nullopt;
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
    int w = 0, h = 0, channels = 0;
    uint8_t* data = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 2);
    if (!data || w != int(kWidth) || h % int(kHeight) != 0) {
        stbi_image_free(data);
        return std::nullopt;
    }
    Stack s{.lights = uint32_t(h) / kHeight};
    s.pixels.assign(data, data + size_t(w) * h * 2);
    stbi_image_free(data);
    return s;
}

// What a technique may differ by beyond its stored neighbourhood, and the share of pixels that
// may fall outside it altogether.
struct Allowance {
    double value;
    double outlierShare;
};

Allowance allowanceFor(Technique technique) {
    const double filter = hardwareFilterTolerance();
    switch (technique) {
    case Technique::Hard:
    case Technique::SecondDepth:
        return {0.0, 0.005}; // one comparison per pixel: ties only
    case Technique::Pcf:
        return {filter, 0.005};
    case Technique::Smrt: // a ray's crossing test may flip: one ray of smrt[fast]'s 8
        return {1.0 / 8.0 + 0.02, 0.01};
    default: // blocker searches, moments, fields: see the header
        return {filter + 0.02, 0.01};
    }
}

struct Difference {
    size_t outliers = 0, compared = 0;
    double worstExcess = 0.0, meanAbs = 0.0;
};

Difference compareStacks(const Stack& stored, const Stack& device, double allowed) {
    Difference d;
    const double half = 0.5 / 255.0 + 1e-6;
    double sumAbs = 0.0;
    for (uint32_t l = 0; l < stored.lights; ++l)
        for (int y = 0; y < int(kHeight); ++y)
            for (int x = 0; x < int(kWidth); ++x) {
                double lo = 2.0, hi = -1.0;
                bool anyBackground = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = std::clamp(x + dx, 0, int(kWidth) - 1);
                        const int ny = std::clamp(y + dy, 0, int(kHeight) - 1);
                        if (!stored.foreground(l, nx, ny)) {
                            anyBackground = true;
                            continue;
                        }
                        lo = std::min(lo, stored.value(l, nx, ny));
                        hi = std::max(hi, stored.value(l, nx, ny));
                    }
                const bool was = stored.foreground(l, x, y), is = device.foreground(l, x, y);
                if (!is) { // background where the stored image had scene: only at a silhouette
                    d.outliers += was && !anyBackground;
                    continue;
                }
                ++d.compared;
                if (hi < lo) { // the stored neighbourhood is all background
                    ++d.outliers;
                    continue;
                }
                const double v = device.value(l, x, y);
                if (was)
                    sumAbs += std::abs(v - stored.value(l, x, y));
                const double excess = std::max({0.0, lo - v, v - hi}) - half;
                d.worstExcess = std::max(d.worstExcess, excess);
                d.outliers += excess > allowed;
            }
    d.meanAbs = d.compared ? sumAbs / double(d.compared) : 0.0;
    return d;
}

void writeStack(const fs::path& file, const Stack& s) {
    const std::vector<uint8_t> png = encodePng(kWidth, kHeight * s.lights, 2, s.pixels);
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
}

// builtin:demo's sun, a spot and a bulb, each with a size (the soft techniques need one).
Scene threeLightDemo() {
    Scene scene = builtin::demo();
    Light spot = builtin::spotLight({-4.0f, 7.0f, 4.0f}, {0.0f, 0.5f, -1.0f}, 0.45f, 0.6f);
    spot.radius = 0.3f;
    scene.lights.push_back(spot);
    scene.lights.push_back({.name = "bulb",
                            .type = LightType::Point,
                            .position = {1.5f, 5.0f, 1.5f},
                            .color = {1.0f, 0.9f, 0.75f},
                            .intensity = 20.0f,
                            .radius = 0.25f});
    return scene;
}

} // namespace

using RenderDiffTest = GpuTest;

// PENUMBRA_RENDERDIFF_STORE=1 writes the stored images instead of comparing (the images of a new
// or deliberately changed technique); PENUMBRA_RENDERDIFF_OUT=DIR also writes this device's.
TEST_F(RenderDiffTest, EveryRowAgreesWithTheStoredImagesWithinItsAllowance) {
    const bool store = std::getenv("PENUMBRA_RENDERDIFF_STORE") != nullptr;
    const char* out = std::getenv("PENUMBRA_RENDERDIFF_OUT");
    const Scene scene = threeLightDemo();
    if (store)
        fs::create_directories(storeDir());
    size_t rows = 0;
    for (const TechniqueRow& row : comparisonRows("")) {
        RenderOptions options{.width = kWidth, .height = kHeight, .shadowMapSize = kMapSize};
        options.technique = row.technique;
        for (const auto& [key, value] : row.sets)
            options.parameters.set(key, value);
        applyRow(row, options.parameters, scene.bounds().radius());
        const Stack device = stackOf(render(scene, options));
        ASSERT_EQ(device.lights, scene.lights.size()) << row.name;
        const fs::path file = storeDir() / fileName(row.name);
        if (out) {
            fs::create_directories(out);
            writeStack(fs::path(out) / fileName(row.name), device);
        }
        if (store) {
            writeStack(file, device);
            continue;
        }
        const std::optional<Stack> stored = readStack(file);
        ASSERT_TRUE(stored) << file << " is missing or not a " << kWidth
                            << "-wide stack: `make renderdiff-store` writes it";
        ASSERT_EQ(stored->lights, device.lights) << file;
        const Allowance allowance = allowanceFor(row.technique);
        const Difference d = compareStacks(*stored, device, allowance.value);
        std::printf("%-24s outliers %4zu of %5zu (allowed %.1f%%)  worst %.4f (allowed %.4f)  "
                    "mean |diff| %.5f\n",
                    row.name.c_str(), d.outliers, d.compared, 100 * allowance.outlierShare,
                    d.worstExcess, allowance.value, d.meanAbs);
        EXPECT_LE(double(d.outliers), allowance.outlierShare * double(d.compared))
            << row.name << " (" << file << "): " << d.outliers
            << " pixels outside their stored neighbourhood by more than " << allowance.value;
        ++rows;
    }
    if (!store) {
        EXPECT_GE(rows, allTechniques().size());
    }
}
