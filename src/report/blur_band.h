#pragma once
// How far a technique's filter reaches on the screen, per pixel: the radius of the blur band
// that acne_beyond_blur and leak_beyond_blur leave out (report/metrics.h), so that the blur a
// wide kernel is meant to make is not counted as self-shadowing or missing shadow.
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "report/metrics.h"

#include <span>
#include <utility>

#include <vector>

namespace penumbra {

// One value per pixel of `gbuffer` (its positions): `blurTexels` (the technique's declared blur
// radius, TechniqueModule::blurRadiusTexels, in texels of the light's first view, which a
// sun's cascades scale their kernels to) as a world distance across the light's rays at the
// pixel, over the smallest stretch of the pixel's footprint across those rays: the widest the
// blur's disc can appear on the screen, in pixels. The footprint comes from the neighbour on
// each axis nearer in world space (the one likely on the same surface); a pixel with no
// neighbour, the background, and a light that casts no shadow give NaN (the metric's minimum).
std::vector<float> blurBandPixels(const Light& light, const LightShadow& shadow,
                                  const RenderResult& gbuffer, double blurTexels);

// One view's render, its truth (one image per visibility layer, as the render's) and each
// layer's mask of counted pixels.
struct TruthView {
    const RenderResult* result = nullptr;
    std::span<const std::vector<float>> truth;
    std::span<const std::vector<uint8_t>> masks;
    // The truth's occluder distances (ReferenceResult::occluderDistance, one image per layer)
    // and the contact band (world units; contactBand()) for leak_near_contact; empty: none.
    std::span<const std::vector<float>> occluderDistance = {};
    double contactBand = 0.0;
};

// The distance from a caster within which its shadow counts as a contact shadow: 2% of the
// scene's bounding radius (shadows::kContactRowFraction: the contact layer's rows march as far).
double contactBand(const Scene& scene);

// The metrics of the views' renders against their truth, pooled (every view the same size),
// with the blur band of a technique whose declared blur radius is `blurTexels`; `lit`: the scene
// with the light sizes the truth used.
// The technique's blur radius in texels (TechniqueModule::blurRadiusTexels), and on a point
// light's cube faces its own where it has one (cubeRadiusTexels; negative: the same).
struct BlurReach {
    double texels = 0.0, cubeTexels = -1.0;
    BlurReach(double t = 0.0, double cube = -1.0) : texels(t), cubeTexels(cube) {}
    BlurReach(std::pair<double, double> radii) : texels(radii.first), cubeTexels(radii.second) {}
    double on(const Light& light) const {
        return light.type == LightType::Point && cubeTexels >= 0.0 ? cubeTexels : texels;
    }
};

ErrorMetrics metricsAgainstTruth(const Scene& lit, std::span<const TruthView> views,
                                 BlurReach blur);
ErrorMetrics metricsAgainstTruth(const Scene& lit, const RenderResult& result,
                                 std::span<const std::vector<float>> truth,
                                 std::span<const std::vector<uint8_t>> masks, BlurReach blur,
                                 std::span<const std::vector<float>> occluderDistance = {});

// metrics.json's rmse_per_channel for a render against a coloured truth (`truthTransmittance`,
// ReferenceResult::transmittance): the first light's light per channel (the translucent layer's,
// else its visibility in every channel) over the pixels its mask counts. Empty where the truth is
// grey (no transmittance) or no light casts a shadow.
std::vector<double> firstLightRmsePerChannel(const RenderResult& result,
                                             std::span<const std::vector<float>> truthTransmittance,
                                             std::span<const std::vector<uint8_t>> masks);

} // namespace penumbra
