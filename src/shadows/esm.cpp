// Technique `esm` [Annen et al. 2008, 'Exponential shadow maps'; Salvi 2008, 'Rendering filtered
// shadows with exponential shadow maps']: the map keeps e^(c z) of the moment depth, blurred
// like VSM's moments (shaders/include/moments_blur.glsl); the visibility is the filtered value
// over e^(c t), at most 1 (shaders/include/shadow_moments.glsl). CPU mirror:
// src/reference/filter_reference.cpp; derivations in docs/techniques.md.
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr GaussianBlur kBlur{.sizeKey = "esm.size",
                             .rowsShader = "esm_blur_rows.comp",
                             .columnsShader = "esm_blur_columns.comp",
                             .output = "exponentials",
                             .format = MapFormat::R32F};

} // namespace

const TechniqueModule& esmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Esm,
                 .name = "esm",
                 .summary = "exponential shadow maps: blurred e^(c z), the lit fraction "
                            "e^(-c t) E[e^(c z)] (one channel; light near contact)",
                 .reference = "Annen et al. 2008, 'Exponential shadow maps'; Salvi 2008",
                 .families = {"bias", "esm", "csm", "composite"},
                 .variants = {{.label = ""}}},
        .parameters = {{.key = "esm.c",
                        .type = ParameterType::Float,
                        .defaultValue = 80.0,
                        .min = 1.0,
                        .max = 88.0,
                        .description =
                            "exponent over the [0, 1] moment depth: sharper and less light near "
                            "contact as it grows; 88 keeps e^(c z) within 32-bit floats"},
                       kBlur.sizeParameter()},
        .maps = kBlur.maps(),
        .postPasses = kBlur.passes(),
        .visibilityMap = "exponentials",
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                f.esmParams = {static_cast<float>(p.number("esm.c")),
                               static_cast<float>(p.number("esm.size")), 0.0f, 0.0f};
            },
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
