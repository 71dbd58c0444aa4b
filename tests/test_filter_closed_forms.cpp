// Every filter against answers that do not come from its CPU mirror: closed forms on synthetic
// maps (a straight occluder edge, a constant map, a checkerboard, a receiver tilted against a flat
// occluder) and equalities that must hold between variants. A bug written into both the shader
// and its module's CPU reference (src/shadows/) passes the parity test; it fails these, which
// check both sides.
//
// Texel coordinates: texel i spans [i, i + 1) and has its centre at i + 1/2; a probe at texel
// position x has u = x / size. A bilinear comparison tap at x over a step whose tests change
// between texels k - 1 and k reads the ramp clamp(x - k + 1/2, 0, 1) (seed 000's 4-tap with
// texel centres); an n-tap box of such taps one texel apart, centred on x, reads
// clamp((x - k + 1/2 + (n - 1)/2) / n, 0, 1), the unit ramps tiling a ramp n texels wide.
#include "gpu_fixture.h"
#include "render/frame_data.h"
#include "shadows/poisson.h"
#include "shadows/technique.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kSize = 64;
constexpr int kEdge = 32;           // texels i < kEdge hold the occluder
constexpr float kOccluder = 0.25f;  // occluder depth
constexpr float kFloor = 0.75f;     // depth where nothing occludes
constexpr float kReceiver = 0.5f;   // receiver depth: behind the occluder, in front of the floor
constexpr double kTolerance = 2e-4; // float arithmetic of the kernels' weights

std::vector<float> edgeMap() {
    std::vector<float> d(kSize * kSize);
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
            d[j * kSize + i] = static_cast<int>(i) < kEdge ? kOccluder : kFloor;
    return d;
}

FilterProbe probeAt(double x, double y, float depth = kReceiver, glm::vec2 gradient = {},
                    glm::uvec2 pixel = {}) {
    return {.uv = glm::vec2(static_cast<float>(x / kSize), static_cast<float>(y / kSize)),
            .depth = depth,
            .gradient = gradient,
            .pixel = pixel};
}

// Probes across the edge, 25 texels wide, at positions that avoid no special offsets (the closed
// forms are continuous), on three rows away from the map's border.
std::vector<FilterProbe> probesAcrossTheEdge(double halfWidth = 12.0) {
    std::vector<FilterProbe> probes;
    for (double y : {20.3, 31.77, 44.5})
        for (double x = kEdge - halfWidth; x <= kEdge + halfWidth; x += 0.0937)
            probes.push_back(probeAt(x, y, kReceiver, {}, {uint32_t(x * 7), uint32_t(y * 3)}));
    return probes;
}

double texelX(const FilterProbe& p) {
    return static_cast<double>(p.uv.x) * kSize;
}

double ramp(double x) {
    return std::clamp(x - kEdge + 0.5, 0.0, 1.0);
}

ParameterValues parameters(std::initializer_list<const char*> sets) {
    ParameterValues p;
    for (const char* s : sets)
        p.assign(s);
    return p;
}

struct Evaluated {
    std::vector<glm::vec4> gpu, cpu;
};

// The technique on the GPU (the visibility pass's code) and on the CPU (its mirror).
Evaluated evaluate(Technique technique, const ParameterValues& params,
                   const std::vector<float>& map, const std::vector<FilterProbe>& probes,
                   const ProbeLight& light = {}) {
    Evaluated e;
    e.gpu = sharedRenderer().probeTechnique(technique, params, map, kSize, probes, light);
    const shadows::FilterSettings frame = shadows::filterSettings(
        shadows::moduleOf(technique), params, sharedRenderer().device().depthLinearFilter,
        sharedRenderer().device().subTexelPrecisionBits);
    const gpu::ShadowViewData viewData = render::probeViewData(light);
    for (const FilterProbe& p : probes)
        e.cpu.push_back(shadows::techniqueReference(technique, {map, kSize}, p, frame, viewData));
    return e;
}

