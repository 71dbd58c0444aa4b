// Shadow-map ray tracing (`smrt`): its CPU reference against the shader on synthetic maps, and
// its error against the ray-traced truth under spots, suns and point lights of every size.
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

using Sets = std::vector<std::pair<std::string, std::string>>;

struct Case {
    std::string name;
    Scene scene;
};

// The analytic lights: spots of radius 0.1 to 1.5, a 6-degree sun, point lights of radius
// 0.1 to 0.5 low over the spheres.
std::vector<Case> analyticCases() {
    std::vector<Case> cases;
    for (float r : {0.1f, 0.5f, 1.5f})
        cases.push_back({fmt::format("spot {}", r), sphereOverPlane(acceptanceSpot(r))});
    cases.push_back({"sun 6", sphereOverPlane(acceptanceSun(6.0f))});
    for (float r : {0.1f, 0.3f, 0.5f})
        cases.push_back({fmt::format("point {}", r), spheresOverPlane({.name = "bulb",
                                                                       .type = LightType::Point,
                                                                       .position = {0, 1.2f, 0},
                                                                       .radius = r})});
    return cases;
}

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

// The analytic set-ups at 384x384 against the truth (128 rays a pixel): at its defaults
// smrt beats pcss wherever pcss's planar-blocker estimate fails (a wide spot, a sun, close
// bulbs) and stays below it everywhere, with no acne or leak beyond its reach; its noise filter
// (smrt.filter) helps where penumbrae are wide and costs little where they are narrow; with many
// rays and samples it converges to the truth, which only a correct march does.
TEST_F(QualityTest, SmrtFollowsTheTruthUnderEveryLight) {
    for (Case& c : analyticCases()) {
        const Truth t = groundTruth(c.scene, {.width = 384, .height = 384, .samples = 128});
        const double pcss = errorOf(t, renderRow(t, Technique::Pcss, {})).rmse;
        const RenderResult r = renderRow(t, Technique::Smrt, {});
        const ErrorMetrics smrt = errorOf(t, r);
        const ErrorMetrics beyond = errorBeyondBlur(t, r, Technique::Smrt);
        const double everyPixel =
            errorOf(t, renderRow(t, Technique::Smrt, {{"smrt.checkerboard", "false"}})).rmse;
        std::printf("%-10s rmse pcss %.4f smrt %.4f (every pixel traced %.4f); beyond blur acne "
                    "%.3f%% leak %.3f%%\n",
                    c.name.c_str(), pcss, smrt.rmse, everyPixel, 100 * beyond.acneBeyondBlur,
                    100 * beyond.leakBeyondBlur);
        // smrt.checkerboard: half the pixels traced and most of the others filled costs at most
        // this much error (measured: 1.04x, 1.02x and 1.07x under the bulbs, whose 8 rays a pixel
        // differ by 1/8 between neighbours: cubeFillRange 0.3, and cubeFilterWide 8 for the rays
        // the checkerboard does not trace; 1.00x-1.05x under spots and the sun, fillRange 0.1).
        EXPECT_LT(smrt.rmse, (c.name.rfind("point", 0) == 0 ? 1.2 : 1.1) * everyPixel) << c.name;
        EXPECT_LT(beyond.acneBeyondBlur, 0.001) << c.name;
        EXPECT_LT(beyond.leakBeyondBlur, 0.001) << c.name;
        EXPECT_LT(smrt.rmse, 0.06) << c.name;
        // Each set-up's measured error (lavapipe) and an eighth more.
        const std::map<std::string, double> measured = {
            {"spot 0.1", 0.0032},  {"spot 0.5", 0.0047},  {"spot 1.5", 0.0067}, {"sun 6", 0.0051},
            {"point 0.1", 0.0114}, {"point 0.3", 0.0116}, {"point 0.5", 0.0178}};
        EXPECT_LT(smrt.rmse, 1.125 * measured.at(c.name)) << c.name;
        // pcss follows the bulbs' penumbrae on their faces up to pcss.cubeRadius (96 texels) and
        // reads 0.029 at radius 0.3 against smrt's 0.012; at 0.5 its estimate fails again.
        if (c.name == "spot 1.5" || c.name == "sun 6" || c.name == "point 0.3" ||
            c.name == "point 0.5")
            EXPECT_LT(smrt.rmse, 0.8 * pcss) << c.name;
        else if (c.name == "point 0.1") // 0.0114 against 0.0133
            EXPECT_LT(smrt.rmse, 0.9 * pcss) << c.name;
        else // 0.0032 against 0.0036, 0.0046 against 0.0097
            EXPECT_LT(smrt.rmse, 0.95 * pcss) << c.name;
        // The filter: measured 0.0081 -> 0.0064 under the wide spot, 0.0359 -> 0.0162 under the
        // bulb (8 rays a pixel on its faces, tolerance 0.7), 0.0030 -> 0.0032 under the narrow
        // spot (32 rays, tolerance 0.15: its range keeps most of a steep penumbra).
        // (Every pixel traced on both sides: the checkerboard's fill averages some noise too.)
        if (c.name == "spot 1.5" || c.name == "point 0.3" || c.name == "spot 0.1") {
            const double unfiltered = errorOf(t, renderRow(t, Technique::Smrt,
                                                           {{"smrt.filter", "0"},
                                                            {"smrt.cubeFilter", "0"},
                                                            {"smrt.checkerboard", "false"}}))
                                          .rmse;
            std::printf("%-10s unfiltered %.4f\n", c.name.c_str(), unfiltered);
            EXPECT_LT(everyPixel, (c.name == "spot 0.1" ? 1.1 : 0.85) * unfiltered) << c.name;
        }
        // The gaps' samples (smrt.cubeGapSamples, off by default since 16 samples a ray cost
        // less for the same error): on the march of 12 samples they were made for, the outer
        // penumbrae no longer read too bright where the long far steps passed a sphere's
        // silhouette. Measured with 256 truth rays: 0.0120 -> 0.0089 and 0.0138 -> 0.0103.
        if (c.name == "point 0.1" || c.name == "point 0.3") {
            auto twelve = [&](const char* gaps) {
                return errorOf(t, renderRow(t, Technique::Smrt,
                                            {{"smrt.cubeSamples", "12"},
                                             {"smrt.cubeAdaptive", "4"},
                                             {"smrt.cubeGapSamples", gaps},
                                             {"smrt.checkerboard", "false"}}))
                    .rmse;
            };
            const double noGaps = twelve("0"), gaps = twelve("3");
            std::printf("%-10s 12 samples a ray: %.4f, with the gaps' samples %.4f\n",
                        c.name.c_str(), noGaps, gaps);
            EXPECT_LT(gaps, 0.9 * noGaps) << c.name;
        }
        if (c.name == "point 0.3" || c.name == "spot 1.5") {
            const double converged = errorOf(t, renderRow(t, Technique::Smrt,
                                                          {{"smrt.rays", "64"},
                                                           {"smrt.samples", "32"},
                                                           {"smrt.cubeRays", "64"},
                                                           {"smrt.cubeSamples", "32"},
                                                           {"smrt.adaptive", "0"},
                                                           {"smrt.cubeAdaptive", "0"},
                                                           {"smrt.filter", "0"},
                                                           {"smrt.cubeFilter", "0"},
                                                           {"smrt.checkerboard", "false"}}))
                                         .rmse;
            std::printf("%-10s converged (64 rays, 32 samples) %.4f\n", c.name.c_str(), converged);
            EXPECT_LT(converged, 0.015) << c.name;
        }
    }
}

