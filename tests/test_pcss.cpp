// PCSS against the ray-traced ground truth: accuracy against fixed-size PCF, and contact
// hardening measured across the leaning pole's shadow, for a directional and a spot light.
#include "gpu_fixture.h"
#include "penumbra/reference.h"
#include "report/blur_band.h"
#include "report/light_mask.h"
#include "report/metrics.h"
#include "scene/builtin_scenes.h"
#include "shadows/technique.h"

#include <algorithm>
#include <cstdio>
#include <map>

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct Setup {
    const char* scene;
    float radius, angle; // light size overrides (-1: keep)
    double tip, base;    // where along the pole's ground shadow "tip" and "base" are measured
    double rmseRatio;    // PCSS's RMSE at most this times the best fixed PCF's (measured - 10%)
    double hardening;    // PCSS's penumbra at the tip at least this times that at the base
    double tipError;     // PCSS's penumbra at the tip within this fraction of the truth's
};

// Light sizes for which the pole's penumbra at its tip spans more than 20 pixels at 1280x720.
// Under the spot the last quarter of the pole's shadow falls on the cube, so its "tip" is the
// farthest stretch still on the ground.
// Measured (bias.mode=adaptive): sun penumbra 0.185 at the tip and 0.100 at the base (1.85x;
// the truth 0.250 / 0.060), spot 0.340 / 0.100 (3.4x; the truth 0.235 / 0.080); the hardening
// bounds sit 10% under. The spot's tip reads 45% wide: PCSS's average blocker depth over a
// search region that takes in the pole's nearer part. The fixed mode's offsets, a fraction of
// the perspective depth range and a slope term, pushed the pole 0.1 units back and hid some of
// it (0.305 / 0.075 then, and 0.205 / 0.090 under the sun), at the price of the leaks the
// adaptive mode removes (docs/techniques.md, "Adaptive depth bias"); over the whole image PCSS
// reads closer to the truth now (RMSE 0.0092 against 0.0100 on the showcase, 0.0077 against
// 0.0126 under the spot, 480x270).
constexpr Setup kDirectional{"builtin:showcase", -1.0f, 12.0f, 0.85, 0.15, 0.6, 1.65, 0.35};
constexpr Setup kSpot{"builtin:spot", 1.5f, -1.0f, 0.62, 0.15, 0.5, 3.0, 0.5};

Scene sceneFor(const Setup& s) {
    Scene scene = loadScene(s.scene);
    applyLightSizeOverrides(scene, s.radius, s.angle);
    return scene;
}

RenderResult renderRow(const Scene& scene, uint32_t w, uint32_t h, const TechniqueRow& row) {
    RenderOptions o{.width = w, .height = h, .frames = 1, .technique = row.technique};
    for (const auto& [key, value] : row.sets)
        o.parameters.set(key, value);
    return sharedRenderer().render(scene, o);
}

ErrorMetrics errorOf(const Scene& scene, const RenderResult& r, const ReferenceResult& truth) {
    const std::vector<uint8_t> mask = lightMask(scene.lights[r.lights[0].sceneLight], r);
    const MetricLayer layer{r.visibility[0], truth.visibility[0], mask};
    return computeMetrics(r.width, r.height, std::span(&layer, 1));
}

void expectPcssBeatsFixedPcf(const Setup& setup) {
    const Scene scene = sceneFor(setup);
    const TechniqueRow pcss{.name = "pcss", .technique = Technique::Pcss};
    const RenderResult pcssResult = renderRow(scene, 640, 360, pcss);
    const ReferenceResult truth = computeReference(scene, pcssResult, {.samples = 256});
    const ErrorMetrics p = errorOf(scene, pcssResult, truth);
    const std::vector<std::vector<uint8_t>> masks{
        lightMask(scene.lights[pcssResult.lights[0].sceneLight], pcssResult)};
    const ErrorMetrics pcssBeyondBlur =
        metricsAgainstTruth(scene, pcssResult, std::span(truth.visibility).first(1), masks,
                            shadows::pcssModule().blurRadiusTexels(ParameterValues()));
    double best = 1e9;
    std::string bestName;
    for (const TechniqueRow& row : comparisonRows("pcf")) {
        const double rmse = errorOf(scene, renderRow(scene, 640, 360, row), truth).rmse;
        if (rmse < best)
            best = rmse, bestName = row.name;
    }
    std::printf("%s: pcss rmse %.4f (acne %.3f%%, leak %.3f%%), best fixed PCF %s %.4f (%.0f%% "
                "lower)\n",
                setup.scene, p.rmse, 100 * p.acne, 100 * p.leak, bestName.c_str(), best,
                100 * (1 - p.rmse / best));
    EXPECT_LE(p.rmse, setup.rmseRatio * best) << "PCSS against " << bestName;
    // Beyond the blur band: PCSS's 12-degree penumbrae reach past the fixed 2-pixel band (fixed
    // band, bias.mode=adaptive: 0.081% sun, 0.039% spot).
    EXPECT_LT(pcssBeyondBlur.acneBeyondBlur, 0.0006);
    // Measured: 0.80% (sun: 19 pixels of 2369 at 0.10-0.12, the Poisson disk's noise deep in
    // a 12-degree penumbra), 0 (spot).
    EXPECT_LT(p.leak, 0.012);
}

// Where the pole's points fall on the ground, seen from the light.
glm::vec3 groundShadow(const Light& light, const glm::vec3& p) {
    if (light.type == LightType::Directional) {
        const glm::vec3 d = glm::normalize(light.direction);
        return p + d * (p.y / -d.y);
    }
    return light.position + (p - light.position) * (light.position.y / (light.position.y - p.y));
}