// Both sides of `technique` against `expected` (the visibility) at every probe; at least
// `minBetweenShare` of the probes must expect a value strictly between 0 and 1.
void expectClosedForm(const std::string& what, Technique technique, const ParameterValues& params,
                      const std::vector<float>& map, const std::vector<FilterProbe>& probes,
                      const std::function<double(const FilterProbe&)>& expected,
                      double tolerance = kTolerance, double minBetweenShare = 0.025) {
    const Evaluated e = evaluate(technique, params, map, probes);
    double worstGpu = 0, worstCpu = 0;
    size_t worstAt = 0, between = 0;
    for (size_t i = 0; i < probes.size(); ++i) {
        const double want = expected(probes[i]);
        between += want > 0.01 && want < 0.99;
        const double g = std::abs(e.gpu[i].x - want), c = std::abs(e.cpu[i].x - want);
        if (std::max(g, c) > std::max(worstGpu, worstCpu))
            worstAt = i;
        worstGpu = std::max(worstGpu, g), worstCpu = std::max(worstCpu, c);
    }
    const FilterProbe& p = probes[worstAt];
    EXPECT_LE(worstGpu, tolerance) << what << " (GPU), worst at texel x " << texelX(p)
                                   << ": expected " << expected(p) << ", got " << e.gpu[worstAt].x;
    EXPECT_LE(worstCpu, tolerance) << what << " (CPU reference), worst at texel x " << texelX(p)
                                   << ": expected " << expected(p) << ", got " << e.cpu[worstAt].x;
    EXPECT_GE(static_cast<double>(between), minBetweenShare * static_cast<double>(probes.size()))
        << what << ": the probes must cross the penumbra";
}

double hardwareTolerance() {
    return kTolerance + hardwareFilterTolerance();
}

} // namespace

TEST_F(FilterTest, BilinearAndHardwareTapsReadTheRampAcrossAStraightEdge) {
    const std::vector<float> map = edgeMap();
    const std::vector<FilterProbe> probes = probesAcrossTheEdge(3.0);
    auto want = [](const FilterProbe& p) { return ramp(texelX(p)); };
    expectClosedForm("bilinear", Technique::Pcf, parameters({"pcf.filter=bilinear"}), map, probes,
                     want);
    expectClosedForm("hardware", Technique::Pcf, parameters({"pcf.filter=hardware"}), map, probes,
                     want, hardwareTolerance());
}

TEST_F(FilterTest, BoxKernelsReadARampTheirWidthAcrossAStraightEdge) {
    const std::vector<float> map = edgeMap();
    const std::vector<FilterProbe> probes = probesAcrossTheEdge();
    for (int n = 3; n <= 15; n += 2)
        for (const char* adaptive : {"false", "true"}) {
            // Edge-only PCF decides away from a straight edge exactly where the full kernel
            // reads 0 or 1, so both read the same ramp.
            const ParameterValues params =
                parameters({"pcf.filter=box", ("pcf.size=" + std::to_string(n)).c_str(),
                            (std::string("pcf.adaptive=") + adaptive).c_str()});
            expectClosedForm("box" + std::to_string(n) + " adaptive=" + adaptive, Technique::Pcf,
                             params, map, probes, [n](const FilterProbe& p) {
                                 const double h = 0.5 * (n - 1);
                                 return std::clamp((texelX(p) - kEdge + 0.5 + h) / n, 0.0, 1.0);
                             });
        }
}

TEST_F(FilterTest, GaussianKernelsWeighTheirTapsByTheNormalDensity) {
    const std::vector<float> map = edgeMap();
    const std::vector<FilterProbe> probes = probesAcrossTheEdge();
    struct Case {
        int n;
        double sigma; // 0: the documented default, size / 4
    };
    for (const Case c : {Case{5, 0.0}, Case{7, 0.0}, Case{9, 1.3}, Case{15, 0.0}, Case{11, 6.0}}) {
        const double sigma = c.sigma > 0 ? c.sigma : c.n / 4.0;
        const ParameterValues params =
            parameters({"pcf.filter=gaussian", ("pcf.size=" + std::to_string(c.n)).c_str(),
                        ("pcf.sigma=" + std::to_string(c.sigma)).c_str()});
        expectClosedForm("gaussian" + std::to_string(c.n) + " sigma " + std::to_string(sigma),
                         Technique::Pcf, params, map, probes, [&](const FilterProbe& p) {
                             double sum = 0, weights = 0;
                             for (int j = -(c.n - 1) / 2; j <= (c.n - 1) / 2; ++j) {
                                 const double w = std::exp(-0.5 * j * j / (sigma * sigma));
                                 sum += w * ramp(texelX(p) + j), weights += w;
                             }
                             return sum / weights;
                         });
    }
}

