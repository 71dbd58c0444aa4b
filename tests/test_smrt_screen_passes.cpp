// smrt's screen-space passes on the GPU against their CPU mirrors: checkerboard tracing's fill
// (src/shadows/checkerboard_fill.cpp) and the edge-aware visibility filter
// (src/shadows/visibility_filter.cpp), under each light type. The mirrors on images made in code:
// tests/test_checkerboard.cpp, tests/test_visibility_filter.cpp.
#include "analytic_scenes.h"
#include "checkerboard.h"
#include "gpu_fixture.h"
#include "shadows/checkerboard_fill.h"
#include "shadows/visibility_filter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

using namespace penumbra;
using namespace penumbra::test;

// Checkerboard tracing on the GPU against its CPU mirror (smrt.checkerboard; the filters off, so
// that each layer holds what its three dispatches left), in one frame of a bulb and a spot (their
// ranges differ, and the lights take turns at one trace list) and under a sun: each filled pixel
// is the mean fillCheckerboard takes from the render's own even pixels, positions and normals (to
// rounding, 1e-5); each even pixel and each listed one is what a render that traces every pixel
// gives (the same code at the same pixel; a rounding may still move a ray's read across a texel's
// border: at most 0.1% of the pixels by more than 1e-5; an image's last row is 0.5%). Pixels a
// rounding could send either way (the mirror's `close`) are left out, and counted. Every list holds
// more than one workgroup's pixels (64): its dispatch's group count must grow with it.
TEST_F(FilterTest, CheckerboardMatchesItsCpuReference) {
    Scene both = spheresOverPlane(
        {.name = "bulb", .type = LightType::Point, .position = {0, 1.2f, 0}, .radius = 0.3f});
    both.lights.push_back(acceptanceSpot(0.5f));
    // The sun's camera looks past the plane's far edge: odd background pixels must stay NaN.
    Scene sunPastThePlane = sphereOverPlane(acceptanceSun(6.0f));
    sunPastThePlane.cameras.front().target = {0.0f, 1.0f, -3.0f};
    const std::pair<const char*, Scene> scenes[] = {{"bulb and spot", both},
                                                    {"sun", sunPastThePlane}};
    for (const auto& [name, scene] : scenes)
        for (const float range : {0.0f, 0.3f}) {
            // Under point lights the range is the other one plus 0.2: a light given the wrong one
            // fills what the mirror does not.
            const float cubeRange = range + 0.2f;
            auto render = [&](const Scene& lit, bool checkerboard) {
                // The sun's image has odd sides: the dispatches half the image high must still
                // reach its last row.
                const bool sun = std::string(name) == "sun";
                RenderOptions o{.width = sun ? 127u : 128u,
                                .height = sun ? 129u : 128u,
                                .frames = 1,
                                .technique = Technique::Smrt};
                o.parameters.set("smrt.filter", "0");
                o.parameters.set("smrt.cubeFilter", "0");
                o.parameters.set("smrt.checkerboard", checkerboard ? "true" : "false");
                o.parameters.set("smrt.fillRange", fmt::format("{}", range));
                o.parameters.set("smrt.cubeFillRange", fmt::format("{}", cubeRange));
                return sharedRenderer().render(lit, o);
            };
            // The visibility image outlives a render of the same size: before the checkerboard's,
            // the lights shine from under the plane, which reads 0 where they lit it. A pixel the
            // checkerboard never writes keeps that 0, not the full render's value.
            Scene below = scene;
            for (Light& light : below.lights) {
                light.position.y = -light.position.y;
                light.direction = -light.direction;
            }
            (void)render(below, false);
            const RenderResult gpu = render(scene, true), full = render(scene, false);
            ASSERT_EQ(gpu.visibility.size(), scene.lights.size());
            for (size_t l = 0; l < scene.lights.size(); ++l) {
                const bool point = scene.lights[l].type == LightType::Point;
                const std::string what =
                    fmt::format("{} (light {}, range {})", name, l, point ? cubeRange : range);
                const shadows::CheckerboardFill cpu =
                    shadows::fillCheckerboard(gpu.width, gpu.height, gpu.position, gpu.normal,
                                              gpu.visibility[l], point ? cubeRange : range);
                size_t count[4] = {}, close = 0, moved = 0;
                float worstFill = 0.0f;
                for (size_t i = 0; i < cpu.pixels.size(); ++i) {
                    const float v = gpu.visibility[l][i], traced = full.visibility[l][i];
                    const auto kind = cpu.pixels[i];
                    ++count[static_cast<int>(kind)];
                    ASSERT_EQ(std::isnan(v), kind == shadows::CheckerboardPixel::Background)
                        << what << " " << i;
                    if (kind == shadows::CheckerboardPixel::Background)
                        continue;
                    if (cpu.close[i]) {
                        ++close;
                        continue;
                    }
                    if (kind == shadows::CheckerboardPixel::Filled)
                        worstFill = std::max(worstFill, std::abs(v - cpu.visibility[i]));
                    else
                        moved += std::abs(v - traced) > 1e-5f;
                }
                const size_t pixels = cpu.pixels.size() - count[0];
                std::printf("%-22s traced %zu, filled %zu, listed %zu (%zu close); filled "
                            "against the mirror %.2g, traced off the full render %zu\n",
                            what.c_str(), count[1], count[2], count[3], close, worstFill, moved);
                EXPECT_LE(worstFill, 1e-5f) << what;
                EXPECT_LE(moved, pixels / 1000) << what;
                EXPECT_LE(close, pixels / 100) << what;
                if (std::string(name) == "sun") {
                    EXPECT_GT(count[0], pixels / 10) << what << ": background";
                }
                // Both fates must be common, or the checks above prove little.
                EXPECT_GT(count[2], pixels / 10) << what << ": filled";
                EXPECT_GT(count[3], size_t{CHECKERBOARD_LIST_GROUP}) << what << ": listed";
            }
        }
}

