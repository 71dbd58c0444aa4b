// Technique `msm-soft` [Peters, Munstermann, Wetzstein and Klein 2016, 'Beyond hard shadows:
// moment shadow maps for single scattering, soft shadows and translucent occluders']: PCSS's
// three steps on a summed-area table of four fixed-point moments. The blocker search takes the
// blockers' weight and mean depth from the Hamburger reconstruction's atoms in front of the
// receiver (momentBlockers in moments.h), the filter is moment shadow mapping's bound over a
// box of the penumbra's width. Shared with vssm: shaders/include/shadow_sat.glsl
// (shadowSoftDetail), its block params_tables.h; CPU mirror: softReference
// (src/shadows/cpu_tables.cpp); derivations in
// docs/techniques.md.
#include "moments.h"
#include "params_tables.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_tables.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr SummedAreaTable kTable{.rowsShader = "msm_soft_sum_rows.comp",
                                 .columnsShader = "msm_soft_sum_columns.comp",
                                 .format = MapFormat::RGBA32UI};
constexpr SoftSearch kSearch{.maxRadiusKey = "msm-soft.maxRadius",
                             .cubeRadiusKey = "msm-soft.cubeRadius",
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
                 .families = {"bias", "msm-soft", "csm", "composite"}},
        .parameters = msmSoftParameters(),
        .maps = kTable.maps(),
        .postPasses = kTable.passes(),
        .visibilityMaps = {kMomentTable},
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                gpu::SoftParams s = kSearch.pack(p);
                s.momentBias = static_cast<float>(p.number("msm-soft.bias"));
                block.set(s);
            },
        .reference =
            [](const FilterInput& in) {
                return softReference(MOMENTS_MSM, in.params.get<gpu::SoftParams>(), in);
            },
        .modelsLightSize = true,
        .blurRadiusTexels = [](const ParameterValues& p) { return kSearch.radiusTexels(p); },
        .cubeRadiusTexels = [](const ParameterValues& p) { return kSearch.cubeRadiusTexels(p); },
        .blockerSearchKey = kSearch.maxRadiusKey};
    return module;
}

} // namespace penumbra::shadows