// The close bulb (radius 0.3, 1.2 over the spheres): every soft technique within 0.05 of
// the truth. The summed-area members and pcss reach it through their cube faces' own cap
// (<family>.cubeRadius, 96): at their spots' and cascades' caps (pcss 40, the others 64) the
// same faces clip the penumbrae (0.067, 0.047, 0.047 measured), and sdf through its automatic
// resolution (256 voxels on the 60-unit plane: 0.082).
TEST_F(QualityTest, EverySoftTechniqueHoldsUnderACloseBulb) {
    for (Case& c : analyticCases()) {
        if (c.name != "point 0.3")
            continue;
        const Truth t = groundTruth(c.scene, {.width = 384, .height = 384, .samples = 128});
        const std::pair<Technique, const char*> members[] = {
            {Technique::Pcss, "pcss"}, {Technique::Vssm, "vssm"}, {Technique::MsmSoft, "msm-soft"}};
        for (const auto& [technique, family] : members) {
            const double atDefaults = errorOf(t, renderRow(t, technique, {})).rmse;
            const std::string maxRadius =
                fmt::format("{}", ParameterValues().number(std::string(family) + ".maxRadius"));
            const double clipped =
                errorOf(t,
                        renderRow(t, technique, {{std::string(family) + ".cubeRadius", maxRadius}}))
                    .rmse;
            std::printf("%-9s rmse %.4f; at its maxRadius (%s) on the faces %.4f\n", family,
                        atDefaults, maxRadius.c_str(), clipped);
            EXPECT_LT(atDefaults, 0.05) << family;
            EXPECT_LT(atDefaults, 0.85 * clipped) << family << ": the cube faces' own cap";
        }
        for (const Technique technique : {Technique::Sdf, Technique::Smrt}) {
            const double rmse = errorOf(t, renderRow(t, technique, {})).rmse;
            std::printf("%-9s rmse %.4f\n", std::string(techniqueName(technique)).c_str(), rmse);
            EXPECT_LT(rmse, 0.05) << techniqueName(technique);
        }
    }
}

