// Shadow-map ray tracing (`smrt`) against its CPU reference: the shader on synthetic maps for
// both light models and every march branch, and smrt equal to hard under lights without size.
// Its error against the truth is in test_smrt_truth.cpp.
#include "analytic_scenes.h"
#include "render/frame_data.h"
#include "truth_fixture.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A ground plane at depth 0.7 with box and dome occluders nearer the light (0.25-0.5), some of
// them touching the ground's depth (contact).
std::vector<float> occludersOverGround(uint32_t seed, uint32_t size) {
    std::mt19937 engine(seed);
    auto unit = [&] { return float(engine() >> 8) / 16777216.0f; };
    std::vector<float> depth(size * size, 0.7f);
    for (int b = 0; b < 14; ++b) {
        const float cx = unit() * float(size), cy = unit() * float(size);
        const float radius = 2.0f + 8.0f * unit(), top = 0.25f + 0.25f * unit();
        const bool dome = b % 2 == 0;
        for (uint32_t y = 0; y < size; ++y)
            for (uint32_t x = 0; x < size; ++x) {
                const float dx = (float(x) + 0.5f - cx) / radius,
                            dy = (float(y) + 0.5f - cy) / radius;
                const float r2 = dx * dx + dy * dy;
                if (dome ? r2 < 1.0f : std::max(std::abs(dx), std::abs(dy)) < 1.0f) {
                    const float d = dome ? top + 0.2f * r2 : top;
                    float& stored = depth[y * size + x];
                    stored = std::min(stored, d);
                }
            }
    }
    return depth;
}

// `count` probes over the map of occludersOverGround, seven in ten on the ground, at random
// pixels (the rotation's input).
std::vector<FilterProbe> probesOverGround(uint32_t seed, size_t count) {
    std::mt19937 engine(seed);
    auto unit = [&] { return float(engine() >> 8) / 16777216.0f; };
    std::vector<FilterProbe> probes(count);
    for (FilterProbe& p : probes) {
        p.uv = {0.05f + 0.9f * unit(), 0.05f + 0.9f * unit()};
        p.depth = unit() < 0.7f ? 0.6995f : 0.3f + 0.3f * unit(); // mostly on the ground
        p.pixel = {engine() % 1920, engine() % 1080};
    }
    return probes;
}

// A sun, a spot and a cube face for the parity tests, with the sizes given.
std::array<ProbeLight, 3> parityLights(float sunSize, float size) {
    return {{{.perspective = false,
              .size = sunSize,
              .nearPlane = 1.0f,
              .farPlane = 21.0f,
              .worldPerUv = {12.0f, 12.0f}},
             {.perspective = true,
              .size = size,
              .nearPlane = 0.5f,
              .farPlane = 12.0f,
              .worldPerUv = {2.0f, 2.0f}},
             {.perspective = true,
              .size = size,
              .nearPlane = 0.5f,
              .farPlane = 12.0f,
              .worldPerUv = {2.0f, 2.0f},
              .cubeFace = true}}};
}

} // namespace

