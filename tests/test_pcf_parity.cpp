// CPU reference vs GPU for every shadow-map filter, on synthetic shadow maps: the visibility
// pass's own filter code (Renderer::probeTechnique) against each module's CPU reference
// (src/shadows/).
#include "gpu_fixture.h"
#include "render/frame_data.h"
#include "shadows/technique.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kMapSize = 96;

// Depth that varies smoothly, with box-shaped occluders closer to the light on top.
std::vector<float> syntheticMap(uint32_t seed) {
    std::mt19937 engine(seed);
    auto rng = [&] { return static_cast<uint32_t>(engine()); };
    std::vector<float> depth(kMapSize * kMapSize);
    for (uint32_t j = 0; j < kMapSize; ++j)
        for (uint32_t i = 0; i < kMapSize; ++i)
            depth[j * kMapSize + i] =
                0.55f + 0.15f * std::sin(0.21f * float(i)) * std::cos(0.17f * float(j));
    for (int b = 0; b < 24; ++b) {
        const uint32_t x0 = rng() % kMapSize, y0 = rng() % kMapSize, w = 2 + rng() % 12,
                       h = 2 + rng() % 12;
        const float d = 0.2f + 0.25f * float(rng() % 1000) / 1000.0f;
        for (uint32_t y = y0; y < std::min(y0 + h, kMapSize); ++y)
            for (uint32_t x = x0; x < std::min(x0 + w, kMapSize); ++x)
                depth[y * kMapSize + x] = d;
    }
    return depth;
}

// withAdaptive: bias.mode=adaptive's per-tap terms too (a curvature lift of up to ~3e-3 light
// depth a few texels out, and a reach that clamps the plane's correction).
std::vector<FilterProbe> syntheticProbes(uint32_t seed, bool withGradient,
                                         bool withAdaptive = false) {
    std::mt19937 engine(seed);
    auto rng = [&] { return static_cast<uint32_t>(engine()); };
    auto unit = [&] { return float(rng() >> 8) / 16777216.0f; };
    std::vector<FilterProbe> probes(3000);
    for (FilterProbe& p : probes) {
        p.uv = {0.02f + 0.96f * unit(), 0.02f + 0.96f * unit()};
        p.depth = 0.25f + 0.5f * unit();
        // Gradients up to 0.5 depth per uv unit: a few texels give corrections of ~1e-2.
        if (withGradient)
            p.gradient = {unit() - 0.5f, unit() - 0.5f};
        p.pixel = {rng() % 1920, rng() % 1080};
        if (withAdaptive) {
            p.curve = {60.0f * unit(), 0.5f * unit()};
            p.planeRange = {-1e30f, 0.02f * unit()};
            // The crease rule: the map's waves rise up to ~8 depth per uv, its blocks' edges far
            // more; limits from 0 (off) to 40 take some gathers as planes and leave others.
            p.creaseLimit = 40.0f * unit();
        }
    }
    return probes;
}

struct Variant {
    std::string name;
    Technique technique;
    std::vector<std::string> sets;
};

std::vector<Variant> everyVariant() {
    std::vector<Variant> v{
        {"hard", Technique::Hard, {}},
        {"second-depth", Technique::SecondDepth, {}},
        {"bilinear", Technique::Pcf, {"pcf.filter=bilinear"}},
        {"hardware", Technique::Pcf, {"pcf.filter=hardware"}},
        // Adaptive bias lifts the hardware tap's one reference depth.
        {"hardware-adaptive", Technique::Pcf, {"pcf.filter=hardware", "bias.mode=adaptive"}}};
    for (int n = 3; n <= 15; n += 2) {
        v.push_back({"box" + std::to_string(n),
                     Technique::Pcf,
                     {"pcf.filter=box", "pcf.size=" + std::to_string(n)}});
        v.push_back({"gauss" + std::to_string(n),
                     Technique::Pcf,
                     {"pcf.filter=gaussian", "pcf.size=" + std::to_string(n)}});
    }
    v.push_back(
        {"gauss9-sigma1", Technique::Pcf, {"pcf.filter=gaussian", "pcf.size=9", "pcf.sigma=1"}});
    for (const char* rotation : {"none", "random", "ign"})
        for (int samples : {1, 7, 16, 32, 64})
            v.push_back({std::string("poisson") + std::to_string(samples) + "-" + rotation,
                         Technique::Pcf,
                         {"pcf.filter=poisson", "pcf.samples=" + std::to_string(samples),
                          std::string("pcf.rotation=") + rotation, "pcf.radius=3.5"}});
    v.push_back(
        {"adaptive-box7", Technique::Pcf, {"pcf.filter=box", "pcf.size=7", "pcf.adaptive=true"}});
    v.push_back({"adaptive-gauss5",
                 Technique::Pcf,
                 {"pcf.filter=gaussian", "pcf.size=5", "pcf.adaptive=true"}});
    v.push_back(
        {"adaptive-poisson16", Technique::Pcf, {"pcf.filter=poisson", "pcf.adaptive=true"}});
    return v;
}