TEST_F(FilterTest, PoissonTapsAverageTheRampAtTheirRotatedOffsets) {
    const std::vector<float> map = edgeMap();
    const std::vector<FilterProbe> probes = probesAcrossTheEdge();
    const auto& disk = poissonDisk();
    // Interleaved gradient noise [Jimenez 2014], in turns.
    auto ign = [](glm::uvec2 q) {
        const double inner = 0.06711056 * q.x + 0.00583715 * q.y;
        const double v = 52.9829189 * (inner - std::floor(inner));
        return v - std::floor(v);
    };
    for (const char* rotation : {"none", "ign"})
        for (int samples : {1, 9, 16, 64})
            for (double radius : {1.5, 4.0}) {
                const ParameterValues params = parameters(
                    {"pcf.filter=poisson", ("pcf.samples=" + std::to_string(samples)).c_str(),
                     ("pcf.radius=" + std::to_string(radius)).c_str(),
                     (std::string("pcf.rotation=") + rotation).c_str()});
                const bool rotated = std::string(rotation) == "ign";
                expectClosedForm(
                    "poisson" + std::to_string(samples) + " radius " + std::to_string(radius) +
                        " rotation " + rotation,
                    Technique::Pcf, params, map, probes,
                    [&](const FilterProbe& p) {
                        const double a = rotated ? 2.0 * M_PI * ign(p.pixel) : 0.0;
                        double sum = 0;
                        for (int i = 0; i < samples; ++i) // only x matters across this edge
                            sum += ramp(texelX(p) + radius * (std::cos(a) * disk[i].x -
                                                              std::sin(a) * disk[i].y));
                        return sum / samples;
                    },
                    // The rotation angle in float, times the radius, moves a tap by ~1e-5 texels.
                    rotated ? 1e-3 : kTolerance);
            }
}

TEST_F(FilterTest, HardPicksTheTexelUnderTheReceiver) {
    const std::vector<float> map = edgeMap();
    std::vector<FilterProbe> probes;
    std::vector<double> want;
    for (double offset : {-0.99, -0.51, -0.49, -0.01, 0.01, 0.49, 0.51, 0.99}) {
        probes.push_back(probeAt(kEdge + offset, 17.5));
        want.push_back(offset < 0 ? 0.0 : 1.0);
    }
    // At the map's far edge: only the last column is free of the occluder.
    std::vector<float> lastColumnFree(kSize * kSize, kOccluder);
    for (uint32_t j = 0; j < kSize; ++j)
        lastColumnFree[j * kSize + kSize - 1] = kFloor;
    const std::vector<FilterProbe> border = {probeAt(kSize, 9.5), probeAt(kSize - 0.01, 9.5),
                                             probeAt(kSize - 1.01, 9.5)};
    const double borderWant[] = {1.0, 1.0, 0.0};
    for (Technique t : {Technique::Hard, Technique::SecondDepth}) {
        const Evaluated e = evaluate(t, {}, map, probes);
        for (size_t i = 0; i < probes.size(); ++i) {
            EXPECT_EQ(e.gpu[i].x, want[i]) << "GPU at texel x " << texelX(probes[i]);
            EXPECT_EQ(e.cpu[i].x, want[i]) << "CPU at texel x " << texelX(probes[i]);
        }
        const Evaluated b = evaluate(t, {}, lastColumnFree, border);
        for (size_t i = 0; i < border.size(); ++i) {
            EXPECT_EQ(b.gpu[i].x, borderWant[i]) << "GPU at texel x " << texelX(border[i]);
            EXPECT_EQ(b.cpu[i].x, borderWant[i]) << "CPU at texel x " << texelX(border[i]);
        }
    }
}

