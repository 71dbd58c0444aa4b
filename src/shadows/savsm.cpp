// Technique `savsm` [Lauritzen 2007, 'Summed-area variance shadow maps', GPU Gems 3 ch. 8]: two
// post passes build a summed-area table of the offset moments (shaders/include/sat_scan.glsl:
// rows, then columns, one invocation per line); the visibility pass
// (shaders/include/shadow_sat.glsl) averages the moments over a box of any width from four
// corners of the table (exact fractional edges) and bounds the lit fraction as VSM does. CPU
// mirror: savsmReference below (src/shadows/cpu_tables.cpp: the table); derivations and
// precision in docs/techniques.md. Its block: params_tables.h.
#include <algorithm>

#include "moments.h"
#include "params_tables.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_tables.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr SummedAreaTable kTable{.rowsShader = "savsm_sum_rows.comp",
                                 .columnsShader = "savsm_sum_columns.comp",
                                 .format = MapFormat::RG32UI};

// shadowSavsmDetail: x visibility, yz the box's mean offset moments, w the receiver's offset
// moment depth.
glm::vec4 savsmReference(const FilterInput& in) {
    const gpu::SavsmParams p = in.params.get<gpu::SavsmParams>();
    const MomentTable table(in.map, in.view, MOMENTS_VSM, p.tableScale);
    const float size = static_cast<float>(in.map.size);
    glm::vec2 lo, hi;
    satBox(in.probe.uv, 0.5f * std::max(p.size * in.view.cascade.z, 1.0f), size, lo, hi);
    const glm::vec2 moments(table.boxMean(MOMENTS_VSM, p.tableScale, lo, hi));
    const float t = gpu::momentDepth(in.view, in.probe.depth) - 0.5f;
    const float v = gpu::chebyshevUpperBound(moments, t, p.minVariance);
    return {gpu::snapToExtremes(gpu::reduceLightBleeding(v, p.bleedReduction)), moments, t};
}

} // namespace

const TechniqueModule& savsmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Savsm,
                 .name = "savsm",
                 .summary = "summed-area variance shadow maps: box-filtered moments of any width "
                            "at a constant cost, from a summed-area table",
                 .reference = "Lauritzen 2007, 'Summed-area variance shadow maps' (GPU Gems 3)",
                 .families = {"bias", "savsm", "csm", "composite"}},
        .parameters = {{.key = "savsm.size",
                        .type = ParameterType::Float,
                        .defaultValue = 7.0,
                        .min = 1.0,
                        .max = 256.0,
                        .unit = "texels",
                        .description =
                            "width of the box the moments are averaged over (fractional widths "
                            "are exact)"},
                       {.key = "savsm.minVariance",
                        .type = ParameterType::Float,
                        .defaultValue = 1e-7,
                        .min = 0.0,
                        .max = 0.01,
                        .unit = "(depth range)^2",
                        .description =
                            "least variance Chebyshev's bound assumes (also hides the table's "
                            "rounding)"},
                       {.key = "savsm.bleedReduction",
                        .type = ParameterType::Float,
                        .defaultValue = 0.2,
                        .min = 0.0,
                        .max = 0.99,
                        .description = "as vsm.bleedReduction"}},
        .maps = kTable.maps(),
        .postPasses = kTable.passes(),
        .visibilityMaps = {kMomentTable},
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                block.set(gpu::SavsmParams{
                    .size = static_cast<float>(p.number("savsm.size")),
                    .minVariance = static_cast<float>(p.number("savsm.minVariance")),
                    .bleedReduction = static_cast<float>(p.number("savsm.bleedReduction")),
                    .tableScale = fixedPointScale(p.number("savsm.size"))});
            },
        .reference = savsmReference,
        .blurRadiusTexels =
            [](const ParameterValues& p) { return 0.5 * p.number("savsm.size") + 1.0; }};
    return module;
}

} // namespace penumbra::shadows