// sdf under the widest bulb (radius 0.5, 24.6 degrees seen from the ground below it): the trace
// must not take the receiver's own thickened surface for an occluder (ownSurface), which the
// horizon already accounts for; counted, it read 0.85 on fully lit ground within 6 units of the
// light's axis (RMSE 0.087, acne 54% of the lit ground).
TEST_F(QualityTest, DistanceFieldIgnoresTheReceiversOwnSurfaceUnderAWideBulb) {
    for (Case& c : analyticCases()) {
        if (c.name != "point 0.5")
            continue;
        const Truth t = groundTruth(c.scene, {.width = 384, .height = 384, .samples = 64});
        const RenderResult r = renderRow(t, Technique::Sdf, {});
        const ErrorMetrics m = errorOf(t, r);
        const ErrorMetrics beyond = errorBeyondBlur(t, r, Technique::Sdf);
        std::printf("sdf under the radius-0.5 bulb: rmse %.4f, acne %.3f%% (beyond blur %.3f%%)\n",
                    m.rmse, 100 * m.acne, 100 * beyond.acneBeyondBlur);
        EXPECT_LT(m.rmse, 0.045); // 0.0363 measured
        EXPECT_LT(beyond.acneBeyondBlur, 0.002);
    }
}

// smrt.skipLit proves pixels lit from the map's bounds and traces no ray there: a proof, so every
// pixel's visibility is bit for bit the march's, under a spot, a sun's cascades and a bulb's cube
// faces, in frames whose maps hold real casters (the parity test checks that it proves pixels).
// A proof that claims too much shows here, where the shader and its mirror share the maths.
TEST_F(QualityTest, SmrtSkipsOnlyWhatItProvesLit) {
    for (Case& c : analyticCases()) {
        if (c.name != "spot 1.5" && c.name != "sun 6" && c.name != "point 0.1")
            continue;
        auto visibility = [&](const char* skip) {
            // 1000 texels: the bounds' levels 125, 31, 15, 7 and 3 are odd-sized (leftovers).
            RenderOptions o{.width = 256,
                            .height = 256,
                            .shadowMapSize = 1000,
                            .frames = 1,
                            .technique = Technique::Smrt};
            o.parameters.set("smrt.skipLit", skip);
            return sharedRenderer().render(c.scene, o).visibility.at(0);
        };
        const std::vector<float> proven = visibility("true"), marched = visibility("false");
        ASSERT_EQ(proven.size(), marched.size());
        size_t differ = 0, lit = 0;
        for (size_t i = 0; i < proven.size(); ++i) {
            differ += std::memcmp(&proven[i], &marched[i], sizeof(float)) != 0;
            lit += marched[i] == 1.0f;
        }
        std::printf("%-10s %zu of %zu pixels differ (%zu fully lit)\n", c.name.c_str(), differ,
                    proven.size(), lit);
        EXPECT_EQ(differ, 0u) << c.name;
        EXPECT_GT(lit, proven.size() / 4) << c.name;
    }
}