namespace {

// Every variant the registry offers, as parameter sets.
std::vector<std::pair<std::string, ParameterValues>> everyPcfVariant() {
    std::vector<std::pair<std::string, ParameterValues>> v;
    v.emplace_back("bilinear", parameters({"pcf.filter=bilinear"}));
    v.emplace_back("hardware", parameters({"pcf.filter=hardware"}));
    for (const char* filter : {"box", "gaussian"})
        for (int n = 3; n <= 15; n += 4)
            v.emplace_back(std::string(filter) + std::to_string(n),
                           parameters({(std::string("pcf.filter=") + filter).c_str(),
                                       ("pcf.size=" + std::to_string(n)).c_str()}));
    for (const char* rotation : {"none", "random", "ign"})
        v.emplace_back(std::string("poisson-") + rotation,
                       parameters({"pcf.filter=poisson", "pcf.samples=32", "pcf.radius=6",
                                   (std::string("pcf.rotation=") + rotation).c_str()}));
    v.emplace_back("adaptive-box7",
                   parameters({"pcf.filter=box", "pcf.size=7", "pcf.adaptive=true"}));
    return v;
}

} // namespace

TEST_F(FilterTest, AConstantMapIsExactlyLitInFrontAndExactlyShadowedBehind) {
    const std::vector<float> flat(kSize * kSize, 0.5f);
    std::vector<FilterProbe> front, behind;
    for (int i = 0; i < 200; ++i) { // the whole map, borders included (clamp to edge)
        const double x = kSize * std::fmod(0.6180339887 * i, 1.0);
        const double y = kSize * std::fmod(0.7548776662 * i + 0.1, 1.0);
        const glm::uvec2 pixel(i * 13 % 640, i * 7 % 480);
        front.push_back(probeAt(x, y, 0.45f, {}, pixel));
        behind.push_back(probeAt(x, y, 0.55f, {}, pixel));
    }
    auto expectAll = [&](const std::string& what, Technique t, const ParameterValues& params,
                         const ProbeLight& light = {}) {
        for (const auto& [probes, want] : {std::pair(&front, 1.0f), std::pair(&behind, 0.0f)}) {
            const Evaluated e = evaluate(t, params, flat, *probes, light);
            for (size_t i = 0; i < probes->size(); ++i) {
                ASSERT_EQ(e.gpu[i].x, want) << what << " GPU, probe " << i;
                ASSERT_EQ(e.cpu[i].x, want) << what << " CPU, probe " << i;
            }
        }
    };
    expectAll("hard", Technique::Hard, {});
    expectAll("second-depth", Technique::SecondDepth, {});
    for (const auto& [name, params] : everyPcfVariant())
        expectAll(name, Technique::Pcf, params);
    expectAll("pcss ortho", Technique::Pcss, {},
              {.size = 0.05f, .nearPlane = 1.0f, .farPlane = 21.0f, .worldPerUv = {12.0f, 12.0f}});
    expectAll("pcss perspective", Technique::Pcss, {},
              {.perspective = true,
               .size = 0.3f,
               .nearPlane = 2.0f,
               .farPlane = 30.0f,
               .worldPerUv = {1.2f, 1.2f}});
}

