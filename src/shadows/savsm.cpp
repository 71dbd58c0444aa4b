// Technique `savsm` [Lauritzen 2007, 'Summed-area variance shadow maps', GPU Gems 3 ch. 8]: two
// post passes build a summed-area table of the offset moments (shaders/include/sat_scan.glsl:
// rows, then columns, one invocation per line); the visibility pass
// (shaders/include/shadow_sat.glsl) averages the moments over a box of any width from four
// corners of the table (exact fractional edges) and bounds the lit fraction as VSM does. CPU
// mirror: src/reference/filter_reference.cpp; derivations and precision in docs/techniques.md.
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr SummedAreaTable kTable{.rowsShader = "savsm_sum_rows.comp",
                                 .columnsShader = "savsm_sum_columns.comp",
                                 .format = MapFormat::RG32UI};

} // namespace

const TechniqueModule& savsmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Savsm,
                 .name = "savsm",
                 .summary = "summed-area variance shadow maps: box-filtered moments of any width "
                            "at a constant cost, from a summed-area table",
                 .reference = "Lauritzen 2007, 'Summed-area variance shadow maps' (GPU Gems 3)",
                 .families = {"bias", "savsm", "csm", "composite"},
                 .variants = {{.label = ""}}},
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
        .visibilityMap = kMomentTable,
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                f.savsmParams = {static_cast<float>(p.number("savsm.size")),
                                 static_cast<float>(p.number("savsm.minVariance")),
                                 static_cast<float>(p.number("savsm.bleedReduction")), 0.0f};
                f.tableScales.x = fixedPointScale(p.number("savsm.size"));
            },
        .blurRadiusTexels =
            [](const ParameterValues& p) { return 0.5 * p.number("savsm.size") + 1.0; }};
    return module;
}

} // namespace penumbra::shadows
