// Technique `evsm` [Lauritzen and McCool 2008, 'Layered variance shadow maps' (the exponential
// warp)]: the moments of two exponential warps of the moment depth, e^(c+ z) and -e^(-c- z),
// blurred like VSM's (shaders/include/moments_blur.glsl); Chebyshev's bound in each warp, the
// smaller one wins (shaders/include/shadow_moments.glsl). The warps squeeze the depths an
// occluder's far side spreads, which is what makes VSM bleed. Its block: params_moments.h; CPU
// mirror: evsmReference below; derivations in docs/techniques.md.
#include "moments.h"
#include "params_moments.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_moments.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr GaussianBlur kBlur{.sizeKey = "evsm.size",
                             .rowsShader = "evsm_blur_rows.comp",
                             .columnsShader = "evsm_blur_columns.comp",
                             .output = "moments",
                             .format = MapFormat::RGBA32F};

// shadowEvsmDetail: x visibility, y the positive warp's filtered first moment, z the negative
// warp's, w the receiver's moment depth.
glm::vec4 evsmReference(const FilterInput& in) {
    const gpu::EvsmParams p = in.params.get<gpu::EvsmParams>();
    const glm::vec2 exponents(p.positive, p.negative);
    const glm::vec4 moments =
        momentsAt(in.map, MOMENTS_EVSM, p.size, exponents, in.view, in.probe.uv);
    const float t = gpu::momentDepth(in.view, in.probe.depth);
    const float v =
        gpu::exponentialVarianceVisibility(moments, t, exponents, p.minVariance, p.components);
    return {gpu::snapToExtremes(gpu::reduceLightBleeding(v, p.bleedReduction)), moments.x,
            moments.z, t};
}

} // namespace

const TechniqueModule& evsmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Evsm,
                 .name = "evsm",
                 .summary = "exponential variance shadow maps: Chebyshev's bound on exponentially "
                            "warped depths (2 or 4 moments; far less light bleeding than vsm)",
                 .reference = "Lauritzen and McCool 2008, 'Layered variance shadow maps'",
                 .families = {"bias", "evsm", "csm", "composite"},
                 .variants = {{.label = ""}, {.label = "2", .sets = {{"evsm.components", "2"}}}}},
        .parameters =
            {{.key = "evsm.components",
              .type = ParameterType::Choice,
              .defaultValue = 1,
              .choices = {"2", "4"},
              .description = "2: the positive warp's moments alone; 4: both warps (the map keeps "
                             "four channels either way)"},
             {.key = "evsm.positive",
              .type = ParameterType::Float,
              .defaultValue = 40.0,
              .min = 0.1,
              .max = 42.0,
              .description = "exponent c+ of the positive warp; 42 keeps e^(2 c+ z) within "
                             "32-bit floats"},
             {.key = "evsm.negative",
              .type = ParameterType::Float,
              .defaultValue = 5.0,
              .min = 0.1,
              .max = 42.0,
              .description = "exponent c- of the negative warp"},
             {.key = "evsm.minVariance",
              .type = ParameterType::Float,
              .defaultValue = 1e-5,
              .min = 0.0,
              .max = 0.01,
              .unit = "(depth range)^2",
              .description = "least variance, in moment-depth units (carried into each warp by "
                             "its slope)"},
             {.key = "evsm.bleedReduction",
              .type = ParameterType::Float,
              .defaultValue = 0.0,
              .min = 0.0,
              .max = 0.99,
              .description = "as vsm.bleedReduction, on the smaller bound"},
             kBlur.sizeParameter()},
        .maps = kBlur.maps(),
        .postPasses = kBlur.passes(),
        .visibilityMaps = {"moments"},
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                block.set(gpu::EvsmParams{
                    .positive = static_cast<float>(p.number("evsm.positive")),
                    .negative = static_cast<float>(p.number("evsm.negative")),
                    .minVariance = static_cast<float>(p.number("evsm.minVariance")),
                    .bleedReduction = static_cast<float>(p.number("evsm.bleedReduction")),
                    .components = p.number("evsm.components") == 0.0 ? 2u : 4u,
                    .size = static_cast<uint32_t>(p.number("evsm.size"))});
            },
        .reference = evsmReference,
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