TEST_F(FilterTest, ACheckerboardReadsItsTexelAtCentresAndHalfAtCorners) {
    // Texel (i, j) occludes when i + j is even.
    std::vector<float> checker(kSize * kSize);
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
            checker[j * kSize + i] = (i + j) % 2 == 0 ? kOccluder : kFloor;
    std::vector<FilterProbe> centres, corners;
    for (int i = 20; i < 30; ++i)
        for (int j = 24; j < 28; ++j) {
            centres.push_back(probeAt(i + 0.5, j + 0.5));
            corners.push_back(probeAt(i, j));
        }
    auto litAt = [](int i, int j) { return (i + j) % 2 == 0 ? 0.0 : 1.0; };
    for (int n : {1, 3, 5, 9}) {
        const ParameterValues params =
            n == 1 ? parameters({"pcf.filter=bilinear"})
                   : parameters({"pcf.filter=box", ("pcf.size=" + std::to_string(n)).c_str()});
        const std::string what = n == 1 ? "bilinear" : "box" + std::to_string(n);
        // At a texel's centre: the share of lit texels in the n x n box around it.
        expectClosedForm(
            what + " at texel centres", Technique::Pcf, params, checker, centres,
            [&](const FilterProbe& p) {
                const int ci = int(std::floor(p.uv.x * kSize));
                const int cj = int(std::floor(p.uv.y * kSize));
                double lit = 0;
                for (int dj = -(n - 1) / 2; dj <= (n - 1) / 2; ++dj)
                    for (int di = -(n - 1) / 2; di <= (n - 1) / 2; ++di)
                        lit += litAt(ci + di, cj + dj);
                return lit / (n * n);
            },
            kTolerance, n == 1 ? 0.0 : 0.9);
        // At a texel corner every bilinear tap sees two lit and two occluding texels.
        const Evaluated e = evaluate(Technique::Pcf, params, checker, corners);
        for (size_t i = 0; i < corners.size(); ++i) {
            EXPECT_NEAR(e.gpu[i].x, 0.5, kTolerance) << what << " GPU at a corner";
            EXPECT_NEAR(e.cpu[i].x, 0.5, kTolerance) << what << " CPU at a corner";
        }
    }
}

TEST_F(FilterTest, ReceiverPlaneBiasComparesEachTexelWithThePlaneAtItsCentre) {
    // A flat occluder at depth 0.5 and a receiver 0.3 texels' worth of slope in front of it,
    // its depth rising along u: texels whose centre lies up to 0.3 texels right of the receiver
    // (and every texel left of it) pass; texels further right are behind the plane.
    const std::vector<float> flat(kSize * kSize, 0.5f);
    const float slope = 0.5f; // depth per uv unit: 1/128 per texel, inside the default clamp
    const double lead = 0.3;  // texels
    const float depth = 0.5f - static_cast<float>(lead) * slope / kSize;
    std::vector<FilterProbe> probes;
    for (double x = 20.0; x < 24.0; x += 0.0731)
        probes.push_back(probeAt(x, 30.2, depth, {slope, 0.0f}));
    // The last texel that passes for a receiver at x, and the share of passing texels a
    // bilinear tap at x + shift reads.
    auto tap = [&](double x, double shift) {
        const double lastLit = std::floor(x + lead - 0.5);
        return std::clamp(lastLit + 1.5 - (x + shift), 0.0, 1.0);
    };
    for (int n : {1, 3, 7}) {
        const ParameterValues params =
            n == 1 ? parameters({"pcf.filter=bilinear", "bias.receiverSides=both"})
                   : parameters({"pcf.filter=box", ("pcf.size=" + std::to_string(n)).c_str(),
                                 "bias.receiverSides=both"});
        expectClosedForm((n == 1 ? std::string("bilinear") : "box" + std::to_string(n)) +
                             " on a tilted receiver",
                         Technique::Pcf, params, flat, probes, [&](const FilterProbe& p) {
                             double sum = 0;
                             for (int j = -(n - 1) / 2; j <= (n - 1) / 2; ++j)
                                 sum += tap(texelX(p), j);
                             return sum / n;
                         });
    }
    // hard: the texel under the receiver, compared at its centre.
    const Evaluated hard =
        evaluate(Technique::Hard, parameters({"bias.receiverSides=both"}), flat, probes);
    for (size_t i = 0; i < probes.size(); ++i) {
        const double x = texelX(probes[i]);
        const double want = std::floor(x) + 0.5 <= x + lead ? 1.0 : 0.0;
        EXPECT_EQ(hard.gpu[i].x, want) << "hard GPU at texel x " << x;
        EXPECT_EQ(hard.cpu[i].x, want) << "hard CPU at texel x " << x;
    }
    // bias.receiverSides=near drops corrections that push a tap away from the light: every
    // texel then compares the receiver's own depth or nearer, and all of them pass.
    const Evaluated near =
        evaluate(Technique::Pcf, parameters({"pcf.filter=box", "pcf.size=7"}), flat, probes);
    for (size_t i = 0; i < probes.size(); ++i) {
        EXPECT_EQ(near.gpu[i].x, 1.0f) << "near-only corrections, GPU";
        EXPECT_EQ(near.cpu[i].x, 1.0f) << "near-only corrections, CPU";
    }
}