// The march reads its map through the page table: on virtual maps, under a spot and a point
// light, it follows the truth as on whole maps.
TEST_F(QualityTest, SmrtReadsVirtualMaps) {
    for (Case& c : analyticCases()) {
        if (c.name != "spot 0.5" && c.name != "point 0.3")
            continue;
        const Truth t = groundTruth(c.scene, {.width = 256, .height = 256, .samples = 64});
        const double whole = errorOf(t, renderRow(t, Technique::Smrt, {})).rmse;
        const double paged =
            errorOf(t, renderRow(t, Technique::Smrt, {{"virtual.enabled", "true"}})).rmse;
        std::printf("%-10s rmse whole maps %.4f, virtual %.4f\n", c.name.c_str(), whole, paged);
        EXPECT_LT(paged, 1.25 * whole + 0.005) << c.name;
    }
}

// docs/techniques.md's table of every soft technique's error against its cost on the analytic
// set-ups (PENUMBRA_SOFT_TABLE=1 prints it; a measurement, not a check: skipped otherwise). Cost:
// the visibility pass (composite.fused off) and smrt's filter passes, medians of 5 frames after a
// warm-up, in one run so that the ratios hold on a noisy machine; smrt's bounds (built once per
// view, over its texels) after a plus.
TEST_F(QualityTest, SoftTechniquesErrorAgainstCostTable) {
    if (!std::getenv("PENUMBRA_SOFT_TABLE"))
        GTEST_SKIP() << "a measurement: PENUMBRA_SOFT_TABLE=1 prints it";
    // Five frames on lavapipe; a real GPU's sub-millisecond passes want more for a stable median.
    const char* framesText = std::getenv("PENUMBRA_SOFT_TABLE_FRAMES");
    const uint32_t frames = framesText ? static_cast<uint32_t>(std::atoi(framesText)) : 5u;
    struct Row {
        const char* name;
        Technique technique;
        Sets sets;
    };
    const std::vector<Row> rows = {
        {"pcf[box7]", Technique::Pcf, {{"pcf.filter", "box"}, {"pcf.size", "7"}}},
        {"pcss", Technique::Pcss, {}},
        {"vssm", Technique::Vssm, {}},
        {"msm-soft", Technique::MsmSoft, {}},
        {"sdf", Technique::Sdf, {}},
        {"smrt[fast]",
         Technique::Smrt,
         {{"smrt.rays", "16"},
          {"smrt.adaptive", "4"},
          {"smrt.filterTolerance", "0.7"},
          {"smrt.cubeSamples", "12"}}},
        {"smrt", Technique::Smrt, {}},
        {"smrt every pixel", Technique::Smrt, {{"smrt.checkerboard", "false"}}},
        {"smrt gaps", Technique::Smrt, {{"smrt.cubeGapSamples", "3"}}},
        {"smrt gaps everywhere",
         Technique::Smrt,
         {{"smrt.gapSamples", "3"}, {"smrt.cubeGapSamples", "3"}}},
        {"smrt unfiltered", Technique::Smrt, {{"smrt.filter", "0"}, {"smrt.cubeFilter", "0"}}},
        {"smrt +4 samples", Technique::Smrt, {{"smrt.samples", "12"}, {"smrt.cubeSamples", "17"}}},
        {"smrt 2x rays", Technique::Smrt, {{"smrt.rays", "64"}, {"smrt.cubeRays", "16"}}},
        {"smrt 4x rays",
         Technique::Smrt,
         {{"smrt.rays", "64"}, {"smrt.cubeRays", "32"}, {"smrt.adaptive", "16"}}}};
    std::vector<Case> cases = analyticCases();
    cases.push_back({"sun 2", sphereOverPlane(acceptanceSun(2.0f))});
    // PENUMBRA_SOFT_TABLE_CASES="point 0.3,point 0.5" measures those lines alone.
    const char* only = std::getenv("PENUMBRA_SOFT_TABLE_CASES");
    for (Case& c : cases) {
        if (only && std::string(only).find(c.name) == std::string::npos)
            continue;
        const Truth t = groundTruth(c.scene, {.width = 384, .height = 384, .samples = 256});
        std::printf("| %s |", c.name.c_str());
        for (const Row& row : rows) {
            Sets sets = row.sets;
            sets.emplace_back("composite.fused", "false");
            RenderOptions o{.width = t.setup.width,
                            .height = t.setup.height,
                            .shadowMapSize = t.setup.shadowMapSize,
                            .frames = std::max(frames, 1u),
                            .technique = row.technique};
            for (const auto& [key, value] : sets)
                o.parameters.set(key, value);
            const RenderResult r = sharedRenderer().render(t.scene, o);
            double ms = 0.0;   // the visibility pass and smrt's filter, the per-pixel work
            double maps = 0.0; // smrt's bounds, built over every texel of every view
            for (const PassTime& p : r.passes) {
                if (p.pass == "visibility" || p.pass == "filter")
                    ms += p.medianMs;
                if (p.pass.rfind("smrt_bounds", 0) == 0)
                    maps += p.medianMs;
            }
            const std::string bounds = maps <= 0.0  ? ""
                                       : maps < 1.0 ? fmt::format(" + {:.3f}", maps)
                                                    : fmt::format(" + {:.1f}", maps);
            std::printf(ms < 1.0 ? " %.4f (%.3f%s ms) |" : " %.4f (%.1f%s ms) |",
                        errorOf(t, r).rmse, ms, bounds.c_str());
            std::fflush(stdout);
        }
        std::printf("\n");
    }
}

