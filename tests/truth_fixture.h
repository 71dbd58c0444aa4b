#pragma once
// Ground-truth comparisons for the GPU tests: one render's G-buffer, the Embree truth traced
// from it, and the metrics of any technique row on the same pixels, as `penumbra compare` does.
#include "gpu_fixture.h"
#include "penumbra/reference.h"
#include "report/blur_band.h"
#include "report/light_mask.h"
#include "report/metrics.h"
#include "shadows/technique.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::test {

struct TruthSetup {
    std::string scene;
    float radius = -1.0f, angle = -1.0f; // light size overrides (< 0: the scene's)
    uint32_t width = 512, height = 512;
    uint32_t shadowMapSize = 2048;
    uint32_t samples = 64; // per pixel (1 for a point-like light)
};

struct Truth {
    TruthSetup setup;
    Scene scene;
    RenderResult gbuffer;
    ReferenceResult reference;
    std::vector<uint8_t> mask; // pixels the metrics count for the first shadow-casting light
};

// The light behind visibility layer `layer` of a render of `scene`.
inline const Light& lightOfLayer(const Scene& scene, const RenderResult& r, size_t layer) {
    for (const LightShadow& s : r.lights)
        if (s.visibilityIndex == static_cast<int>(layer))
            return scene.lights[s.sceneLight];
    throw std::out_of_range("no light has visibility layer " + std::to_string(layer));
}

// The truth of a scene made in code (setup.scene is ignored).
inline Truth groundTruth(Scene scene, const TruthSetup& setup) {
    Truth t{.setup = setup, .scene = std::move(scene)};
    applyLightSizeOverrides(t.scene, setup.radius, setup.angle);
    t.gbuffer = sharedRenderer().render(
        t.scene, {.width = setup.width, .height = setup.height, .frames = 1});
    t.reference = computeReference(t.scene, t.gbuffer, {.samples = setup.samples});
    t.mask = lightMask(lightOfLayer(t.scene, t.gbuffer, 0), t.gbuffer);
    return t;
}

inline Truth groundTruth(const TruthSetup& setup) {
    return groundTruth(loadScene(setup.scene), setup);
}

// `shadowMapSize` 0: the setup's.
inline RenderResult renderRow(const Truth& t, Technique technique,
                              const std::vector<std::pair<std::string, std::string>>& sets,
                              uint32_t shadowMapSize = 0) {
    RenderOptions o{.width = t.setup.width,
                    .height = t.setup.height,
                    .shadowMapSize = shadowMapSize ? shadowMapSize : t.setup.shadowMapSize,
                    .frames = 1,
                    .technique = technique};
    for (const auto& [key, value] : sets)
        o.parameters.set(key, value);
    return sharedRenderer().render(t.scene, o);
}

inline ErrorMetrics errorOf(const Truth& t, const RenderResult& r) {
    const MetricLayer layer{r.visibility[0], t.reference.visibility[0], t.mask};
    return computeMetrics(r.width, r.height, std::span(&layer, 1));
}

// Visibility layer `layer` against its truth, over the pixels its light reaches.
inline ErrorMetrics errorOfLayer(const Truth& t, const RenderResult& r, size_t layer) {
    const std::vector<uint8_t> mask = lightMask(lightOfLayer(t.scene, r, layer), t.gbuffer);
    const MetricLayer m{r.visibility[layer], t.reference.visibility[layer], mask};
    return computeMetrics(r.width, r.height, std::span(&m, 1));
}

// The first layer's error with the technique's blur band (acneBeyondBlur, leakBeyondBlur), as
// `compare` measures it; `sets` as given to renderRow.
inline ErrorMetrics
errorBeyondBlur(const Truth& t, const RenderResult& r, Technique technique,
                const std::vector<std::pair<std::string, std::string>>& sets = {}) {
    ParameterValues p;
    for (const auto& [key, value] : sets)
        p.set(key, value);
    const shadows::TechniqueModule& module = shadows::moduleOf(technique);
    const BlurReach blur = shadows::blurRadii(module, p);
    const std::vector<std::vector<float>> truth{t.reference.visibility[0]};
    const std::vector<std::vector<uint8_t>> masks{t.mask};
    RenderResult first = r;
    first.visibility.resize(1);
    return metricsAgainstTruth(t.scene, first, truth, masks, blur);
}