namespace {

// PCSS geometry from docs/techniques.md, written out again here: light view distance z of a
// depth d (orthographic: n + d (f - n); perspective: n f / (f - d (f - n))), the blocker search
// radius (orthographic: (z_r - n) tan(half angle); perspective: R (z_r - n) / z_r at the near
// plane) and the penumbra (orthographic: (z_r - z_b) tan(half angle); perspective:
// (z_r - z_b) R / z_b at the receiver), each turned into texels at its own distance.
struct PcssGeometry {
    double searchTexels, penumbraTexels;
};

PcssGeometry pcssGeometry(const ProbeLight& l, double receiverDepth, double blockerDepth,
                          double maxRadius) {
    const double n = l.nearPlane, f = l.farPlane, size = l.size, perUv = l.worldPerUv.x;
    auto distance = [&](double d) {
        return l.perspective ? n * f / (f - d * (f - n)) : n + d * (f - n);
    };
    const double zr = distance(receiverDepth), zb = distance(blockerDepth);
    // Texels per world unit at distance z.
    auto texels = [&](double z) { return kSize / (perUv * (l.perspective ? z : 1.0)); };
    const double search =
        l.perspective ? size * (zr - n) / zr * texels(n) : (zr - n) * size * texels(1.0);
    const double penumbra =
        l.perspective ? (zr - zb) * size / zb * texels(zr) : (zr - zb) * size * texels(1.0);
    return {std::max(std::min(search, maxRadius), 0.5), std::clamp(penumbra, 0.5, maxRadius)};
}

} // namespace

TEST_F(FilterTest, PcssFindsTheOccluderAndFiltersThePenumbraItsGeometryPredicts) {
    const std::vector<float> map = edgeMap();
    const std::vector<FilterProbe> probes = probesAcrossTheEdge(20.0);
    const auto& disk = poissonDisk();
    struct Case {
        const char* name;
        ProbeLight light;
    };
    const Case cases[] = {
        {"orthographic, tan 0.1",
         {.size = 0.1f, .nearPlane = 1.0f, .farPlane = 21.0f, .worldPerUv = {12.0f, 12.0f}}},
        {"orthographic, tan 0.25",
         {.size = 0.25f, .nearPlane = 1.0f, .farPlane = 21.0f, .worldPerUv = {12.0f, 12.0f}}},
        {"orthographic, tiny (umbra exit)",
         {.size = 0.01f, .nearPlane = 1.0f, .farPlane = 21.0f, .worldPerUv = {12.0f, 12.0f}}},
        {"perspective, radius 0.8",
         {.perspective = true,
          .size = 0.8f,
          .nearPlane = 2.0f,
          .farPlane = 30.0f,
          .worldPerUv = {1.2f, 1.2f}}},
        {"perspective, radius 0.3",
         {.perspective = true,
          .size = 0.3f,
          .nearPlane = 2.0f,
          .farPlane = 30.0f,
          .worldPerUv = {1.2f, 1.2f}}},
    };
    const ParameterValues params = parameters({"pcss.rotation=none", "pcss.blockerSamples=24",
                                               "pcss.filterSamples=32", "pcss.maxRadius=40"});
    for (const Case& c : cases) {
        const PcssGeometry g = pcssGeometry(c.light, kReceiver, kOccluder, 40.0);
        // The search gathers' leftmost and rightmost first texels, relative to the receiver.
        double left = 1e9, right = -1e9;
        for (int i = 0; i < 24; ++i)
            left = std::min(left, double(disk[i].x)), right = std::max(right, double(disk[i].x));
        const Evaluated e = evaluate(Technique::Pcss, params, map, probes, c.light);
        size_t checked = 0, lit = 0;
        for (size_t i = 0; i < probes.size(); ++i) {
            const double x = texelX(probes[i]);
            const double firstLeft = std::floor(x + g.searchTexels * left - 0.5);
            const double firstRight = std::floor(x + g.searchTexels * right - 0.5);
            for (const auto& [side, got] :
                 {std::pair("GPU", e.gpu[i]), std::pair("CPU", e.cpu[i])}) {
                const std::string at =
                    std::string(c.name) + ", " + side + " at texel x " + std::to_string(x);
                if (firstLeft >= kEdge) { // no gather reaches the occluder: lit, no search result
                    EXPECT_EQ(got.x, 1.0f) << at;
                    EXPECT_EQ(got.z, 0.0f) << at;
                    lit += side[0] == 'G';
                    continue;
                }
                if (std::abs(firstLeft - (x + g.searchTexels * left - 0.5)) < 1e-3 ||
                    std::abs(firstRight - (x + g.searchTexels * right - 0.5)) < 1e-3)
                    continue; // a gather on a texel boundary: float rounding decides
                checked += side[0] == 'G';
                EXPECT_NEAR(got.y, kOccluder, 1e-6) << at << ": average blocker depth";
                EXPECT_NEAR(got.w, g.penumbraTexels, 1e-4 * g.penumbraTexels)
                    << at << ": filter radius";
                double want;
                if (firstRight + 1 < kEdge && g.penumbraTexels <= 1.0) {
                    want = 0.0; // every texel searched blocks, and the penumbra is sub-texel
                } else {
                    double sum = 0;
                    for (int k = 0; k < 32; ++k)
                        sum += ramp(x + g.penumbraTexels * disk[k].x);
                    want = sum / 32;
                }
                EXPECT_NEAR(got.x, want, kTolerance) << at << ": visibility";
            }
        }
        std::printf("pcss %s: search %.3f texels, penumbra %.3f texels; %zu probes with "
                    "blockers, %zu without\n",
                    c.name, g.searchTexels, g.penumbraTexels, checked, lit);
        EXPECT_GT(checked, probes.size() / 4) << c.name;
        EXPECT_GT(lit, probes.size() / 20) << c.name;
    }
}

