// Technique `msm-soft` [Peters, Munstermann, Wetzstein and Klein 2016, 'Beyond hard shadows:
// moment shadow maps for single scattering, soft shadows and translucent occluders']: PCSS's
// three steps on a summed-area table of four fixed-point moments. The blocker search takes the
// blockers' weight and mean depth from the Hamburger reconstruction's atoms in front of the
// receiver (momentBlockers in moments.h), the filter is moment shadow mapping's bound over a
// box of the penumbra's width. Shared with vssm: shaders/include/shadow_sat.glsl
// (shadowSoftDetail); CPU mirror: src/reference/sat_reference.cpp; derivations in
// docs/techniques.md.
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr SummedAreaTable kTable{.rowsShader = "msm_soft_sum_rows.comp",
                                 .columnsShader = "msm_soft_sum_columns.comp",
                                 .format = MapFormat::RGBA32UI};
constexpr SoftSearch kSearch{.maxRadiusKey = "msm-soft.maxRadius",
                             .subdivisionKey = "msm-soft.subdivision",
                             .refineKey = "msm-soft.refine"};

std::vector<ParameterInfo> msmSoftParameters() {
    std::vector<ParameterInfo> parameters = kSearch.parameters();
    parameters.push_back({.key = "msm-soft.bias",
                          .type = ParameterType::Float,
                          .defaultValue = 1e-4,
                          .min = 0.0,
                          .max = 0.01,
                          .description = "moment bias, as msm.bias; covers the table's "
                                         "fixed-point rounding too"});
    return parameters;
}

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
        .parameters = msmSoftParameters(),
        .maps = kTable.maps(),
        .postPasses = kTable.passes(),
        .visibilityMap = kMomentTable,
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                const SoftSearch::Packed s = kSearch.pack(p);
                f.msmSoftParams = {s.maxRadius, static_cast<float>(p.number("msm-soft.bias")), 0.0f,
                                   0.0f};
                f.softMode.z = s.subdivision;
                f.softMode.w = s.refine;
                f.tableScales.z = s.tableScale;
            },
        .modelsLightSize = true,
        .blurRadiusTexels = [](const ParameterValues& p) { return kSearch.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