// Whether the GPU's answer `gpu` at `probe` is the CPU's answer for the probe moved by the
// device's sub-texel precision (2^-subTexelPrecisionBits of a texel) along u or v, where that
// move changes the CPU's answer: a tap that close to a texel's edge may land on either side,
// since a gather picks its texels from a fixed-point coordinate and the GPU's tap positions round
// differently from the CPU's (an H200 put one tap of a randomly rotated Poisson disk 1e-4 texel
// across an edge, and read one probe of 3000 lit where the CPU read 6/7).
template <class Reference>
bool onTexelEdge(const FilterProbe& probe, float cpu, float gpu, const Reference& reference,
                 const DeviceInfo& device, float tolerance) {
    const float step =
        std::ldexp(1.0f, -static_cast<int>(device.subTexelPrecisionBits)) / float(kMapSize);
    for (const glm::vec2 direction :
         {glm::vec2(1, 0), glm::vec2(-1, 0), glm::vec2(0, 1), glm::vec2(0, -1)}) {
        FilterProbe moved = probe;
        moved.uv += step * direction;
        const float there = reference(moved);
        if (std::abs(there - cpu) > tolerance && std::abs(there - gpu) <= tolerance)
            return true;
    }
    return false;
}

} // namespace

TEST_F(FilterTest, EveryFilterMatchesItsCpuReference) {
    const DeviceInfo& device = sharedRenderer().device();
    const std::vector<float> depth = syntheticMap(11);
    const shadows::ShadowMapView map{depth, kMapSize};
    for (int kind = 0; kind < 3; ++kind) {
        const bool gradient = kind > 0, adaptive = kind == 2;
        const std::vector<FilterProbe> probes =
            syntheticProbes(gradient ? 5 + kind : 3, gradient, adaptive);
        for (const Variant& variant : everyVariant()) {
            ParameterValues params;
            for (const std::string& set : variant.sets)
                params.assign(set);
            const std::vector<glm::vec4> gpu =
                sharedRenderer().probeTechnique(variant.technique, params, depth, kMapSize, probes);
            const gpu::ShadowViewData light = render::probeViewData({});
            // The subTexelPrecisionBits the CPU emulates only matter with hardware filtering.
            const shadows::FilterSettings frame =
                shadows::filterSettings(shadows::moduleOf(variant.technique), params,
                                        device.depthLinearFilter, device.subTexelPrecisionBits);
            const bool hardwareTap = variant.name.rfind("hardware", 0) == 0;
            // The CPU rounds the device's steps; the device may truncate them.
            const float tolerance =
                1e-3f + (hardwareTap ? static_cast<float>(hardwareFilterTolerance()) : 0.0f);
            const auto reference = [&](const FilterProbe& probe) {
                return shadows::techniqueReference(variant.technique, map, probe, frame, light).x;
            };
            float worst = 0.0f;
            size_t compared = 0, onEdges = 0;
            for (size_t i = 0; i < probes.size(); ++i) {
                // A tie within float rounding may flip one comparison on either side.
                if (shadows::smallestComparisonMargin(variant.technique, map, probes[i], frame,
                                                      light) < 1e-5f)
                    continue;
                ++compared;
                const float cpu = reference(probes[i]);
                if (std::abs(cpu - gpu[i].x) > tolerance &&
                    onTexelEdge(probes[i], cpu, gpu[i].x, reference, device, tolerance)) {
                    ++onEdges;
                    continue;
                }
                if (std::abs(cpu - gpu[i].x) > tolerance) // what a failure shows
                    std::printf("%s kind %d: probe %zu (pixel %u,%u) gpu %.6f cpu %.6f\n",
                                variant.name.c_str(), kind, i, probes[i].pixel.x, probes[i].pixel.y,
                                gpu[i].x, cpu);
                worst = std::max(worst, std::abs(cpu - gpu[i].x));
            }
            EXPECT_GT(compared, probes.size() * 9 / 10) << variant.name;
            EXPECT_LE(onEdges, probes.size() / 200) << variant.name << ": taps on texel edges";
            EXPECT_LE(worst, tolerance)
                << variant.name << (gradient ? " with" : " without") << " receiver-plane gradient"
                << (adaptive ? " and adaptive terms" : "");
        }
    }
}