TEST_F(FilterTest, VariantsThatSeeTheSameFootprintAgree) {
    // A random map of occluders: the bilinear variant (the grid path with n = 1) and the
    // hand-written bilinear tap (the hardware variant without linear depth filtering) read the
    // same four texels with the same weights; a one-tap Poisson disk is that tap moved by the
    // disk's first point.
    std::vector<float> map(kSize * kSize);
    uint32_t state = 12345;
    for (float& d : map) {
        state = state * 1664525u + 1013904223u;
        d = (state >> 24) % 3 == 0 ? kOccluder : kFloor;
    }
    std::vector<FilterProbe> probes, shifted;
    const glm::vec2 first = poissonDisk()[0];
    const float radius = 2.5f;
    for (int i = 0; i < 500; ++i) {
        const double x = 4 + 56 * std::fmod(0.6180339887 * i, 1.0);
        const double y = 4 + 56 * std::fmod(0.7548776662 * i + 0.3, 1.0);
        probes.push_back(probeAt(x, y));
        shifted.push_back(probeAt(x + radius * first.x, y + radius * first.y));
    }
    const Evaluated bilinear =
        evaluate(Technique::Pcf, parameters({"pcf.filter=bilinear"}), map, probes);
    const Evaluated hardware =
        evaluate(Technique::Pcf, parameters({"pcf.filter=hardware"}), map, probes);
    const Evaluated oneTap = evaluate(
        Technique::Pcf,
        parameters({"pcf.filter=poisson", "pcf.samples=1", "pcf.radius=2.5", "pcf.rotation=none"}),
        map, probes);
    const Evaluated bilinearShifted =
        evaluate(Technique::Pcf, parameters({"pcf.filter=bilinear"}), map, shifted);
    size_t between = 0;
    for (size_t i = 0; i < probes.size(); ++i) {
        between += bilinear.gpu[i].x > 0.0f && bilinear.gpu[i].x < 1.0f;
        EXPECT_NEAR(bilinear.gpu[i].x, hardware.gpu[i].x, hardwareTolerance()) << "probe " << i;
        // The CPU emulates the device's steps (rounding them) when it filters depth itself.
        EXPECT_NEAR(bilinear.cpu[i].x, hardware.cpu[i].x, hardwareTolerance()) << "probe " << i;
        EXPECT_NEAR(oneTap.gpu[i].x, bilinearShifted.gpu[i].x, 1e-3) << "probe " << i;
        EXPECT_NEAR(oneTap.cpu[i].x, bilinearShifted.cpu[i].x, 1e-3) << "probe " << i;
    }
    EXPECT_GT(between, 100u);
}

