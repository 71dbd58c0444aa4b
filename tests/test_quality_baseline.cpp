// Every row `penumbra compare` shows, against the ray-traced truth on four small set-ups (a sun
// and a spot, each small and large), with the error each row measured when the table was made
// (lavapipe; map 1024 so that filters and aliasing show at 512x288). A row that gets 15% worse
// (or better: then the table is stale) on any metric fails, and so does a row that appears or
// disappears: the table names every row. PENUMBRA_PRINT_BASELINE=1 prints the table afresh.
#include "truth_fixture.h"

#include <fmt/format.h>

#include <cstdlib>
#include <map>

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct StoredRow {
    const char* row;
    double rmse, misclassified, acne, leak;
};

// The compare rows, and screen-space receiver-plane bias (the rows use the light-space one),
// which only a stored measurement sees: on a plane both agree.
std::vector<TechniqueRow> rowsToMeasure() {
    std::vector<TechniqueRow> rows = comparisonRows("");
    rows.push_back(
        {.name = "pcf[box7-screen]",
         .technique = Technique::Pcf,
         .sets = {{"pcf.filter", "box"}, {"pcf.size", "7"}, {"bias.receiver", "screen"}}});
    rows.push_back({.name = "pcss-screen",
                    .technique = Technique::Pcss,
                    .sets = {{"bias.receiver", "screen"}}});
    return rows;
}

