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
        const ErrorMetrics m = measure(t, row);
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
        expectStored(what + " misclassified", m.misclassified, s.misclassified, tolerance,
                     storedFloor(1e-4));
        expectStored(what + " acne", m.acne, s.acne, tolerance, storedFloor(1e-4));
        expectStored(what + " leak", m.leak, s.leak, tolerance, storedFloor(1e-4));
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
                       {"hard", 0.024300, 0.000698, 0.000020, 0.000000},
                       {"pcf[bilinear]", 0.016634, 0.000311, 0.000051, 0.000000},
                       {"pcf[hardware]", 0.016818, 0.000311, 0.000051, 0.000000},
                       {"pcf[box3]", 0.019750, 0.000217, 0.000163, 0.000000},
                       {"pcf[box7]", 0.027400, 0.000236, 0.000316, 0.000000},
                       {"pcf[box11]", 0.035536, 0.000368, 0.000438, 0.000000},
                       {"pcf[gauss7]", 0.022856, 0.000217, 0.000234, 0.000000},
                       {"pcf[poisson16]", 0.022613, 0.000217, 0.000193, 0.000000},
                       {"pcf[poisson32]", 0.022043, 0.000217, 0.000193, 0.000000},
                       {"pcf[adaptive-box7]", 0.027400, 0.000236, 0.000316, 0.000000},
                       {"pcss", 0.017645, 0.000292, 0.000071, 0.000000},
                       {"pcss[fast]", 0.017692, 0.000292, 0.000071, 0.000000},
                       {"second-depth", 0.024300, 0.000698, 0.000020, 0.000000},
                       {"second-depth[nobias]", 0.029328, 0.001056, 0.000173, 0.000000},
                       {"vsm", 0.018902, 0.000283, 0.000102, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.018975, 0.000207, 0.000081, 0.000000},
                       {"vsm[mip]", 0.021240, 0.000292, 0.000132, 0.000000},
                       {"esm", 0.020995, 0.000368, 0.000041, 0.000000},
                       {"evsm", 0.019452, 0.000255, 0.000071, 0.000000},
                       {"evsm[2]", 0.019495, 0.000283, 0.000071, 0.000000},
                       {"savsm", 0.026693, 0.000396, 0.000316, 0.000000},
                       {"msm", 0.019449, 0.000236, 0.000061, 0.000000},
                       {"msm[16]", 0.019707, 0.000283, 0.000051, 0.000000},
                       {"vssm", 0.017852, 0.000330, 0.000031, 0.000000},
                       {"msm-soft", 0.018808, 0.000377, 0.000000, 0.000000},
                       {"sdf", 0.030365, 0.001160, 0.000000, 0.000000},
                       {"smrt", 0.024483, 0.000745, 0.000000, 0.000000},
                       {"smrt[fast]", 0.024640, 0.000726, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.027400, 0.000236, 0.000316, 0.000000},
                       {"pcss-screen", 0.017645, 0.000292, 0.000071, 0.000000},
                       {"hard+contact", 0.028641, 0.000933, 0.000020, 0.000000},
                       {"pcf[box3]+contact", 0.025257, 0.000443, 0.000163, 0.000000},
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
                       {"hard", 0.034649, 0.000679, 0.000020, 0.000000},
                       {"pcf[bilinear]", 0.027976, 0.000141, 0.000051, 0.000000},
                       {"pcf[hardware]", 0.028086, 0.000141, 0.000051, 0.000000},
                       {"pcf[box3]", 0.021283, 0.000104, 0.000163, 0.000000},
                       {"pcf[box7]", 0.017748, 0.000066, 0.000316, 0.000000},
                       {"pcf[box11]", 0.022153, 0.000132, 0.000438, 0.000000},
                       {"pcf[gauss7]", 0.018579, 0.000057, 0.000234, 0.000000},
                       {"pcf[poisson16]", 0.019392, 0.000057, 0.000193, 0.000000},
                       {"pcf[poisson32]", 0.019522, 0.000057, 0.000193, 0.000000},
                       {"pcf[adaptive-box7]", 0.017748, 0.000066, 0.000316, 0.000000},
                       {"pcss", 0.012631, 0.000075, 0.000183, 0.000000},
                       {"pcss[fast]", 0.020226, 0.000368, 0.000214, 0.000000},
                       {"second-depth", 0.034649, 0.000679, 0.000020, 0.000000},
                       {"second-depth[nobias]", 0.037742, 0.001009, 0.000173, 0.000000},
                       {"vsm", 0.024183, 0.000113, 0.000102, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.020830, 0.000066, 0.000081, 0.000000},
                       {"vsm[mip]", 0.022847, 0.000085, 0.000132, 0.000000},
                       {"esm", 0.023429, 0.000217, 0.000041, 0.000000},
                       {"evsm", 0.021228, 0.000113, 0.000071, 0.000000},
                       {"evsm[2]", 0.021918, 0.000132, 0.000071, 0.000000},
                       {"savsm", 0.021465, 0.000085, 0.000316, 0.000000},
                       {"msm", 0.021121, 0.000113, 0.000061, 0.000000},
                       {"msm[16]", 0.021406, 0.000151, 0.000051, 0.000000},
                       {"vssm", 0.011655, 0.000085, 0.000031, 0.000000},
                       {"msm-soft", 0.013104, 0.000151, 0.000000, 0.000000},
                       {"sdf", 0.020394, 0.000292, 0.000020, 0.000000},
                       {"smrt", 0.017828, 0.000245, 0.000000, 0.000000},
                       {"smrt[fast]", 0.018048, 0.000273, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.017748, 0.000066, 0.000316, 0.000000},
                       {"pcss-screen", 0.012631, 0.000075, 0.000183, 0.000000},
                       {"hard+contact", 0.037726, 0.000915, 0.000020, 0.000000},
                       {"pcf[box3]+contact", 0.026414, 0.000339, 0.000163, 0.000000},
                   });
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderTheSpot) {
    expectBaseline({.scene = "builtin:spot",
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   {
                       {"hard", 0.037787, 0.000844, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.029316, 0.000074, 0.000029, 0.000000},
                       {"pcf[hardware]", 0.029661, 0.000099, 0.000029, 0.000000},
                       {"pcf[box3]", 0.021102, 0.000062, 0.000087, 0.000000},
                       {"pcf[box7]", 0.023285, 0.000062, 0.000349, 0.000000},
                       {"pcf[box11]", 0.035510, 0.000422, 0.000698, 0.000000},
                       {"pcf[gauss7]", 0.019114, 0.000062, 0.000204, 0.000000},
                       {"pcf[poisson16]", 0.019504, 0.000050, 0.000175, 0.000000},
                       {"pcf[poisson32]", 0.019278, 0.000050, 0.000175, 0.000000},
                       {"pcf[adaptive-box7]", 0.023465, 0.000062, 0.000349, 0.000000},
                       {"pcss", 0.011393, 0.000062, 0.000058, 0.000000},
                       {"pcss[fast]", 0.030139, 0.000869, 0.000058, 0.000000},
                       {"second-depth", 0.037951, 0.000857, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.039440, 0.001005, 0.000044, 0.000000},
                       {"vsm", 0.022485, 0.000037, 0.000073, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.019004, 0.000050, 0.000073, 0.000000},
                       {"vsm[mip]", 0.024881, 0.000074, 0.000131, 0.000000},
                       {"esm", 0.023400, 0.000310, 0.000000, 0.000000},
                       {"evsm", 0.019782, 0.000112, 0.000029, 0.000000},
                       {"evsm[2]", 0.020872, 0.000112, 0.000000, 0.000000},
                       {"savsm", 0.024668, 0.000062, 0.000465, 0.000000},
                       {"msm", 0.019637, 0.000112, 0.000029, 0.000000},
                       {"msm[16]", 0.020109, 0.000124, 0.000029, 0.000000},
                       {"vssm", 0.009882, 0.000112, 0.000015, 0.000000},
                       {"msm-soft", 0.012083, 0.000124, 0.000000, 0.000000},
                       {"sdf", 0.037441, 0.001303, 0.000000, 0.000000},
                       {"smrt", 0.015251, 0.000149, 0.000000, 0.000000},
                       {"smrt[fast]", 0.016035, 0.000161, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.023285, 0.000062, 0.000349, 0.000000},
                       {"pcss-screen", 0.011393, 0.000062, 0.000058, 0.000000},
                       {"hard+contact", 0.042576, 0.001229, 0.000000, 0.000000},
                       {"pcf[box3]+contact", 0.028676, 0.000422, 0.000087, 0.000000},
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
                       {"hard", 0.081120, 0.002743, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.076951, 0.001527, 0.000030, 0.000000},
                       {"pcf[hardware]", 0.077055, 0.001552, 0.000030, 0.000000},
                       {"pcf[box3]", 0.071063, 0.000708, 0.000090, 0.000000},
                       {"pcf[box7]", 0.060442, 0.000174, 0.000361, 0.000000},
                       {"pcf[box11]", 0.052203, 0.000137, 0.000721, 0.000000},
                       {"pcf[gauss7]", 0.064475, 0.000397, 0.000210, 0.000000},
                       {"pcf[poisson16]", 0.065874, 0.000459, 0.000180, 0.000000},
                       {"pcf[poisson32]", 0.066263, 0.000459, 0.000180, 0.000000},
                       {"pcf[adaptive-box7]", 0.060514, 0.000174, 0.000361, 0.000000},
                       {"pcss", 0.021526, 0.000074, 0.000616, 0.013173},
                       {"pcss[fast]", 0.034800, 0.000608, 0.001262, 0.034522},
                       {"second-depth", 0.081153, 0.002756, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.081822, 0.002930, 0.000045, 0.000000},
                       {"vsm", 0.071717, 0.001043, 0.000075, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.068240, 0.000534, 0.000075, 0.000000},
                       {"vsm[mip]", 0.069784, 0.000757, 0.000135, 0.000000},
                       {"esm", 0.069472, 0.000658, 0.000000, 0.000000},
                       {"evsm", 0.068434, 0.000596, 0.000030, 0.000000},
                       {"evsm[2]", 0.067865, 0.000583, 0.000000, 0.000000},
                       {"savsm", 0.065764, 0.000621, 0.000481, 0.000000},
                       {"msm", 0.068318, 0.000596, 0.000030, 0.000000},
                       {"msm[16]", 0.068448, 0.000596, 0.000030, 0.000000},
                       {"vssm", 0.012966, 0.000037, 0.000030, 0.000000},
                       {"msm-soft", 0.015326, 0.000124, 0.000000, 0.000227},
                       {"sdf", 0.028610, 0.000261, 0.000210, 0.001363},
                       {"smrt", 0.019573, 0.000137, 0.000000, 0.000000},
                       {"smrt[fast]", 0.019854, 0.000137, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.060442, 0.000174, 0.000361, 0.000000},
                       {"pcss-screen", 0.021526, 0.000074, 0.000616, 0.013173},
                       {"hard+contact", 0.083458, 0.003128, 0.000000, 0.000000},
                       {"pcf[box3]+contact", 0.073711, 0.001092, 0.000090, 0.000000},
                   });
}