// A table (a top 0.9 high on four legs) with a ball on it and a post beside it, over a floor:
// contact shadows at the legs and the post's foot, a thin top whose shadow the ball's overlaps.
Scene tableUnder(const Light& light) {
    Scene scene;
    scene.name = "table";
    MeshBuilder mb(scene);
    const float g = 10.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("floor", {0.7f, 0.7f, 0.7f}));
    const uint32_t wood = mb.material("wood", {0.6f, 0.45f, 0.3f});
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, 0.9f, 0.0f}), {2.0f, 0.08f, 1.2f}),
           wood);
    for (const glm::vec2 leg :
         {glm::vec2(-0.9f, -0.5f), {0.9f, -0.5f}, {-0.9f, 0.5f}, {0.9f, 0.5f}})
        mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {leg.x, 0.43f, leg.y}),
                          {0.08f, 0.86f, 0.08f}),
               wood);
    mb.tube({1.6f, 0.0f, 1.0f}, {1.6f, 2.6f, 1.0f}, 0.1f, wood, 24);
    mb.sphere({-0.4f, 1.25f, 0.1f}, 0.3f, wood);
    scene.lights.push_back(light);
    scene.cameras.push_back({.name = "above",
                             .position = {2.5f, 5.0f, 5.5f},
                             .target = {0.0f, 0.3f, 0.0f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

// The lights over tableUnder: a spot of radius 0.5 above and aside, a bulb of radius 0.3 above
// the table and a 4-degree sun.
std::array<Light, 3> tableLights() {
    return {Light{.name = "spot",
                  .type = LightType::Spot,
                  .position = {1.0f, 5.0f, 1.0f},
                  .direction = glm::normalize(glm::vec3(-1.0f, -5.0f, -1.0f)),
                  .intensity = 40.0f,
                  .outerConeAngle = 0.8f,
                  .radius = 0.5f},
            Light{.name = "bulb",
                  .type = LightType::Point,
                  .position = {0.5f, 3.2f, 0.8f},
                  .intensity = 8.0f,
                  .radius = 0.3f},
            Light{.name = "sun",
                  .type = LightType::Directional,
                  .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.25f)),
                  .angularDiameter = 4.0f}};
}

// Beyond the spheres over a plane: builtin:room (a bulb of radius 0.1 lighting a room through six
// faces), objects resting on a plane (contact) and a table with a ball on it, under a bulb and a
// spot. smrt at its defaults stays below pcss and has no acne or leak beyond its blur. Under a
// 4-degree sun over the table it reads above pcss (0.0091 against 0.0068): both are far below
// 0.02, and docs/techniques.md says so. In the room pcss met smrt (0.0139 both) when the crease
// rule took its acne off the room's wall creases (pcss was over 5% above before).
TEST_F(QualityTest, SmrtBeatsPcssBeyondTheSpheres) {
    const auto [spot, bulb, sun] = tableLights();
    struct Setup {
        std::string name;
        Scene scene;
        double measured; // smrt's RMSE on lavapipe
        bool belowPcss;
    };
    const Setup setups[] = {{"room", loadScene("builtin:room"), 0.0139, false},
                            {"resting, bulb", restingObjects(bulb), 0.0332, true},
                            {"resting, spot", restingObjects(spot), 0.0157, true},
                            {"table, spot", tableUnder(spot), 0.0138, true},
                            {"table, bulb", tableUnder(bulb), 0.0104, true},
                            {"table, sun", tableUnder(sun), 0.0091, false}};
    for (const Setup& c : setups) {
        const Truth t = groundTruth(c.scene, {.width = 256, .height = 256, .samples = 128});
        const double pcss = errorOf(t, renderRow(t, Technique::Pcss, {})).rmse;
        const RenderResult r = renderRow(t, Technique::Smrt, {});
        const double smrt = errorOf(t, r).rmse;
        const ErrorMetrics beyond = errorBeyondBlur(t, r, Technique::Smrt);
        std::printf("%-14s rmse pcss %.4f smrt %.4f; beyond blur acne %.3f%% leak %.3f%%\n",
                    c.name.c_str(), pcss, smrt, 100 * beyond.acneBeyondBlur,
                    100 * beyond.leakBeyondBlur);
        EXPECT_LT(smrt, 1.15 * c.measured) << c.name;
        if (c.belowPcss) {
            EXPECT_LT(smrt, 0.95 * pcss) << c.name;
        }
        EXPECT_LT(beyond.acneBeyondBlur, 0.001) << c.name;
        EXPECT_LT(beyond.leakBeyondBlur, 0.001) << c.name;
    }
}

// Casters stacked over one another: the table under a slatted roof (slats 0.15 wide, 0.25 apart,
// 1.3 above the table top). Rays from under the table rise through the table top where a slat
// hides it and come out between two slats: without smrt.hidden they count as lit (half the umbra
// under a spot or a bulb); with it the table top is continued under the slat and blocks them. It
// is on by default under every light (smrt.hidden, smrt.cubeHidden).
TEST_F(QualityTest, SmrtHiddenSurfacesStopTheStackedCastersLeak) {
    const auto [spot, bulb, sun] = tableLights();
    for (const Light& light : {spot, bulb, sun}) {
        Scene scene = tableUnder(light);
        MeshBuilder mb(scene);
        const uint32_t wood = mb.material("slats", {0.6f, 0.45f, 0.3f});
        for (int i = -6; i <= 6; ++i)
            mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0.25f * float(i), 2.2f, 0.0f}),
                              {0.15f, 0.05f, 3.0f}),
                   wood);
        const Truth t = groundTruth(scene, {.width = 256, .height = 256, .samples = 128});
        const RenderResult shown =
            renderRow(t, Technique::Smrt, {{"smrt.hidden", "false"}, {"smrt.cubeHidden", "false"}});
        const RenderResult hidden =
            renderRow(t, Technique::Smrt, {{"smrt.hidden", "true"}, {"smrt.cubeHidden", "true"}});
        // The defaults: hidden surfaces under every light.
        const RenderResult defaults = renderRow(t, Technique::Smrt, {});
        const std::vector<float>& expected = hidden.visibility.at(0);
        ASSERT_EQ(expected.size(), defaults.visibility.at(0).size());
        EXPECT_EQ(0, std::memcmp(expected.data(), defaults.visibility.at(0).data(),
                                 expected.size() * sizeof(float)))
            << light.name << ": the defaults' visibility";
        const double pcss = errorOf(t, renderRow(t, Technique::Pcss, {})).rmse;
        const double before = errorOf(t, shown).rmse, after = errorOf(t, hidden).rmse;
        const double leakBefore = errorBeyondBlur(t, shown, Technique::Smrt).leakBeyondBlur;
        const double leakAfter = errorBeyondBlur(t, hidden, Technique::Smrt).leakBeyondBlur;
        std::printf("%-5s rmse pcss %.4f smrt %.4f, smrt.hidden %.4f; leak beyond blur %.3f%% -> "
                    "%.3f%%\n",
                    light.name.c_str(), pcss, before, after, 100 * leakBefore, 100 * leakAfter);
        // Measured: leaks 54.9% -> 13.2% (spot), 53.2% -> 11.9% (bulb), 7.3% -> 0.28% (sun).
        EXPECT_GT(leakBefore, 0.05) << light.name << ": the leak this guards";
        EXPECT_LT(leakAfter, 0.3 * leakBefore) << light.name;
        EXPECT_LT(after, before) << light.name;
        // Under the sun smrt stays above pcss here (0.0272 against 0.0165), though its leak
        // beyond the blur is gone (0.28%).
        if (light.type != LightType::Directional) {
            EXPECT_LT(after, pcss) << light.name;
        }
    }
}
