// Technique `vsm` [Donnelly and Lauritzen 2006, 'Variance shadow maps']: two post passes take the
// moments (z, z^2) of the light's depth and blur them with a separable Gaussian
// (shaders/include/moments_blur.glsl); the visibility pass interpolates them bilinearly and
// bounds the lit fraction by Chebyshev's inequality, with a minimum variance and light-bleeding
// reduction [Lauritzen 2007] (shaders/include/shadow_moments.glsl). CPU mirror:
// src/reference/filter_reference.cpp; derivations in docs/techniques.md.
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr GaussianBlur kBlur{.sizeKey = "vsm.size",
                             .rowsShader = "vsm_blur_rows.comp",
                             .columnsShader = "vsm_blur_columns.comp",
                             .output = "moments",
                             .format = MapFormat::RG32F};

} // namespace

const TechniqueModule& vsmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Vsm,
                 .name = "vsm",
                 .summary = "variance shadow maps: blurred depth moments, Chebyshev's bound on "
                            "the lit fraction (a filter of any width at a fixed cost per pixel)",
                 .reference = "Donnelly and Lauritzen 2006, 'Variance shadow maps'",
                 .families = {"bias", "vsm", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "no-bleed-reduction",
                               .sets = {{"vsm.bleedReduction", "0"}}}}},
        .parameters = {kBlur.sizeParameter(),
                       {.key = "vsm.minVariance",
                        .type = ParameterType::Float,
                        .defaultValue = 1e-5,
                        .min = 0.0,
                        .max = 0.01,
                        .unit = "(depth range)^2",
                        .description =
                            "least variance Chebyshev's bound assumes, in squared units of the "
                            "view's depth range (keeps flat receivers from shadowing themselves)"},
                       {.key = "vsm.bleedReduction",
                        .type = ParameterType::Float,
                        .defaultValue = 0.2,
                        .min = 0.0,
                        .max = 0.99,
                        .description =
                            "bounds up to this count as shadow, the rest rescaled: less light "
                            "bleeding between stacked occluders, darker and harder penumbrae"}},
        .maps = kBlur.maps(),
        .postPasses = kBlur.passes(),
        .visibilityMap = "moments",
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                f.vsmParams = {static_cast<float>(p.number("vsm.minVariance")),
                               static_cast<float>(p.number("vsm.bleedReduction")),
                               static_cast<float>(p.number("vsm.size")), 0.0f};
            },
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
