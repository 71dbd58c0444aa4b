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
                       {"hard", 0.025042, 0.000735, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.018416, 0.000349, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.018703, 0.000349, 0.000204, 0.000000},
                       {"pcf[box3]", 0.021224, 0.000273, 0.000000, 0.000000},
                       {"pcf[box7]", 0.027995, 0.000292, 0.000020, 0.000000},
                       {"pcf[box11]", 0.035546, 0.000424, 0.000092, 0.000000},
                       {"pcf[gauss7]", 0.023903, 0.000292, 0.000020, 0.000000},
                       {"pcf[poisson16]", 0.023703, 0.000292, 0.000020, 0.000000},
                       {"pcf[poisson32]", 0.023209, 0.000292, 0.000020, 0.000000},
                       {"pcf[adaptive-box7]", 0.027995, 0.000292, 0.000020, 0.000000},
                       {"pcss", 0.019691, 0.000368, 0.000000, 0.000000},
                       {"pcss[fast]", 0.019707, 0.000368, 0.000000, 0.000000},
                       {"second-depth", 0.025415, 0.000754, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.029469, 0.001065, 0.000173, 0.000000},
                       {"vsm", 0.020294, 0.000349, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.021262, 0.000358, 0.000000, 0.000000},
                       {"vsm[mip]", 0.022491, 0.000368, 0.000000, 0.000000},
                       {"esm", 0.023701, 0.000575, 0.000000, 0.000000},
                       {"evsm", 0.021419, 0.000358, 0.000000, 0.000000},
                       {"evsm[2]", 0.021774, 0.000368, 0.000000, 0.000000},
                       {"savsm", 0.027259, 0.000462, 0.000000, 0.000000},
                       {"msm", 0.021699, 0.000358, 0.000000, 0.000000},
                       {"msm[16]", 0.021905, 0.000387, 0.000000, 0.000000},
                       {"vssm", 0.020499, 0.000443, 0.000000, 0.000000},
                       {"msm-soft", 0.021346, 0.000500, 0.000000, 0.000000},
                       {"sdf", 0.040065, 0.001942, 0.000081, 0.000000},
                       {"pcf[box7-screen]", 0.028264, 0.000302, 0.000031, 0.000000},
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
                       {"hard", 0.035126, 0.000717, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.029032, 0.000179, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.029215, 0.000179, 0.000204, 0.000000},
                       {"pcf[box3]", 0.022611, 0.000170, 0.000000, 0.000000},
                       {"pcf[box7]", 0.018616, 0.000141, 0.000020, 0.000000},
                       {"pcf[box11]", 0.022136, 0.000207, 0.000092, 0.000000},
                       {"pcf[gauss7]", 0.019814, 0.000141, 0.000020, 0.000000},
                       {"pcf[poisson16]", 0.020616, 0.000141, 0.000020, 0.000000},
                       {"pcf[poisson32]", 0.020794, 0.000141, 0.000020, 0.000000},
                       {"pcf[adaptive-box7]", 0.018616, 0.000141, 0.000020, 0.000000},
                       {"pcss", 0.014714, 0.000151, 0.000000, 0.000000},
                       {"pcss[fast]", 0.021000, 0.000424, 0.000010, 0.000000},
                       {"second-depth", 0.035389, 0.000735, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.037836, 0.001018, 0.000173, 0.000000},
                       {"vsm", 0.026200, 0.000226, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.023607, 0.000207, 0.000000, 0.000000},
                       {"vsm[mip]", 0.024929, 0.000226, 0.000000, 0.000000},
                       {"esm", 0.027533, 0.000415, 0.000000, 0.000000},
                       {"evsm", 0.023494, 0.000217, 0.000000, 0.000000},
                       {"evsm[2]", 0.025438, 0.000226, 0.000000, 0.000000},
                       {"savsm", 0.022991, 0.000283, 0.000000, 0.000000},
                       {"msm", 0.023508, 0.000217, 0.000000, 0.000000},
                       {"msm[16]", 0.023788, 0.000255, 0.000000, 0.000000},
                       {"vssm", 0.015221, 0.000179, 0.000000, 0.000000},
                       {"msm-soft", 0.016278, 0.000226, 0.000000, 0.000000},
                       {"sdf", 0.028004, 0.000783, 0.000143, 0.000000},
                       {"pcf[box7-screen]", 0.018933, 0.000151, 0.000031, 0.000000},
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
                       {"hard", 0.040356, 0.001055, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.032821, 0.000298, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.032808, 0.000286, 0.000000, 0.000000},
                       {"pcf[box3]", 0.025278, 0.000286, 0.000000, 0.000000},
                       {"pcf[box7]", 0.025655, 0.000323, 0.000000, 0.000000},
                       {"pcf[box11]", 0.036187, 0.000608, 0.000000, 0.000000},
                       {"pcf[gauss7]", 0.022815, 0.000298, 0.000000, 0.000000},
                       {"pcf[poisson16]", 0.023231, 0.000298, 0.000000, 0.000000},
                       {"pcf[poisson32]", 0.023102, 0.000298, 0.000000, 0.000000},
                       {"pcf[adaptive-box7]", 0.025776, 0.000323, 0.000000, 0.000000},
                       {"pcss", 0.017900, 0.000248, 0.000000, 0.000000},
                       {"pcss[fast]", 0.033190, 0.001130, 0.000000, 0.000000},
                       {"second-depth", 0.041866, 0.001179, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.039521, 0.001030, 0.000044, 0.000000},
                       {"vsm", 0.030803, 0.000596, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.030841, 0.000670, 0.000000, 0.000000},
                       {"vsm[mip]", 0.033275, 0.000832, 0.000000, 0.000000},
                       {"esm", 0.046237, 0.002048, 0.000000, 0.000709},
                       {"evsm", 0.030030, 0.000683, 0.000000, 0.000000},
                       {"evsm[2]", 0.042084, 0.001291, 0.000000, 0.000000},
                       {"savsm", 0.030850, 0.000832, 0.000000, 0.000000},
                       {"msm", 0.028947, 0.000708, 0.000000, 0.000000},
                       {"msm[16]", 0.029511, 0.000732, 0.000000, 0.000000},
                       {"vssm", 0.028042, 0.000757, 0.000000, 0.000000},
                       {"msm-soft", 0.021690, 0.000459, 0.000000, 0.000000},
                       {"sdf", 0.048308, 0.003339, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.025801, 0.000323, 0.000000, 0.000177},
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
                       {"hard", 0.082374, 0.002954, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.078346, 0.001788, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.078342, 0.001788, 0.000000, 0.000000},
                       {"pcf[box3]", 0.072426, 0.000968, 0.000000, 0.000000},
                       {"pcf[box7]", 0.061397, 0.000385, 0.000000, 0.000000},
                       {"pcf[box11]", 0.052672, 0.000310, 0.000000, 0.000000},
                       {"pcf[gauss7]", 0.065675, 0.000645, 0.000000, 0.000000},
                       {"pcf[poisson16]", 0.067087, 0.000720, 0.000000, 0.000000},
                       {"pcf[poisson32]", 0.067493, 0.000720, 0.000000, 0.000000},
                       {"pcf[adaptive-box7]", 0.061450, 0.000385, 0.000000, 0.000000},
                       {"pcss", 0.021085, 0.000223, 0.000000, 0.006359},
                       {"pcss[fast]", 0.033271, 0.000708, 0.000286, 0.018624},
                       {"second-depth", 0.082956, 0.003078, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.081857, 0.002954, 0.000045, 0.000000},
                       {"vsm", 0.075406, 0.001378, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.072616, 0.000956, 0.000000, 0.000000},
                       {"vsm[mip]", 0.074263, 0.001204, 0.000000, 0.000000},
                       {"esm", 0.076913, 0.001502, 0.000000, 0.000908},
                       {"evsm", 0.072323, 0.000956, 0.000000, 0.000000},
                       {"evsm[2]", 0.074274, 0.001018, 0.000000, 0.000000},
                       {"savsm", 0.070139, 0.001105, 0.000000, 0.000000},
                       {"msm", 0.071226, 0.000993, 0.000000, 0.000000},
                       {"msm[16]", 0.071479, 0.000993, 0.000000, 0.000000},
                       {"vssm", 0.031105, 0.000981, 0.000000, 0.000000},
                       {"msm-soft", 0.025744, 0.000695, 0.000000, 0.000000},
                       {"sdf", 0.032401, 0.000546, 0.000421, 0.020441},
                       {"pcf[box7-screen]", 0.061363, 0.000385, 0.000000, 0.000227},
                       {"pcss-screen", 0.021381, 0.000223, 0.000000, 0.006814},
                   });
}
