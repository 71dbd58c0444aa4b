// Technique `esm` [Annen et al. 2008, 'Exponential shadow maps'; Salvi 2008, 'Rendering filtered
// shadows with exponential shadow maps']: the map keeps e^(c z) of the moment depth, blurred
// like VSM's moments (shaders/include/moments_blur.glsl); the visibility is the filtered value
// over e^(c t), at most 1 (shaders/include/shadow_moments.glsl; its block params_moments.h). CPU
// mirror: esmReference below; derivations in docs/techniques.md.
#include "moments.h"
#include "params_moments.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_moments.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr GaussianBlur kBlur{.sizeKey = "esm.size",
                             .rowsShader = "esm_blur_rows.comp",
                             .columnsShader = "esm_blur_columns.comp",
                             .output = "exponentials",
                             .format = MapFormat::R32F};

// shadowEsmDetail: x visibility, y the filtered e^(c z), z the receiver's moment depth.
glm::vec4 esmReference(const FilterInput& in) {
    const gpu::EsmParams p = in.params.get<gpu::EsmParams>();
    const float filtered =
        momentsAt(in.map, MOMENTS_ESM, p.size, glm::vec2(p.c), in.view, in.probe.uv).x;
    const float t = gpu::momentDepth(in.view, in.probe.depth);
    return {gpu::snapToExtremes(gpu::exponentialVisibility(filtered, t, p.c)), filtered, t, 0.0f};
}

} // namespace

const TechniqueModule& esmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Esm,
                 .name = "esm",
                 .summary = "exponential shadow maps: blurred e^(c z), the lit fraction "
                            "e^(-c t) E[e^(c z)] (one channel; light near contact)",
                 .reference = "Annen et al. 2008, 'Exponential shadow maps'; Salvi 2008",
                 .families = {"bias", "esm", "csm", "composite"}},
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
        .visibilityMaps = {"exponentials"},
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                block.set(gpu::EsmParams{.c = static_cast<float>(p.number("esm.c")),
                                         .size = static_cast<uint32_t>(p.number("esm.size"))});
            },
        .reference = esmReference,
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
