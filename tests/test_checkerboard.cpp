// Checkerboard tracing's fill on the CPU (src/shadows/checkerboard_fill.cpp, its rules shared with
// visibility_fill.comp in shaders/include/checkerboard.h) on images made in code: what it fills
// (a smooth ramp, exactly), what it traces (edges past the range, lone pixels), what it never
// mixes (other surfaces, the background). The GPU against this mirror: FilterTest in
// tests/test_smrt_screen_passes.cpp.
#include "checkerboard.h"
#include "light_geometry.h"
#include "shadows/checkerboard_fill.h"
#include "surface_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

using namespace penumbra;
using shadows::CheckerboardPixel;
using test::onPlane;
using test::up;

namespace {

constexpr uint32_t kWidth = 12, kHeight = 9; // odd and even sides: both parities end a row
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

using Image = test::SurfaceImage;

// A kWidth x kHeight image: position(x, y) (NaN: background), normal(x, y), visibility(x, y).
Image image(const std::function<glm::vec3(int, int)>& position,
            const std::function<glm::vec3(int, int)>& normal,
            const std::function<float(int, int)>& visibility) {
    return test::surfaceImage(kWidth, kHeight, position, normal, visibility);
}

shadows::CheckerboardFill fill(const Image& s, float range) {
    return shadows::fillCheckerboard(kWidth, kHeight, s.position, s.normal, s.visibility, range);
}

size_t at(int x, int y) {
    return size_t(y) * kWidth + size_t(x);
}

} // namespace

// The invocations of a dispatch half the image high (checkerboardRows; the image's height is odd)
// reach every pixel of one parity once.
TEST(Checkerboard, InvocationsCoverEachParityOnce) {
    for (uint32_t odd = 0; odd < 2; ++odd) {
        std::vector<int> seen(kWidth * kHeight, 0);
        for (uint32_t gy = 0; gy < gpu::checkerboardRows(kHeight); ++gy)
            for (uint32_t gx = 0; gx < kWidth; ++gx) {
                const glm::ivec2 p = gpu::checkerboardPixel({gx, gy}, odd);
                if (p.y < int(kHeight))
                    ++seen[at(p.x, p.y)];
            }
        for (int y = 0; y < int(kHeight); ++y)
            for (int x = 0; x < int(kWidth); ++x)
                EXPECT_EQ(seen[at(x, y)], (x + y) % 2 == int(odd) ? 1 : 0) << x << " " << y;
    }
    EXPECT_EQ(gpu::unpackPixel(gpu::packPixel({4095, 16383})), glm::ivec2(4095, 16383));
}

// A ramp's odd pixels are its four neighbours' mean: exactly the ramp. Even pixels are kept.
TEST(Checkerboard, FillsASmoothRampExactly) {
    const Image s = image(onPlane, up, [](int x, int y) {
        return (x + y) % 2 ? -1.0f : 0.25f + 0.02f * float(x) + 0.01f * float(y);
    });
    const shadows::CheckerboardFill f = fill(s, 0.1f);
    for (int y = 0; y < int(kHeight); ++y)
        for (int x = 0; x < int(kWidth); ++x) {
            const float ramp = 0.25f + 0.02f * float(x) + 0.01f * float(y);
            const bool edge = x == 0 || y == 0 || x == int(kWidth) - 1 || y == int(kHeight) - 1;
            if ((x + y) % 2 == 0) {
                EXPECT_EQ(f.pixels[at(x, y)], CheckerboardPixel::Traced);
                EXPECT_EQ(f.visibility[at(x, y)], s.visibility[at(x, y)]);
            } else {
                EXPECT_EQ(f.pixels[at(x, y)], CheckerboardPixel::Filled) << x << " " << y;
                // On the image's border the mean of three neighbours is off the ramp.
                if (!edge) {
                    EXPECT_NEAR(f.visibility[at(x, y)], ramp, 1e-6f) << x << " " << y;
                }
            }
        }
    // The corner (1, 0) has three neighbours: (0, 0), (2, 0), (1, 1).
    EXPECT_NEAR(f.visibility[at(1, 0)], (0.25f + 0.29f + 0.28f) / 3.0f, 1e-6f);
}

// Neighbours that span more than the range send the pixel to the trace list; just within it,
// they fill. A range of 0 fills only between equal neighbours.
TEST(Checkerboard, TracesWhereNeighboursDisagree) {
    // Even pixels left of x = 6 are 0.2, right of it 0.5: the odd pixels at x = 5 and 6 see both.
    const Image s = image(onPlane, up, [](int x, int) { return x < 6 ? 0.2f : 0.5f; });
    for (const float range : {0.29f, 0.31f, 0.0f}) {
        const shadows::CheckerboardFill f = fill(s, range);
        for (int y = 0; y < int(kHeight); ++y)
            for (int x = 0; x < int(kWidth); ++x) {
                if ((x + y) % 2 == 0)
                    continue;
                const bool straddles = x == 5 || x == 6;
                const CheckerboardPixel expected = straddles && range < 0.3f
                                                       ? CheckerboardPixel::Listed
                                                       : CheckerboardPixel::Filled;
                EXPECT_EQ(f.pixels[at(x, y)], expected) << range << ": " << x << " " << y;
                if (expected == CheckerboardPixel::Listed) {
                    EXPECT_TRUE(std::isnan(f.visibility[at(x, y)]));
                }
            }
    }
}

