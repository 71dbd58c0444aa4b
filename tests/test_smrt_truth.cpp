// Shadow-map ray tracing (`smrt`) against the ray-traced truth under spots, suns and point
// lights of every size, beside the other soft techniques. Its CPU reference against the shader
// is in test_smrt.cpp.
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

} // namespace

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