// The shader against its CPU mirror on synthetic maps, for both light models, every march
// branch (refinement, the adaptive stop, rotation): the blocked and extrapolated ray counts
// exactly, the visibility and the march length to rounding. Probes where a comparison came
// within 1e-5 (relative) of a tie, or a sample within 1e-5 of a texel's border, are skipped.
TEST_F(FilterTest, SmrtMatchesItsCpuReference) {
    // 95 texels: every level of smrt.skipLit's bounds is odd-sized (47, 23, 11, 5, 2, 1), and a
    // box on the last columns lies in the leftovers their last tiles must take.
    constexpr uint32_t kSize = 95;
    std::vector<float> depth = occludersOverGround(7, kSize);
    for (uint32_t y = 30; y < 60; ++y)
        for (uint32_t x = kSize - 3; x < kSize; ++x)
            depth[y * kSize + x] = 0.3f;
    const shadows::ShadowMapView map{depth, kSize};
    const std::vector<FilterProbe> probes = probesOverGround(5, 2000);
    // The cube face: smrt.cubeRays and smrt.cubeSamples (5, 6 here).
    const std::array<ProbeLight, 3> lights = parityLights(0.0524f, 0.4f);
    for (const ProbeLight& light : lights)
        for (const char* sets :
             // The cube face's adaptive stop the other way round from the spots' and suns'.
             // The gaps' samples likewise (the first one's marches are too short for them), and
             // smrt.hidden: the spots' and suns' in the second, the cube face's in the third, and
             // every light's in the fourth, in the march without gaps (the defaults' on cube
             // faces).
             {"smrt.rotation=none,smrt.refine=0,smrt.adaptive=0,smrt.cubeAdaptive=2,"
              "smrt.maxRadius=3,smrt.gapSamples=0,smrt.cubeGapSamples=2,smrt.cubeHidden=0",
              "smrt.rotation=ign,smrt.refine=3,smrt.adaptive=4,smrt.cubeAdaptive=0,"
              "smrt.maxRadius=24,smrt.gapSamples=3,smrt.cubeGapSamples=0,smrt.hidden=1,"
              "smrt.cubeHidden=0",
              // Long marches, whose far steps the gaps' samples fill under every light.
              "smrt.rotation=random,smrt.refine=2,smrt.adaptive=0,smrt.cubeAdaptive=0,"
              "smrt.maxRadius=128,smrt.gapSamples=4,smrt.cubeGapSamples=3,smrt.hidden=0,"
              "smrt.cubeHidden=1",
              "smrt.rotation=ign,smrt.refine=3,smrt.adaptive=0,smrt.cubeAdaptive=3,"
              "smrt.maxRadius=128,smrt.gapSamples=0,smrt.cubeGapSamples=0,smrt.hidden=1,"
              "smrt.cubeHidden=1"}) {
            ParameterValues params;
            params.set("smrt.rays", "16");
            params.set("smrt.cubeRays", "5");
            params.set("smrt.cubeSamples", "6");
            std::string all(sets);
            for (size_t at = 0; at < all.size();) {
                const size_t comma = std::min(all.find(',', at), all.size());
                params.assign(all.substr(at, comma - at));
                at = comma + 1;
            }
            const std::vector<glm::vec4> gpuResult = sharedRenderer().probeTechnique(
                Technique::Smrt, params, depth, kSize, probes, light);
            const shadows::FilterSettings frame =
                shadows::filterSettings(shadows::moduleOf(Technique::Smrt), params, false, 8);
            // The same without the gaps' samples: the probes they move.
            ParameterValues noGaps = params;
            noGaps.set("smrt.gapSamples", "0");
            noGaps.set("smrt.cubeGapSamples", "0");
            const shadows::FilterSettings frameNoGaps =
                shadows::filterSettings(shadows::moduleOf(Technique::Smrt), noGaps, false, 8);
            // The same without smrt.hidden: the probes it moves.
            ParameterValues shown = params;
            shown.set("smrt.hidden", "false");
            shown.set("smrt.cubeHidden", "false");
            const shadows::FilterSettings frameShown =
                shadows::filterSettings(shadows::moduleOf(Technique::Smrt), shown, false, 8);
            const gpu::ShadowViewData view = render::probeViewData(light);
            size_t compared = 0, valid = 0, penumbra = 0, extrapolated = 0, stopped = 0, proven = 0,
                   nan = 0, gapMoved = 0, hiddenMoved = 0;
            float most = 0.0f; // the most rays a probe found blocked
            glm::vec4 worst(0.0f);
            for (size_t i = 0; i < probes.size(); ++i) {
                if (shadows::smallestComparisonMargin(Technique::Smrt, map, probes[i], frame,
                                                      view) < 1e-5f)
                    continue;
                ++compared;
                const glm::vec4 cpu =
                    shadows::techniqueReference(Technique::Smrt, map, probes[i], frame, view);
                penumbra += cpu.x > 0.0f && cpu.x < 1.0f;
                gapMoved += cpu != shadows::techniqueReference(Technique::Smrt, map, probes[i],
                                                               frameNoGaps, view);
                hiddenMoved += cpu != shadows::techniqueReference(Technique::Smrt, map, probes[i],
                                                                  frameShown, view);
                valid += cpu.x >= 0.0f && cpu.x <= 1.0f && gpuResult[i].x >= 0.0f &&
                         gpuResult[i].x <= 1.0f;
                extrapolated += cpu.z > 0.0f;
                // Fewer rays traced than the view's budget.
                stopped += cpu.x == 0.0f && cpu.y < (light.cubeFace ? 5.0f : 16.0f);
                most = std::max(most, cpu.y);
                proven += cpu.x == 1.0f && cpu.w == 0.0f; // smrt.skipLit: no ray traced
                // glm::max passes over a NaN: count them apart.
                nan += glm::any(glm::isnan(gpuResult[i]));
                worst = glm::max(worst, glm::abs(cpu - gpuResult[i]) /
                                            glm::vec4(1.0f, 1.0f, 1.0f, std::max(cpu.w, 1.0f)));
            }
            const std::string what = std::string(light.cubeFace      ? "cube face "
                                                 : light.perspective ? "perspective "
                                                                     : "orthographic ") +
                                     sets;
            EXPECT_GT(compared, probes.size() * 7 / 10) << what;
            // No probe traces more rays than its view's budget; without the adaptive stop, umbra
            // probes find all of them blocked.
            const float budget = light.cubeFace ? 5.0f : 16.0f;
            // The view's own adaptive stop: smrt.cubeAdaptive on the cube face.
            const double adaptive =
                params.number(light.cubeFace ? "smrt.cubeAdaptive" : "smrt.adaptive");
            EXPECT_LE(most, budget) << what << ": rays traced";
            if (adaptive == 0) {
                EXPECT_EQ(most, budget) << what << ": rays traced";
            }
            EXPECT_EQ(valid, compared) << what << ": visibilities in [0, 1]";
            EXPECT_EQ(nan, 0u) << what << ": NaN in the GPU's results";
            EXPECT_GT(penumbra, 50u) << what << ": penumbrae";
            // The light's own smrt.gapSamples or smrt.cubeGapSamples: its gaps' samples find
            // occluders the long steps pass, and none where it has none. The 3-degree sun's rays
            // reach its near plane within 17 texels, and a march cut at 3 texels has no long step.
            const double gaps =
                params.number(light.cubeFace ? "smrt.cubeGapSamples" : "smrt.gapSamples");
            // smrt.hidden (smrt.cubeHidden on the cube face): the probe map's steps hide surfaces
            // from a few probes' rays (2 to 12); where it is off, from none.
            if (params.number(light.cubeFace ? "smrt.cubeHidden" : "smrt.hidden") != 0) {
                EXPECT_GT(hiddenMoved, 0u) << what << ": probes smrt.hidden moves";
            } else {
                EXPECT_EQ(hiddenMoved, 0u) << what << ": probes smrt.hidden moves";
            }
            if (gaps > 0 && light.perspective && params.number("smrt.maxRadius") > 10.0) {
                EXPECT_GT(gapMoved, 10u) << what << ": probes the gaps' samples move";
            } else if (gaps == 0) {
                EXPECT_EQ(gapMoved, 0u) << what << ": probes the gaps' samples move";
            }
            std::printf("%s: %zu of %zu probes moved by the gaps' samples, %zu by smrt.hidden\n",
                        what.c_str(), gapMoved, compared, hiddenMoved);
            if (adaptive > 0) {
                EXPECT_GT(stopped, 50u) << what << ": pixels the first rays settle";
            }
            // smrt.skipLit proves most of the open ground lit, at either reach.
            EXPECT_GT(proven, probes.size() / 8) << what << ": pixels proven lit";
            if (params.number("smrt.maxRadius") < 10.0) { // marches cut short
                EXPECT_GT(extrapolated, 20u) << what << ": extrapolated rays";
            }
            EXPECT_LE(worst.x, 1e-5f) << what << ": visibility";
            EXPECT_EQ(worst.y, 0.0f) << what << ": blocked rays";
            EXPECT_EQ(worst.z, 0.0f) << what << ": extrapolated rays";
            EXPECT_LE(worst.w, 1e-4f) << what << ": march length (relative)";
        }
}

