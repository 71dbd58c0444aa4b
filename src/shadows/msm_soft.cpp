// Technique `msm-soft` [Peters, Munstermann, Wetzstein and Klein 2016, 'Beyond hard shadows:
// moment shadow maps for single scattering, soft shadows and translucent occluders']: PCSS's
// three steps on a summed-area table of four fixed-point moments. The blocker search takes the
// blockers' weight and mean depth from the Hamburger reconstruction's atoms in front of the
// receiver (momentBlockers in filter_math.h), the filter is moment shadow mapping's bound over a
// box of the penumbra's width. Shared with vssm: shaders/include/shadow_sat.glsl
// (shadowSoftDetail); CPU mirror: src/reference/sat_reference.cpp; derivations in
// docs/techniques.md.
#include "filter_math.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr SummedAreaTable kTable{.rowsShader = "msm_soft_sum_rows.comp",
                                 .columnsShader = "msm_soft_sum_columns.comp",
                                 .format = MapFormat::RGBA32UI};

} // namespace

const TechniqueModule& msmSoftModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::MsmSoft,
                 .name = "msm-soft",
                 .summary = "moment soft shadows: PCSS's blocker search, penumbra and filter "
                            "from a summed-area table of four moments, at a constant cost",
                 .reference = "Peters et al. 2016, 'Beyond hard shadows: moment shadow maps for "
                              "single scattering, soft shadows and translucent occluders'",
                 .families = {"bias", "msm-soft", "csm", "composite"},
                 .variants = {{.label = ""}}},
        .parameters = {{.key = "msm-soft.maxRadius",
                        .type = ParameterType::Float,
                        .defaultValue = 64.0,
                        .min = 1.0,
                        .max = 256.0,
                        .unit = "texels",
                        .description = "largest blocker-search and filter half-width, in texels "
                                       "of the map sampled (also the guard band of cube faces "
                                       "and cascades; wider boxes leave fewer fixed-point bits)"},
                       {.key = "msm-soft.bias",
                        .type = ParameterType::Float,
                        .defaultValue = 1e-4,
                        .min = 0.0,
                        .max = 0.01,
                        .description = "moment bias, as msm.bias; covers the table's fixed-point "
                                       "rounding too"},
                       {.key = "msm-soft.subdivision",
                        .type = ParameterType::Int,
                        .defaultValue = 3,
                        .min = 1,
                        .max = VSSM_MAX_SUBDIVISION,
                        .unit = "sub-kernels per axis",
                        .description = "as vssm.subdivision"},
                       {.key = "msm-soft.refine",
                        .type = ParameterType::Bool,
                        .defaultValue = 1,
                        .description = "as vssm.refine"}},
        .maps = kTable.maps(),
        .postPasses = kTable.passes(),
        .visibilityMap = kMomentTable,
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                f.msmSoftParams = {static_cast<float>(p.number("msm-soft.maxRadius")),
                                   static_cast<float>(p.number("msm-soft.bias")), 0.0f, 0.0f};
                f.softMode.z = static_cast<uint32_t>(p.number("msm-soft.subdivision"));
                f.softMode.w = p.number("msm-soft.refine") != 0.0 ? 1u : 0u;
                f.tableScales.z = fixedPointScale(2.0 * p.number("msm-soft.maxRadius"));
            },
        .modelsLightSize = true,
        .blurRadiusTexels =
            [](const ParameterValues& p) { return p.number("msm-soft.maxRadius") + 1.0; }};
    return module;
}

} // namespace penumbra::shadows
