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
                       {"hard", 0.025673, 0.000773, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.019287, 0.000387, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.019562, 0.000387, 0.000204, 0.000000},
                       {"pcf[box3]", 0.021993, 0.000311, 0.000000, 0.000000},
                       {"pcf[box7]", 0.028576, 0.000330, 0.000020, 0.000000},
                       {"pcf[box11]", 0.035982, 0.000462, 0.000092, 0.000000},
                       {"pcf[gauss7]", 0.024582, 0.000330, 0.000020, 0.000000},
                       {"pcf[poisson16]", 0.024389, 0.000330, 0.000020, 0.000000},
                       {"pcf[poisson32]", 0.023911, 0.000330, 0.000020, 0.000000},
                       {"pcf[adaptive-box7]", 0.028576, 0.000330, 0.000020, 0.000000},
                       {"pcss", 0.020522, 0.000405, 0.000000, 0.000000},
                       {"pcss[fast]", 0.020539, 0.000405, 0.000000, 0.000000},
                       {"second-depth", 0.026038, 0.000792, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.029716, 0.001084, 0.000173, 0.000000},
                       {"vsm", 0.021219, 0.000396, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.022185, 0.000415, 0.000000, 0.000000},
                       {"esm", 0.024445, 0.000603, 0.000000, 0.000000},
                       {"evsm", 0.022180, 0.000396, 0.000000, 0.000000},
                       {"evsm[2]", 0.022419, 0.000387, 0.000000, 0.000000},
                       {"savsm", 0.027864, 0.000500, 0.000000, 0.000000},
                       {"msm", 0.022421, 0.000396, 0.000000, 0.000000},
                       {"msm[16]", 0.022649, 0.000424, 0.000000, 0.000000},
                       {"vssm", 0.021558, 0.000490, 0.000000, 0.000000},
                       {"msm-soft", 0.022112, 0.000537, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.028801, 0.000339, 0.000031, 0.000000},
                       {"pcss-screen", 0.020628, 0.000405, 0.000000, 0.000000},
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
                       {"hard", 0.035267, 0.000754, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.029200, 0.000217, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.029382, 0.000217, 0.000203, 0.000000},
                       {"pcf[box3]", 0.022814, 0.000207, 0.000000, 0.000000},
                       {"pcf[box7]", 0.018853, 0.000179, 0.000020, 0.000000},
                       {"pcf[box11]", 0.022298, 0.000245, 0.000092, 0.000000},
                       {"pcf[gauss7]", 0.020043, 0.000179, 0.000020, 0.000000},
                       {"pcf[poisson16]", 0.020839, 0.000179, 0.000020, 0.000000},
                       {"pcf[poisson32]", 0.021016, 0.000179, 0.000020, 0.000000},
                       {"pcf[adaptive-box7]", 0.018853, 0.000179, 0.000020, 0.000000},
                       {"pcss", 0.016131, 0.000160, 0.000000, 0.000000},
                       {"pcss[fast]", 0.022017, 0.000434, 0.000010, 0.000000},
                       {"second-depth", 0.035529, 0.000773, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.037928, 0.001037, 0.000173, 0.000000},
                       {"vsm", 0.026484, 0.000273, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.023953, 0.000264, 0.000000, 0.000000},
                       {"esm", 0.027563, 0.000453, 0.000000, 0.000000},
                       {"evsm", 0.023741, 0.000255, 0.000000, 0.000000},
                       {"evsm[2]", 0.025406, 0.000264, 0.000000, 0.000000},
                       {"savsm", 0.023201, 0.000321, 0.000000, 0.000000},
                       {"msm", 0.023791, 0.000255, 0.000000, 0.000000},
                       {"msm[16]", 0.024101, 0.000292, 0.000000, 0.000000},
                       {"vssm", 0.016909, 0.000198, 0.000000, 0.000000},
                       {"msm-soft", 0.017582, 0.000236, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.019069, 0.000179, 0.000031, 0.000000},
                       {"pcss-screen", 0.016215, 0.000170, 0.000000, 0.000000},
                   });
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderTheSpot) {
    expectBaseline({.scene = "builtin:spot",
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   {
                       {"hard", 0.040502, 0.001068, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.032987, 0.000310, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.032974, 0.000298, 0.000000, 0.000000},
                       {"pcf[box3]", 0.025478, 0.000298, 0.000000, 0.000000},
                       {"pcf[box7]", 0.025877, 0.000335, 0.000000, 0.000000},
                       {"pcf[box11]", 0.036348, 0.000621, 0.000000, 0.000000},
                       {"pcf[gauss7]", 0.023054, 0.000310, 0.000000, 0.000000},
                       {"pcf[poisson16]", 0.023463, 0.000310, 0.000000, 0.000000},
                       {"pcf[poisson32]", 0.023333, 0.000310, 0.000000, 0.000000},
                       {"pcf[adaptive-box7]", 0.025996, 0.000335, 0.000000, 0.000000},
                       {"pcss", 0.018902, 0.000261, 0.000000, 0.000000},
                       {"pcss[fast]", 0.033741, 0.001142, 0.000000, 0.000000},
                       {"second-depth", 0.042007, 0.001192, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.039748, 0.001055, 0.000044, 0.000000},
                       {"vsm", 0.031045, 0.000621, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.031049, 0.000695, 0.000000, 0.000000},
                       {"esm", 0.046252, 0.002048, 0.000000, 0.000709},
                       {"evsm", 0.030168, 0.000695, 0.000000, 0.000000},
                       {"evsm[2]", 0.042115, 0.001241, 0.000000, 0.000000},
                       {"savsm", 0.031015, 0.000844, 0.000000, 0.000000},
                       {"msm", 0.029116, 0.000720, 0.000000, 0.000000},
                       {"msm[16]", 0.029670, 0.000745, 0.000000, 0.000000},
                       {"vssm", 0.028950, 0.000794, 0.000000, 0.000000},
                       {"msm-soft", 0.022502, 0.000472, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.025790, 0.000310, 0.000000, 0.000177},
                       {"pcss-screen", 0.018906, 0.000261, 0.000000, 0.000000},
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
                       {"hard", 0.082440, 0.002967, 0.000000, 0.000000},
                       {"pcf[bilinear]", 0.078412, 0.001788, 0.000000, 0.000000},
                       {"pcf[hardware]", 0.078408, 0.001788, 0.000000, 0.000000},
                       {"pcf[box3]", 0.072498, 0.000956, 0.000000, 0.000000},
                       {"pcf[box7]", 0.061481, 0.000360, 0.000000, 0.000000},
                       {"pcf[box11]", 0.052776, 0.000298, 0.000000, 0.000000},
                       {"pcf[gauss7]", 0.065754, 0.000633, 0.000000, 0.000000},
                       {"pcf[poisson16]", 0.067164, 0.000708, 0.000000, 0.000000},
                       {"pcf[poisson32]", 0.067569, 0.000708, 0.000000, 0.000000},
                       {"pcf[adaptive-box7]", 0.061534, 0.000360, 0.000000, 0.000000},
                       {"pcss", 0.021777, 0.000223, 0.000000, 0.006583},
                       {"pcss[fast]", 0.033717, 0.000708, 0.000285, 0.018842},
                       {"second-depth", 0.083021, 0.003091, 0.000000, 0.000000},
                       {"second-depth[nobias]", 0.081909, 0.002979, 0.000045, 0.000000},
                       {"vsm", 0.075508, 0.001378, 0.000000, 0.000000},
                       {"vsm[no-bleed-reduction]", 0.072695, 0.000956, 0.000000, 0.000000},
                       {"esm", 0.076962, 0.001477, 0.000000, 0.000908},
                       {"evsm", 0.072390, 0.000943, 0.000000, 0.000000},
                       {"evsm[2]", 0.074326, 0.001005, 0.000000, 0.000000},
                       {"savsm", 0.070211, 0.001092, 0.000000, 0.000000},
                       {"msm", 0.071297, 0.000981, 0.000000, 0.000000},
                       {"msm[16]", 0.071549, 0.000981, 0.000000, 0.000000},
                       {"vssm", 0.031663, 0.000993, 0.000000, 0.000000},
                       {"msm-soft", 0.026305, 0.000695, 0.000000, 0.000000},
                       {"pcf[box7-screen]", 0.061273, 0.000348, 0.000000, 0.000227},
                       {"pcss-screen", 0.022182, 0.000223, 0.000000, 0.007037},
                   });
}