// Penumbra width (world units, per side) across the pole's shadow at fraction `a` of its
// length, and the ground distance between neighbouring pixels there.
struct CrossSection {
    double width = 0, pixel = 0;
};

CrossSection penumbraAcross(const RenderResult& r, const std::vector<float>& visibility,
                            const Light& light, double a) {
    const glm::vec3 base = groundShadow(light, builtin::kPoleBase);
    const glm::vec3 tip = groundShadow(light, builtin::kPoleTip);
    const glm::vec3 axis = glm::normalize(tip - base);
    const glm::vec3 across = glm::normalize(glm::cross(glm::vec3(0, 1, 0), axis));
    const double length = glm::length(tip - base), window = 0.03 * length;
    const glm::vec3 centre = base + axis * static_cast<float>(a * length);
    std::map<int, std::pair<double, int>> bins; // 0.01-unit bins across: mean visibility
    std::vector<double> steps;
    for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x) {
            const size_t i = size_t{y} * r.width + x;
            if (!onGround(r, i))
                continue;
            const glm::vec3 d = pixelVec(r.position, i) - centre;
            if (std::abs(glm::dot(d, axis)) > window)
                continue;
            const double lateral = glm::dot(d, across);
            if (std::abs(lateral) > 1.0)
                continue;
            auto& bin = bins[static_cast<int>(std::floor(lateral / 0.01))];
            bin.first += visibility[i], ++bin.second;
            if (x + 1 < r.width && onGround(r, i + 1))
                steps.push_back(glm::length(pixelVec(r.position, i + 1) - pixelVec(r.position, i)));
        }
    // The 10%-90% rise of the occlusion 1 - v relative to its own peak, on each side: a thin
    // pole's shadow loses its umbra once the penumbra is wider than the pole, and its darkest
    // point then stays above 10% visibility, so absolute levels would stop measuring.
    std::vector<std::pair<double, double>> profile; // (lateral, occlusion)
    for (const auto& [index, bin] : bins)
        profile.emplace_back((index + 0.5) * 0.01, 1.0 - bin.first / bin.second);
    CrossSection c;
    size_t peak = 0;
    for (size_t i = 0; i < profile.size(); ++i)
        if (profile[i].second > profile[peak].second)
            peak = i;
    if (profile.empty() || profile[peak].second < 0.05)
        return c; // no shadow here
    const double top = profile[peak].second;
    auto rise = [&](int step) {
        double at90 = profile[peak].first, at10 = at90;
        bool seen90 = false;
        for (int i = static_cast<int>(peak); i >= 0 && i < static_cast<int>(profile.size());
             i += step) {
            if (!seen90 && profile[i].second <= 0.9 * top)
                at90 = profile[i].first, seen90 = true;
            if (profile[i].second <= 0.1 * top) {
                at10 = profile[i].first;
                break;
            }
            at10 = profile[i].first;
        }
        return std::abs(at10 - at90);
    };
    c.width = 0.5 * (rise(-1) + rise(+1));
    std::sort(steps.begin(), steps.end());
    c.pixel = steps.empty() ? 1.0 : steps[steps.size() / 2];
    return c;
}

void expectContactHardening(const Setup& setup) {
    const Scene scene = sceneFor(setup);
    const RenderResult pcss =
        renderRow(scene, 1280, 720, {.name = "pcss", .technique = Technique::Pcss});
    // The truth only along the pole's shadow would do, but the reference is fast enough here.
    const ReferenceResult truth = computeReference(scene, pcss, {.samples = 128});
    const Light& light = scene.lights[0];
    const CrossSection truthTip = penumbraAcross(pcss, truth.visibility[0], light, setup.tip);
    const CrossSection truthBase = penumbraAcross(pcss, truth.visibility[0], light, setup.base);
    const CrossSection tip = penumbraAcross(pcss, pcss.visibility[0], light, setup.tip);
    const CrossSection base = penumbraAcross(pcss, pcss.visibility[0], light, setup.base);
    // The penumbra spans both 10%-90% rises across the shadow (at the tip there is no umbra).
    const double truthSpanPixels = 2.0 * truthTip.width / truthTip.pixel;
    std::printf("%s: penumbra width per side at the tip / near the base: truth %.3f / %.3f, "
                "pcss %.3f / %.3f; the truth's penumbra spans %.0f px at the tip\n",
                setup.scene, truthTip.width, truthBase.width, tip.width, base.width,
                truthSpanPixels);
    ASSERT_GE(truthSpanPixels, 20.0) << "the light must be big enough";
    EXPECT_GT(tip.width, setup.hardening * base.width) << "contact hardening";
    EXPECT_NEAR(tip.width, truthTip.width, setup.tipError * truthTip.width)
        << "penumbra at the tip";
}

} // namespace

TEST_F(QualityTest, PcssBeatsFixedPcfUnderALargeSun) {
    expectPcssBeatsFixedPcf(kDirectional);
}
TEST_F(QualityTest, PcssBeatsFixedPcfUnderALargeSpot) {
    expectPcssBeatsFixedPcf(kSpot);
}
TEST_F(QualityTest, PcssHardensAtContactUnderALargeSun) {
    expectContactHardening(kDirectional);
}
TEST_F(QualityTest, PcssHardensAtContactUnderALargeSpot) {
    expectContactHardening(kSpot);
}