// A light without size: every ray runs along the hard test's line, and smrt answers with the hard
// test itself (evaluateSmrt), on the GPU and in its mirror, for a sun, a spot and a cube face:
// the shader's smrt equals its hard on every probe, and the mirror equals the shader (probes
// whose comparison came within 1e-5 of a tie left out).
TEST_F(FilterTest, SmrtIsTheHardTestUnderALightWithoutSize) {
    constexpr uint32_t kSize = 64;
    const std::vector<float> depth = occludersOverGround(11, kSize);
    const shadows::ShadowMapView map{depth, kSize};
    const std::vector<FilterProbe> probes = probesOverGround(3, 1000);
    const std::array<ProbeLight, 3> lights = parityLights(0.0f, 0.0f);
    ParameterValues params; // smrt's defaults, and hard's (the bias family)
    const shadows::FilterSettings frame =
        shadows::filterSettings(shadows::moduleOf(Technique::Smrt), params, false, 8);
    for (const ProbeLight& light : lights) {
        const std::vector<glm::vec4> smrt =
            sharedRenderer().probeTechnique(Technique::Smrt, params, depth, kSize, probes, light);
        const std::vector<glm::vec4> hard =
            sharedRenderer().probeTechnique(Technique::Hard, params, depth, kSize, probes, light);
        const gpu::ShadowViewData view = render::probeViewData(light);
        size_t shadowed = 0, compared = 0, differ = 0, mirrorDiffers = 0;
        for (size_t i = 0; i < probes.size(); ++i) {
            differ += smrt[i].x != hard[i].x;
            shadowed += hard[i].x == 0.0f;
            if (shadows::smallestComparisonMargin(Technique::Hard, map, probes[i], frame, view) <
                1e-5f)
                continue;
            ++compared;
            mirrorDiffers +=
                shadows::techniqueReference(Technique::Smrt, map, probes[i], frame, view).x !=
                smrt[i].x;
        }
        const std::string what = light.cubeFace ? "cube face" : light.perspective ? "spot" : "sun";
        EXPECT_EQ(differ, 0u) << what << ": probes where smrt is not the hard test";
        EXPECT_GT(shadowed, probes.size() / 10) << what << ": probes in shadow";
        EXPECT_GT(compared, probes.size() * 9 / 10) << what;
        EXPECT_EQ(mirrorDiffers, 0u) << what << ": probes where the mirror differs";
    }
}