void expectBaseline(const TruthSetup& setup, const std::vector<StoredRow>& table) {
    const Truth t = groundTruth(setup);
    const bool print = std::getenv("PENUMBRA_PRINT_BASELINE") != nullptr;
    std::map<std::string, const StoredRow*> stored;
    for (const StoredRow& s : table)
        stored[s.row] = &s;
    std::string where = setup.scene;
    if (setup.angle >= 0)
        where += fmt::format(" sun {:g} deg", setup.angle);
    if (setup.radius >= 0)
        where += fmt::format(" radius {:g}", setup.radius);
    for (const TechniqueRow& row : rowsToMeasure()) {
        const ErrorMetrics m = measure(t, row.technique, row.sets);
        std::printf("%-44s rmse %.5f misclassified %.4f%% acne %.4f%% leak %.4f%%\n",
                    (where + " " + row.name).c_str(), m.rmse, 100 * m.misclassified, 100 * m.acne,
                    100 * m.leak);
        if (print)
            std::printf("    {\"%s\", %.6f, %.6f, %.6f, %.6f},\n", row.name.c_str(), m.rmse,
                        m.misclassified, m.acne, m.leak);
        const auto it = stored.find(row.name);
        if (it == stored.end()) {
            ADD_FAILURE() << where << ": row " << row.name << " has no stored metrics";
            continue;
        }
        const StoredRow& s = *it->second;
        const std::string what = where + " " + row.name;
        const double tolerance = storedTolerance();
        expectStored(what + " rmse", m.rmse, s.rmse, tolerance, 2e-4);
        expectStored(what + " misclassified", m.misclassified, s.misclassified, tolerance, 1e-4);
        expectStored(what + " acne", m.acne, s.acne, tolerance, 1e-4);
        expectStored(what + " leak", m.leak, s.leak, tolerance, 1e-4);
        stored.erase(it);
    }
    for (const auto& [name, row] : stored)
        ADD_FAILURE() << where << ": stored row " << name << " is no longer a compare row";
}

} // namespace

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderTheSun) {
    expectBaseline({.scene = "builtin:showcase",
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   {
                       {"hard", 0.028055, 0.000896, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.022341, 0.000509, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.022579, 0.000509, 0.000204, 0.000000},
                       {"pcf[box3]", 0.024707, 0.000434, 0.000000, 0.000000},
                       {"pcf[box7]", 0.030720, 0.000453, 0.000020, 0.000000},
                       {"pcf[box11]", 0.037729, 0.000585, 0.000092, 0.000000},
                       {"pcf[gauss7]", 0.027043, 0.000453, 0.000020, 0.000000},
                       {"pcf[poisson16]", 0.026866, 0.000453, 0.000020, 0.000000},
                       {"pcf[poisson32]", 0.026432, 0.000453, 0.000020, 0.000000},
                       {"pcf[adaptive-box7]", 0.030720, 0.000453, 0.000020, 0.000000},
                       {"pcss", 0.019691, 0.000368, 0.000000, 0.000000},
                       {"pcss[fast]", 0.019707, 0.000368, 0.000000, 0.000000},
                       {"second-depth", 0.028389, 0.000915, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.031773, 0.001207, 0.000173, 0.000000},
                       {"vsm", 0.023914, 0.000509, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.024740, 0.000519, 0.000000, 0.000000},
                       {"vsm[mip]", 0.025804, 0.000528, 0.000000, 0.000000},
                       {"esm", 0.026865, 0.000735, 0.000000, 0.000000},
                       {"evsm", 0.024875, 0.000519, 0.000000, 0.000000},
                       {"evsm[2]", 0.025182, 0.000528, 0.000000, 0.000000},
                       {"savsm", 0.030050, 0.000622, 0.000000, 0.000000},
                       {"msm", 0.025117, 0.000519, 0.000000, 0.000000},
                       {"msm[16]", 0.025313, 0.000547, 0.000000, 0.000000},
                       {"vssm", 0.020499, 0.000443, 0.000000, 0.000000},
                       {"msm-soft", 0.021346, 0.000500, 0.000000, 0.000000},
                       {"sdf", 0.040065, 0.001942, 0.000081, 0.000000},
                       {"pcf[box7-screen]", 0.030692, 0.000462, 0.000031, 0.000000},
                       {"pcss-screen", 0.019798, 0.000368, 0.000000, 0.000000},
                   });
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderALargeSun) {
    expectBaseline({.scene = "builtin:showcase",
                    .angle = 4.0f,
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   {
                       {"hard", 0.036568, 0.000877, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.030762, 0.000339, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.030934, 0.000339, 0.000204, 0.000000},
                       {"pcf[box3]", 0.024793, 0.000330, 0.000000, 0.000000},
                       {"pcf[box7]", 0.021212, 0.000302, 0.000020, 0.000000},
                       {"pcf[box11]", 0.024361, 0.000368, 0.000092, 0.000000},
                       {"pcf[gauss7]", 0.022272, 0.000302, 0.000020, 0.000000},
                       {"pcf[poisson16]", 0.022988, 0.000302, 0.000020, 0.000000},
                       {"pcf[poisson32]", 0.023147, 0.000302, 0.000020, 0.000000},
                       {"pcf[adaptive-box7]", 0.021212, 0.000302, 0.000020, 0.000000},
                       {"pcss", 0.014714, 0.000151, 0.000000, 0.000000},
                       {"pcss[fast]", 0.021000, 0.000424, 0.000010, 0.000000},
                       {"second-depth", 0.036821, 0.000896, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.038937, 0.001160, 0.000173, 0.000000},
                       {"vsm", 0.028105, 0.000387, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.025704, 0.000368, 0.000000, 0.000000},
                       {"vsm[mip]", 0.026923, 0.000387, 0.000000, 0.000000},
                       {"esm", 0.029351, 0.000575, 0.000000, 0.000000},
                       {"evsm", 0.025600, 0.000377, 0.000000, 0.000000},
                       {"evsm[2]", 0.027396, 0.000387, 0.000000, 0.000000},
                       {"savsm", 0.025139, 0.000443, 0.000000, 0.000000},
                       {"msm", 0.025613, 0.000377, 0.000000, 0.000000},
                       {"msm[16]", 0.025889, 0.000415, 0.000000, 0.000000},
                       {"vssm", 0.015221, 0.000179, 0.000000, 0.000000},
                       {"msm-soft", 0.016278, 0.000226, 0.000000, 0.000000},
                       {"sdf", 0.028004, 0.000783, 0.000143, 0.000000},
                       {"pcf[box7-screen]", 0.021234, 0.000273, 0.000031, 0.000000},
                       {"pcss-screen", 0.014798, 0.000160, 0.000000, 0.000000},
                   });
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderTheSpot) {
    expectBaseline({.scene = "builtin:spot",
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   {
                       {"hard", 0.043361, 0.001440, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.036452, 0.000683, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.036440, 0.000670, 0.000000, 0.000000},
                       {"pcf[box3]", 0.029842, 0.000670, 0.000000, 0.000000},
                       {"pcf[box7]", 0.030161, 0.000708, 0.000000, 0.000000},
                       {"pcf[box11]", 0.039510, 0.000993, 0.000000, 0.000000},
                       {"pcf[gauss7]", 0.027786, 0.000683, 0.000000, 0.000000},
                       {"pcf[poisson16]", 0.028129, 0.000683, 0.000000, 0.000000},
                       {"pcf[poisson32]", 0.028022, 0.000683, 0.000000, 0.000000},
                       {"pcf[adaptive-box7]", 0.030264, 0.000708, 0.000000, 0.000000},
                       {"pcss", 0.017900, 0.000248, 0.000000, 0.000000},
                       {"pcss[fast]", 0.033190, 0.001130, 0.000000, 0.000000},
                       {"second-depth", 0.044769, 0.001564, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.042438, 0.001403, 0.000044, 0.000000},
                       {"vsm", 0.034646, 0.000981, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.034680, 0.001055, 0.000000, 0.000000},
                       {"vsm[mip]", 0.036861, 0.001216, 0.000000, 0.000000},
                       {"esm", 0.048882, 0.002433, 0.000000, 0.000709},
                       {"evsm", 0.033961, 0.001068, 0.000000, 0.000000},
                       {"evsm[2]", 0.044974, 0.001676, 0.000000, 0.000000},
                       {"savsm", 0.034688, 0.001216, 0.000000, 0.000000},
                       {"msm", 0.033007, 0.001092, 0.000000, 0.000000},
                       {"msm[16]", 0.033503, 0.001117, 0.000000, 0.000000},
                       {"vssm", 0.028042, 0.000757, 0.000000, 0.000000},
                       {"msm-soft", 0.021690, 0.000459, 0.000000, 0.000000},
                       {"sdf", 0.048308, 0.003339, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.029308, 0.000670, 0.000000, 0.000177},
                       {"pcss-screen", 0.017904, 0.000248, 0.000000, 0.000000},
                   });
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderALargeSpot) {
    expectBaseline({.scene = "builtin:spot",
                    .radius = 1.0f,
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   {
                       {"hard", 0.083150, 0.003327, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.079162, 0.002160, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.079158, 0.002160, 0.000000, 0.000000},
                       {"pcf[box3]", 0.073309, 0.001341, 0.000000, 0.000000},
                       {"pcf[box7]", 0.062435, 0.000757, 0.000000, 0.000000},
                       {"pcf[box11]", 0.053879, 0.000683, 0.000000, 0.000000},
                       {"pcf[gauss7]", 0.066647, 0.001018, 0.000000, 0.000000},
                       {"pcf[poisson16]", 0.068039, 0.001092, 0.000000, 0.000000},
                       {"pcf[poisson32]", 0.068439, 0.001092, 0.000000, 0.000000},
                       {"pcf[adaptive-box7]", 0.062487, 0.000757, 0.000000, 0.000000},
                       {"pcss", 0.021085, 0.000223, 0.000000, 0.006359},
                       {"pcss[fast]", 0.033271, 0.000708, 0.000286, 0.018624},
                       {"second-depth", 0.083727, 0.003451, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.082605, 0.003314, 0.000045, 0.000000},
                       {"vsm", 0.076254, 0.001750, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.073496, 0.001328, 0.000000, 0.000000},
                       {"vsm[mip]", 0.075124, 0.001576, 0.000000, 0.000000},
                       {"esm", 0.077744, 0.001874, 0.000000, 0.000908},
                       {"evsm", 0.073207, 0.001328, 0.000000, 0.000000},
                       {"evsm[2]", 0.075134, 0.001390, 0.000000, 0.000000},
                       {"savsm", 0.071049, 0.001477, 0.000000, 0.000000},
                       {"msm", 0.072123, 0.001365, 0.000000, 0.000000},
                       {"msm[16]", 0.072373, 0.001365, 0.000000, 0.000000},
                       {"vssm", 0.031105, 0.000981, 0.000000, 0.000000},
                       {"msm-soft", 0.025744, 0.000695, 0.000000, 0.000000},
                       {"sdf", 0.032401, 0.000546, 0.000421, 0.020441},
                       {"pcf[box7-screen]", 0.062083, 0.000509, 0.000000, 0.000227},
                       {"pcss-screen", 0.021381, 0.000223, 0.000000, 0.006814},
                   });
}