TEST_F(FilterTest, PcssFiltersAHoleItsBlockerSearchStepsOver) {
    // An occluder over the whole map but one texel (a hole), and a receiver just behind the
    // occluder: the search region (16 texels) is far wider than the penumbra (2.67 texels).
    // Where no search gather covers the hole, every texel searched blocks; the penumbra is wider
    // than a texel, so PCSS must still filter, and its taps see the hole through the bilinear
    // tent max(0, 1 - |dx|) max(0, 1 - |dy|) around the hole's centre.
    constexpr int kHole = 32;
    std::vector<float> map(kSize * kSize, kOccluder);
    map[kHole * kSize + kHole] = kFloor;
    const ProbeLight light{
        .size = 0.5f, .nearPlane = 1.0f, .farPlane = 21.0f, .worldPerUv = {12.0f, 12.0f}};
    const float receiver = 0.3f;
    const PcssGeometry g = pcssGeometry(light, receiver, kOccluder, 40.0);
    ASSERT_NEAR(g.searchTexels, 16.0, 1e-4);
    ASSERT_NEAR(g.penumbraTexels, 8.0 / 3.0, 1e-4);
    std::vector<FilterProbe> probes;
    for (double dy = -0.9; dy <= 0.9; dy += 0.15)
        for (double dx = -0.9; dx <= 0.9; dx += 0.15)
            probes.push_back(probeAt(kHole + 0.5 + dx, kHole + 0.5 + dy, receiver));
    const ParameterValues params =
        parameters({"pcss.rotation=none", "pcss.blockerSamples=24", "pcss.filterSamples=32"});
    const Evaluated e = evaluate(Technique::Pcss, params, map, probes, light);
    const auto& disk = poissonDisk();
    size_t checked = 0, seen = 0;
    for (size_t i = 0; i < probes.size(); ++i) {
        const glm::dvec2 centre = glm::dvec2(probes[i].uv) * double(kSize);
        bool searchSeesHole = false;
        for (int k = 0; k < 24; ++k) {
            const glm::dvec2 base = glm::floor(centre + g.searchTexels * glm::dvec2(disk[k]) - 0.5);
            searchSeesHole |= (base.x == kHole || base.x == kHole - 1) &&
                              (base.y == kHole || base.y == kHole - 1);
        }
        if (searchSeesHole)
            continue;
        double want = 0;
        for (int k = 0; k < 32; ++k) {
            const glm::dvec2 q = centre + g.penumbraTexels * glm::dvec2(disk[k]);
            want += std::max(0.0, 1.0 - std::abs(q.x - (kHole + 0.5))) *
                    std::max(0.0, 1.0 - std::abs(q.y - (kHole + 0.5)));
        }
        want /= 32;
        ++checked;
        seen += want > 0.01;
        for (const auto& [side, got] : {std::pair("GPU", e.gpu[i]), std::pair("CPU", e.cpu[i])}) {
            EXPECT_EQ(got.z, 96.0f) << side << ": every searched texel blocks";
            EXPECT_NEAR(got.w, g.penumbraTexels, 1e-4) << side;
            EXPECT_NEAR(got.x, want, kTolerance) << side << " at " << centre.x << ", " << centre.y;
        }
    }
    std::printf("hole in the umbra: %zu probes where the search misses it, %zu see it\n", checked,
                seen);
    EXPECT_GE(checked, 20u); // measured: 34 of 169, every one of them sees the hole
    EXPECT_GT(seen, checked / 2);
}