// The same in whole renders at smrt's defaults, against the exact truth of a light without size
// (one ray a pixel): a spot, a sun (cascades) and bulbs (cube faces), built-in and generated.
// Its views are fitted as hard's there (a band of one tap, not its march's: GuardBand), and no
// pixel is filled from its neighbours (Checkerboard::rangeFor), so every pixel reads as hard's:
// the same value but where its filter evens out a sun's cascade blend (values between 0 and 1 on
// either side of 0.5 stay there). The same value within rounding, not the same bits: the two
// techniques are two pipelines, and a compiler may fuse a multiply and an add in one and not in
// the other (SPIR-V lets it where NoContraction is absent). An H200 moved 419-553 of 57600
// pixels of every scene below by under 5e-7; lavapipe moves none. So a pixel moves when it
// differs by more than kRounding, a few units in the last place of a visibility near 1. Before
// (lavapipe, 320x180): the sun 0.0482% misclassified against hard's 0.0314%, gen/plates 1 0.361%
// against 0.254%, gen/clutter 2 0.224% against 0.078%.
TEST_F(QualityTest, SmrtEqualsHardUnderLightsWithoutSize) {
    const TruthSetup setups[] = {
        {.scene = "builtin:spot", .radius = 0.0f, .width = 320, .height = 180, .samples = 1},
        {.scene = "builtin:showcase", .angle = 0.0f, .width = 320, .height = 180, .samples = 1},
        {.scene = "builtin:room", .radius = 0.0f, .width = 320, .height = 180, .samples = 1},
        {.scene = "builtin:gen/plates?seed=1",
         .radius = 0.0f,
         .angle = 0.0f,
         .width = 320,
         .height = 180,
         .samples = 1},
        {.scene = "builtin:gen/clutter?seed=2",
         .radius = 0.0f,
         .angle = 0.0f,
         .width = 320,
         .height = 180,
         .samples = 1}};
    for (const TruthSetup& setup : setups) {
        const Truth t = groundTruth(setup);
        const RenderResult hardRender = renderRow(t, Technique::Hard, {});
        const RenderResult smrtRender = renderRow(t, Technique::Smrt, {});
        const ErrorMetrics hard = errorOf(t, hardRender), smrt = errorOf(t, smrtRender);
        const std::vector<float>&a = smrtRender.visibility.at(0), &b = hardRender.visibility.at(0);
        ASSERT_EQ(a.size(), b.size());
        constexpr float kRounding = 8.0f * std::numeric_limits<float>::epsilon();
        size_t flipped = 0, moved = 0;
        float largest = 0.0f; // the largest difference where both are numbers
        for (size_t i = 0; i < a.size(); ++i) {
            if (std::isnan(a[i]) || std::isnan(b[i])) {
                EXPECT_EQ(std::isnan(a[i]), std::isnan(b[i])) << setup.scene;
                continue;
            }
            const float difference = std::abs(a[i] - b[i]);
            largest = std::max(largest, difference);
            flipped += (a[i] < 0.5f) != (b[i] < 0.5f);
            moved += difference > kRounding;
            const bool between = (a[i] > 0.0f && a[i] < 1.0f) || (b[i] > 0.0f && b[i] < 1.0f);
            if (difference > kRounding) { // only where hard blends cascades
                EXPECT_TRUE(between)
                    << setup.scene << " pixel " << i << ": " << a[i] << " against " << b[i];
            }
        }
        std::printf("%-26s misclassified hard %.4f%% smrt %.4f%%, %zu pixels moved (at most "
                    "%.6f)\n",
                    setup.scene.c_str(), 100 * hard.misclassified, 100 * smrt.misclassified, moved,
                    largest);
        EXPECT_GT(hard.misclassified, 0.0) << setup.scene << ": edges to get wrong";
        EXPECT_EQ(flipped, 0u) << setup.scene;
        EXPECT_LE(moved, a.size() / 1000) << setup.scene; // a blend band's few
        if (t.scene.lights.front().type != LightType::Directional) {
            EXPECT_EQ(moved, 0u) << setup.scene << ": no cascades to blend";
        }
    }
}

