// Technique `vssm` [Yang, Dong, Feng, Peng, Wang and Peng 2010, 'Variance soft shadow mapping']:
// PCSS's three steps on savsm's summed-area table of offset moments, each at a constant cost
// whatever the light's size: the blocker search reads the moments over the search box and takes
// the average blocker depth from Chebyshev's bound (chebyshevBlockers in filter_math.h), the
// penumbra follows from similar triangles, and the filter is the bound over a box of that width.
// The paper's answer to non-planar receivers, kernel subdivision, is `vssm.subdivision`: each
// sub-kernel is compared with the receiver's plane at its centre. Shader:
// shaders/include/shadow_sat.glsl; CPU mirror: src/reference/filter_reference.cpp; derivations
// in docs/techniques.md.
#include "filter_math.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

// savsm's offset moments, in a table of its own scale (the widest box is the search's).
constexpr SummedAreaTable kTable{.rowsShader = "vssm_sum_rows.comp",
                                 .columnsShader = "vssm_sum_columns.comp",
                                 .format = MapFormat::RG32UI};

} // namespace

const TechniqueModule& vssmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Vssm,
                 .name = "vssm",
                 .summary = "variance soft shadow maps: PCSS's blocker search, penumbra and "
                            "filter from a summed-area table of moments, at a constant cost",
                 .reference = "Yang et al. 2010, 'Variance soft shadow mapping'",
                 .families = {"bias", "vssm", "csm", "composite"},
                 .variants = {{.label = ""}}},
        .parameters = {{.key = "vssm.maxRadius",
                        .type = ParameterType::Float,
                        .defaultValue = 64.0,
                        .min = 1.0,
                        .max = 256.0,
                        .unit = "texels",
                        .description = "largest blocker-search and filter half-width, in texels "
                                       "of the map sampled (also the guard band of cube faces "
                                       "and cascades)"},
                       {.key = "vssm.minVariance",
                        .type = ParameterType::Float,
                        .defaultValue = 1e-5,
                        .min = 0.0,
                        .max = 0.01,
                        .unit = "(depth range)^2",
                        .description = "least variance Chebyshev's bound assumes, in the search "
                                       "and the filter"},
                       {.key = "vssm.bleedReduction",
                        .type = ParameterType::Float,
                        .defaultValue = 0.1,
                        .min = 0.0,
                        .max = 0.99,
                        .description = "as vsm.bleedReduction, on each sub-kernel's bound"},
                       {.key = "vssm.subdivision",
                        .type = ParameterType::Int,
                        .defaultValue = 3,
                        .min = 1,
                        .max = VSSM_MAX_SUBDIVISION,
                        .unit = "sub-kernels per axis",
                        .description = "kernel subdivision for non-planar receivers: the search "
                                       "and filter boxes are cut into n x n sub-kernels, each "
                                       "bounded on its own (1: the whole box at once)"},
                       {.key = "vssm.refine",
                        .type = ParameterType::Bool,
                        .defaultValue = 1,
                        .description = "search again over the region where blockers at the first "
                                       "estimate's depth can hide the light (the penumbra's own "
                                       "box), so blockers far off to the side do not widen it"}},
        .maps = kTable.maps(),
        .postPasses = kTable.passes(),
        .visibilityMap = kMomentTable,
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                f.vssmParams = {static_cast<float>(p.number("vssm.maxRadius")),
                                static_cast<float>(p.number("vssm.minVariance")),
                                static_cast<float>(p.number("vssm.bleedReduction")), 0.0f};
                f.softMode.x = static_cast<uint32_t>(p.number("vssm.subdivision"));
                f.softMode.y = p.number("vssm.refine") != 0.0 ? 1u : 0u;
                f.tableScales.y = fixedPointScale(2.0 * p.number("vssm.maxRadius"));
            },
        .modelsLightSize = true,
        .blurRadiusTexels =
            [](const ParameterValues& p) { return p.number("vssm.maxRadius") + 1.0; }};
    return module;
}

} // namespace penumbra::shadows