// The visibility filter's two passes on the GPU against their CPU mirror, under each light
// type: the unfiltered render's visibility, positions and normals through filterVisibility give
// the filtered render's visibility to rounding (every weight is continuous; 1e-4 is a hundred
// times what float sums of nine terms can move), the background stays NaN, and the shaded image
// (composite.fused asked for: the filter must keep the composite out of the visibility dispatch)
// changes with it.
TEST_F(FilterTest, VisibilityFilterMatchesItsCpuReference) {
    const std::pair<const char*, Scene> scenes[] = {
        {"spot", sphereOverPlane(acceptanceSpot(0.5f))},
        {"sun", sphereOverPlane(acceptanceSun(6.0f))},
        {"point", spheresOverPlane({.name = "bulb",
                                    .type = LightType::Point,
                                    .position = {0, 1.2f, 0},
                                    .radius = 0.3f})}};
    for (const auto& [name, scene] : scenes) {
        // The point light's filter takes smrt.cubeFilter, the others smrt.filter: each render
        // sets the other one to 0, so that a light given the wrong radius is not filtered.
        const bool point = std::string(name) == "point";
        auto render = [&](const char* radius) {
            RenderOptions o{.width = 128, .height = 128, .frames = 1, .technique = Technique::Smrt};
            o.parameters.set("smrt.filter", point ? "0" : radius);
            o.parameters.set("smrt.cubeFilter", point ? radius : "0");
            // The same for the tolerance: the light's own 0.5, the other 0.9.
            o.parameters.set("smrt.filterTolerance", point ? "0.9" : "0.5");
            o.parameters.set("smrt.cubeFilterTolerance", point ? "0.5" : "0.9");
            // And the radius inside wide penumbrae: the light's own 4, the other none.
            o.parameters.set("smrt.filterWide", point ? "0" : "4");
            o.parameters.set("smrt.cubeFilterWide", point ? "4" : "0");
            o.parameters.set("composite.fused", "true");
            // Every pixel traced: the checkerboard would keep the composite out of the
            // visibility dispatch whether or not a filter runs.
            o.parameters.set("smrt.checkerboard", "false");
            return sharedRenderer().render(scene, o);
        };
        const RenderResult base = render("0"), gpu = render("2");
        const std::vector<float> cpu = shadows::filterVisibility(
            base.width, base.height, base.position, base.normal, base.visibility[0],
            {.radius = 2, .tolerance = 0.5f, .wide = 4});
        // The wide penumbrae's reach must change some pixels, or the check above proves nothing.
        const std::vector<float> narrow =
            shadows::filterVisibility(base.width, base.height, base.position, base.normal,
                                      base.visibility[0], {.radius = 2, .tolerance = 0.5f});
        float widened = 0.0f;
        for (size_t i = 0; i < cpu.size(); ++i)
            if (!std::isnan(cpu[i]))
                widened = std::max(widened, std::abs(cpu[i] - narrow[i]));
        EXPECT_GT(widened, 0.01f) << name << ": no pixel reached into a wide penumbra";
        float worst = 0.0f, moved = 0.0f;
        size_t background = 0, outside = 0;
        for (size_t i = 0; i < cpu.size(); ++i) {
            ASSERT_EQ(std::isnan(cpu[i]), std::isnan(gpu.visibility[0][i])) << name << " " << i;
            if (std::isnan(cpu[i])) {
                ++background;
                continue;
            }
            worst = std::max(worst, std::abs(cpu[i] - gpu.visibility[0][i]));
            outside += gpu.visibility[0][i] < 0.0f || gpu.visibility[0][i] > 1.0f;
            moved = std::max(moved, std::abs(gpu.visibility[0][i] - base.visibility[0][i]));
        }
        std::printf("%-6s filter: GPU against CPU %.2g, moved up to %.3f (wide penumbrae %.3f), "
                    "%zu background\n",
                    name, worst, moved, widened, background);
        EXPECT_LE(worst, 1e-4f) << name;
        EXPECT_EQ(outside, 0u) << name << ": filtered visibilities outside [0, 1]";
        EXPECT_GT(moved, 0.05f) << name << ": the filter changed nothing";
        EXPECT_NE(gpu.image, base.image) << name << ": the composite shaded unfiltered visibility";
    }
}