// The stop short of the light (smrtNearestBehind) only on rays that near it: receivers on the
// map's nearest surface (a little nearer the light than their texels store, as a steep surface's
// point may lie within its texel), under a cube face whose
// light's radius reaches past them, have rays that rise away from the light's plane, climb past
// the ground's depth and fall behind it. The shader, which stops, against the mirror, which
// marches every ray to its end: the same blocked rays.
TEST_F(FilterTest, SmrtStopsOnlyOnRaysThatNearTheLight) {
    constexpr uint32_t kSize = 95;
    const std::vector<float> depth = occludersOverGround(7, kSize);
    const shadows::ShadowMapView map{depth, kSize};
    const float nearest = *std::min_element(depth.begin(), depth.end());
    std::vector<FilterProbe> probes;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x)
            if (depth[y * kSize + x] < nearest + 0.02f)
                probes.push_back(
                    {.uv = {(float(x) + 0.5f) / float(kSize), (float(y) + 0.5f) / float(kSize)},
                     .depth = depth[y * kSize + x] - 0.005f,
                     .pixel = {x * 7u, y * 5u}});
    ASSERT_GT(probes.size(), 20u);
    const ProbeLight light{.perspective = true,
                           .size = 0.4f,
                           .nearPlane = 0.05f,
                           .farPlane = 12.0f,
                           .worldPerUv = {2.0f, 2.0f},
                           .cubeFace = true};
    ParameterValues params;
    params.set("smrt.cubeAdaptive", "0");
    const std::vector<glm::vec4> gpuResult =
        sharedRenderer().probeTechnique(Technique::Smrt, params, depth, kSize, probes, light);
    const shadows::FilterSettings frame =
        shadows::filterSettings(shadows::moduleOf(Technique::Smrt), params, false, 8);
    const gpu::ShadowViewData view = render::probeViewData(light);
    size_t compared = 0, blocked = 0, differ = 0;
    for (size_t i = 0; i < probes.size(); ++i) {
        if (shadows::smallestComparisonMargin(Technique::Smrt, map, probes[i], frame, view) < 1e-5f)
            continue;
        ++compared;
        const glm::vec4 cpu =
            shadows::techniqueReference(Technique::Smrt, map, probes[i], frame, view);
        blocked += cpu.y > 0.0f;
        differ += cpu.y != gpuResult[i].y || std::abs(cpu.x - gpuResult[i].x) > 1e-5f;
    }
    std::printf("%zu of %zu probes compared, %zu with blocked rays, %zu differ\n", compared,
                probes.size(), blocked, differ);
    EXPECT_GT(compared, probes.size() / 2);
    EXPECT_GT(blocked, compared / 4) << "probes whose rising rays fall behind the ground";
    EXPECT_EQ(differ, 0u);
}
