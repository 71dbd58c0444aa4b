// Technique `vssm` [Yang, Dong, Feng, Peng, Wang and Peng 2010, 'Variance soft shadow mapping']:
// PCSS's three steps on savsm's summed-area table of offset moments, each at a constant cost
// whatever the light's size: the blocker search reads the moments over the search box and takes
// the average blocker depth from Chebyshev's bound (chebyshevBlockers in moments.h), the
// penumbra follows from similar triangles, and the filter is the bound over a box of that width.
// The paper's answer to non-planar receivers, kernel subdivision, is `vssm.subdivision`: each
// sub-kernel is compared with the receiver's plane at its centre. Shader:
// shaders/include/shadow_sat.glsl (shadowSoftDetail, shared with msm-soft), its block
// params_tables.h; CPU mirror: softReference (src/shadows/cpu_tables.cpp); derivations in
// docs/techniques.md.
#include "moments.h"
#include "params_tables.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_tables.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

// savsm's offset moments, in a table of its own scale (the widest box is the search's).
constexpr SummedAreaTable kTable{.rowsShader = "vssm_sum_rows.comp",
                                 .columnsShader = "vssm_sum_columns.comp",
                                 .format = MapFormat::RG32UI};
constexpr SoftSearch kSearch{.maxRadiusKey = "vssm.maxRadius",
                             .cubeRadiusKey = "vssm.cubeRadius",
                             .subdivisionKey = "vssm.subdivision",
                             .refineKey = "vssm.refine",
                             // 4 by measurement on the corpus's grazing spots (docs/techniques.md).
                             .defaultSubdivision = 4};

std::vector<ParameterInfo> vssmParameters() {
    std::vector<ParameterInfo> parameters = kSearch.parameters();
    parameters.push_back({.key = "vssm.minVariance",
                          .type = ParameterType::Float,
                          .defaultValue = 1e-7,
                          .min = 0.0,
                          .max = 0.01,
                          .unit = "(depth range)^2",
                          .description = "least variance Chebyshev's bound assumes, in the search "
                                         "and the filter"});
    parameters.push_back({.key = "vssm.bleedReduction",
                          .type = ParameterType::Float,
                          .defaultValue = 0.1,
                          .min = 0.0,
                          .max = 0.99,
                          .description = "as vsm.bleedReduction, on each sub-kernel's bound"});
    return parameters;
}

} // namespace

const TechniqueModule& vssmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Vssm,
                 .name = "vssm",
                 .summary = "variance soft shadow maps: PCSS's blocker search, penumbra and "
                            "filter from a summed-area table of moments, at a constant cost",
                 .reference = "Yang et al. 2010, 'Variance soft shadow mapping'",
                 .families = {"bias", "vssm", "csm", "composite"}},
        .parameters = vssmParameters(),
        .maps = kTable.maps(),
        .postPasses = kTable.passes(),
        .visibilityMaps = {kMomentTable},
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                gpu::SoftParams s = kSearch.pack(p);
                s.minVariance = static_cast<float>(p.number("vssm.minVariance"));
                s.bleedReduction = static_cast<float>(p.number("vssm.bleedReduction"));
                block.set(s);
            },
        .reference =
            [](const FilterInput& in) {
                return softReference(MOMENTS_VSM, in.params.get<gpu::SoftParams>(), in);
            },
        .modelsLightSize = true,
        .blurRadiusTexels = [](const ParameterValues& p) { return kSearch.radiusTexels(p); },
        .cubeRadiusTexels = [](const ParameterValues& p) { return kSearch.cubeRadiusTexels(p); },
        .blockerSearchKey = kSearch.maxRadiusKey};
    return module;
}

} // namespace penumbra::shadows