// A neighbour off the pixel's surface (a step in depth, a crease, the background) does not count
// towards the mean: a pixel with none left is traced; the background stays NaN.
TEST(Checkerboard, NeverMixesOtherSurfacesOrTheBackground) {
    // Columns 0-5 a floor at z = 0, lit; columns 6-11 a wall standing on it (facing -x), dark;
    // row 8 background.
    auto position = [](int x, int y) {
        if (y == int(kHeight) - 1)
            return glm::vec3(kNan);
        return x < 6 ? onPlane(x, y) : glm::vec3(0.6f, 0.1f * float(y), 0.1f * float(x - 5));
    };
    auto normal = [](int x, int) { return x < 6 ? glm::vec3(0, 0, 1) : glm::vec3(-1, 0, 0); };
    const Image s = image(position, normal, [](int x, int) { return x < 6 ? 1.0f : 0.0f; });
    const shadows::CheckerboardFill f = fill(s, 1.0f); // the range lets anything through
    for (int y = 0; y < int(kHeight); ++y)
        for (int x = 0; x < int(kWidth); ++x) {
            if (y == int(kHeight) - 1) {
                EXPECT_EQ(f.pixels[at(x, y)], CheckerboardPixel::Background);
                EXPECT_TRUE(std::isnan(f.visibility[at(x, y)]));
            } else if ((x + y) % 2) {
                EXPECT_EQ(f.pixels[at(x, y)], CheckerboardPixel::Filled) << x << " " << y;
                EXPECT_EQ(f.visibility[at(x, y)], x < 6 ? 1.0f : 0.0f) << x << " " << y;
            }
        }
    // With a range below the step, the pixels beside the crease are traced: their neighbours on
    // the other surface count towards the span (a shadow's edge along an object's edge), not
    // towards the mean.
    const shadows::CheckerboardFill edged = fill(s, 0.5f);
    for (int y = 0; y + 1 < int(kHeight); ++y)
        for (int x = 0; x < int(kWidth); ++x)
            if ((x + y) % 2) {
                EXPECT_EQ(edged.pixels[at(x, y)],
                          x == 5 || x == 6 ? CheckerboardPixel::Listed : CheckerboardPixel::Filled)
                    << x << " " << y;
            }
    // A pixel whose neighbours are all background or elsewhere is traced.
    auto lone = [](int x, int y) { return x == 3 && y == 4 ? onPlane(x, y) : glm::vec3(kNan); };
    const shadows::CheckerboardFill alone =
        fill(image(lone, up, [](int, int) { return 1.0f; }), 1.0f);
    EXPECT_EQ(alone.pixels[at(3, 4)], CheckerboardPixel::Listed);
    // Even pixels' normals tilted past the bound (cos 37 degrees) from the odd ones': 40 degrees
    // off, no neighbour counts.
    auto tilted = [](int x, int y) {
        return (x + y) % 2 ? glm::vec3(0, 0, 1) : glm::vec3(std::sin(0.7f), 0.0f, std::cos(0.7f));
    };
    const shadows::CheckerboardFill kinked =
        fill(image(onPlane, tilted, [](int, int) { return 0.5f; }), 1.0f);
    EXPECT_EQ(kinked.pixels[at(3, 4)], CheckerboardPixel::Listed);
    // Within it (30 degrees) the neighbours count.
    auto gentle = [](int x, int y) {
        return (x + y) % 2 ? glm::vec3(0, 0, 1) : glm::vec3(std::sin(0.52f), 0.0f, std::cos(0.52f));
    };
    const shadows::CheckerboardFill smooth =
        fill(image(onPlane, gentle, [](int, int) { return 0.5f; }), 1.0f);
    EXPECT_EQ(smooth.pixels[at(3, 4)], CheckerboardPixel::Filled);
}

// A list longer than a row of groups may hold spreads over rows; a short one takes one.
TEST(Checkerboard, LongListsTakeRowsOfGroups) {
    const uint32_t row = CHECKERBOARD_ROW_GROUPS * CHECKERBOARD_LIST_GROUP; // entries a row holds
    EXPECT_EQ(gpu::checkerboardListRows(0), 1u);
    EXPECT_EQ(gpu::checkerboardListRows(1), 1u);
    EXPECT_EQ(gpu::checkerboardListRows(row), 1u);
    EXPECT_EQ(gpu::checkerboardListRows(row + 1), 2u);
    EXPECT_EQ(gpu::checkerboardListRows(3 * row), 3u);
    // An image of 32768 x 32768: its odd pixels in rows of at most CHECKERBOARD_ROW_GROUPS.
    const uint32_t odd = 32768u * 32768u / 2;
    const uint32_t rows = gpu::checkerboardListRows(odd);
    EXPECT_LE((odd + CHECKERBOARD_LIST_GROUP * rows - 1) / (CHECKERBOARD_LIST_GROUP * rows),
              CHECKERBOARD_ROW_GROUPS);
}

// The ranges by light kind.
TEST(Checkerboard, PointLightsTakeTheCubeRange) {
    const shadows::Checkerboard c{.runs = true, .range = 0.1f, .cubeRange = 0.3f};
    EXPECT_EQ(c.rangeFor(LIGHT_POINT, true), 0.3f);
    EXPECT_EQ(c.rangeFor(LIGHT_SPOT, true), 0.1f);
    EXPECT_EQ(c.rangeFor(LIGHT_DIRECTIONAL, true), 0.1f);
    // Under a light without size no pixel is filled, whatever agrees.
    for (uint32_t type : {LIGHT_POINT, LIGHT_SPOT, LIGHT_DIRECTIONAL})
        EXPECT_LT(c.rangeFor(type, false), 0.0f);
}