TEST_F(FilterTest, FiltersAreFractionalAndReachBothExtremes) {
    // A kernel over a real edge must produce in-between values (it filters) and still report
    // fully lit and fully shadowed receivers exactly.
    const std::vector<float> depth = syntheticMap(11);
    const std::vector<FilterProbe> probes = syntheticProbes(3, false);
    ParameterValues params;
    params.assign("pcf.filter=box");
    params.assign("pcf.size=7");
    const std::vector<glm::vec4> v =
        sharedRenderer().probeTechnique(Technique::Pcf, params, depth, kMapSize, probes);
    size_t zero = 0, one = 0, between = 0;
    for (const glm::vec4& x : v)
        (x.x == 0.0f ? zero : x.x == 1.0f ? one : between) += 1;
    EXPECT_GT(zero, 50u);
    EXPECT_GT(one, 50u);
    EXPECT_GT(between, 200u);
}

TEST_F(FilterTest, PcssBlockerSearchAndPenumbraMatchTheCpuReference) {
    // Both light models, both sizes of light, with and without rotation: the average blocker
    // depth, the number of blocking texels and the filter radius agree, not only the result.
    const std::vector<float> depth = syntheticMap(17);
    const shadows::ShadowMapView map{depth, kMapSize};
    const ProbeLight lights[] = {{.perspective = false,
                                  .size = std::tan(0.5f * 0.2f),
                                  .nearPlane = 1.0f,
                                  .farPlane = 21.0f,
                                  .worldPerUv = {12.0f, 12.0f}},
                                 {.perspective = true,
                                  .size = 0.8f,
                                  .nearPlane = 2.0f,
                                  .farPlane = 30.0f,
                                  .worldPerUv = {1.2f, 1.2f}},
                                 // A point light's cube face: its own cap (pcss.cubeRadius).
                                 {.perspective = true,
                                  .size = 0.8f,
                                  .nearPlane = 2.0f,
                                  .farPlane = 30.0f,
                                  .worldPerUv = {1.2f, 1.2f},
                                  .cubeFace = true}};
    for (const ProbeLight& probeLight : lights)
        for (const char* rotation : {"none", "ign"}) {
            ParameterValues params;
            params.set("pcss.rotation", rotation);
            params.assign("pcss.maxRadius=24");
            params.assign("pcss.cubeRadius=3");
            const float cap = probeLight.cubeFace ? 3.0f : 24.0f;
            // The blocker search and the filter both test taps: with the adaptive mode's
            // per-tap terms on the rotated runs.
            const std::vector<FilterProbe> probes =
                syntheticProbes(23, true, std::string(rotation) == "ign");
            const std::vector<glm::vec4> gpuResult = sharedRenderer().probeTechnique(
                Technique::Pcss, params, depth, kMapSize, probes, probeLight);
            const shadows::FilterSettings frame =
                shadows::filterSettings(shadows::moduleOf(Technique::Pcss), params, false, 8);
            const gpu::ShadowViewData light = render::probeViewData(probeLight);
            glm::vec4 worst(0.0f);
            size_t compared = 0, searched = 0, capped = 0;
            float widest = 0.0f;
            for (size_t i = 0; i < probes.size(); ++i) {
                if (shadows::smallestComparisonMargin(Technique::Pcss, map, probes[i], frame,
                                                      light) < 1e-5f)
                    continue;
                ++compared;
                const glm::vec4 cpu =
                    shadows::techniqueReference(Technique::Pcss, map, probes[i], frame, light);
                searched += cpu.z > 0.0f;
                widest = std::max(widest, gpuResult[i].w);
                capped += gpuResult[i].w == cap;
                // Depths and radii relative to their size; counts exactly.
                worst = glm::max(worst, glm::abs(cpu - gpuResult[i]) /
                                            glm::max(glm::vec4(1.0f, 1.0f, 1.0f, std::abs(cpu.w)),
                                                     glm::vec4(1.0f)));
            }
            const std::string what = std::string(probeLight.cubeFace      ? "cube face"
                                                 : probeLight.perspective ? "perspective"
                                                                          : "ortho") +
                                     ", rotation " + rotation;
            // The filter radius stops at this view's cap, and wide penumbrae reach it.
            // The filter radius stops at this view's cap: the synthetic penumbrae (up to 10
            // texels) reach a cube face's 3, not the others' 24.
            EXPECT_LE(widest, cap) << what;
            if (probeLight.cubeFace) {
                EXPECT_GT(capped, 20u) << what << ": penumbrae at the cap";
            }
            EXPECT_GT(compared, probes.size() * 8 / 10) << what;
            EXPECT_GT(searched, probes.size() / 4) << what << ": blockers must be found";
            EXPECT_LE(worst.x, 1e-3f) << what << ": visibility";
            EXPECT_LE(worst.y, 1e-5f) << what << ": average blocker depth";
            EXPECT_EQ(worst.z, 0.0f) << what << ": blocking texel count";
            EXPECT_LE(worst.w, 1e-4f) << what << ": filter radius (relative)";
        }
}