inline ErrorMetrics measure(const Truth& t, Technique technique,
                            const std::vector<std::pair<std::string, std::string>>& sets) {
    return errorOf(t, renderRow(t, technique, sets));
}

// A compare row as `compare` renders it on this truth's scene (its layers sized to the scene).
inline ErrorMetrics measure(const Truth& t, const TechniqueRow& row) {
    RenderOptions o{.width = t.setup.width,
                    .height = t.setup.height,
                    .shadowMapSize = t.setup.shadowMapSize,
                    .frames = 1,
                    .technique = row.technique};
    applyRow(row, o.parameters, t.scene.bounds().radius());
    return errorOf(t, sharedRenderer().render(t.scene, o));
}

// How far a measurement may move from the value stored beside its check. Lavapipe renders
// bit-identically run after run, so the tables are tight there (a 20% worse error must fail);
// another device rasterizes and filters a little differently, so they only catch gross changes.
inline bool onCpuDevice() {
    return sharedRenderer().device().type.find("CPU") != std::string::npos;
}
inline double storedTolerance() {
    return onCpuDevice() ? 0.15 : 0.5;
}
// The floor of a stored pixel fraction (acne, leak, misclassified): `onLavapipe` there; on
// another device ten times it, since a few pixels whose rounding moves a stochastic
// technique's rays (smrt's) or a tap across a test's threshold flip (smrt's leak on the
// showcase read 0.049% on an H100, 0 on lavapipe: 5 pixels).
inline double storedFloor(double onLavapipe) {
    return onCpuDevice() ? onLavapipe : 10.0 * onLavapipe;
}

// A measured value against the one stored beside its threshold: within `relative` of it, or
// `floor` for values near zero. Both directions fail: a worse value is a regression, a better
// one means the stored table no longer describes the code (re-measure and update it).
inline void expectStored(const std::string& what, double measured, double stored, double relative,
                         double floor) {
    const double slack = std::max(relative * stored, floor);
    EXPECT_LE(measured, stored + slack) << what << ": worse than the stored " << stored;
    EXPECT_GE(measured, stored - slack)
        << what << ": better than the stored " << stored << " (run `make baselines`)";
}

// RMSE over the pixels whose truth is not fully lit, grown by `grow` pixels (a square), among
// those the light reaches: the soft region, where filtering techniques differ (the issue's
// measure). groundOnly: only the plane's pixels (not the sphere's own terminator).
inline double softRegionRmse(const Truth& t, const RenderResult& r, bool groundOnly = false,
                             int grow = 8) {
    const auto w = static_cast<int>(r.width), h = static_cast<int>(r.height);
    const std::vector<float>& truth = t.reference.visibility[0];
    auto at = [w](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(w) + x; };
    std::vector<uint8_t> region(truth.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!t.mask[at(x, y)] || !(truth[at(x, y)] < 1.0f))
                continue;
            for (int v = std::max(0, y - grow); v <= std::min(h - 1, y + grow); ++v)
                for (int u = std::max(0, x - grow); u <= std::min(w - 1, x + grow); ++u)
                    region[at(u, v)] = 1;
        }
    double sum = 0;
    size_t n = 0;
    for (size_t i = 0; i < truth.size(); ++i)
        if (region[i] && t.mask[i] && std::isfinite(r.visibility[0][i]) &&
            (!groundOnly || onGround(t.gbuffer, i))) {
            const double d = r.visibility[0][i] - truth[i];
            sum += d * d, ++n;
        }
    return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

} // namespace penumbra::test
