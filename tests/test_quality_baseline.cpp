// Every row `penumbra compare` shows, against the ray-traced truth on four small set-ups (a sun
// and a spot, each small and large), with the error each row measured when the figures were
// stored (lavapipe; map 1024 so that filters and aliasing show at 512x288) in
// tests/baselines/compare-rows/SETUP.json. A row that gets 15% worse (or better: then the figures
// are stale) on any metric fails, and so does a row that appears or disappears: the file names
// every row. `make baselines` stores them afresh (docs/testing.md, "Baselines").
#include "baseline_store.h"
#include "truth_fixture.h"

#include <fmt/format.h>

using namespace penumbra;
using namespace penumbra::test;

namespace {

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

void expectBaseline(const TruthSetup& setup, const std::string& name) {
    const Truth t = groundTruth(setup);
    std::string where = setup.scene;
    if (setup.angle >= 0)
        where += fmt::format(" sun {:g} deg", setup.angle);
    if (setup.radius >= 0)
        where += fmt::format(" radius {:g}", setup.radius);
    BaselineTable table("compare-rows", name,
                        fmt::format("{}; {}x{}, map {}, {} samples", where, setup.width,
                                    setup.height, setup.shadowMapSize, setup.samples));
    for (const TechniqueRow& row : rowsToMeasure()) {
        const ErrorMetrics m = measure(t, row);
        std::printf("%-44s rmse %.5f misclassified %.4f%% acne %.4f%% leak %.4f%%\n",
                    (where + " " + row.name).c_str(), m.rmse, 100 * m.misclassified, 100 * m.acne,
                    100 * m.leak);
        table.record(row.name, {{"rmse", m.rmse},
                                {"misclassified", m.misclassified},
                                {"acne", m.acne},
                                {"leak", m.leak}});
        const Figures* s = table.stored(row.name);
        if (s == nullptr || table.writing())
            continue;
        const std::string what = where + " " + row.name;
        const double tolerance = storedTolerance();
        expectStored(what + " rmse", m.rmse, s->at("rmse"), tolerance, 2e-4);
        expectStored(what + " misclassified", m.misclassified, s->at("misclassified"), tolerance,
                     storedFloor(1e-4));
        expectStored(what + " acne", m.acne, s->at("acne"), tolerance, storedFloor(1e-4));
        expectStored(what + " leak", m.leak, s->at("leak"), tolerance, storedFloor(1e-4));
    }
}

} // namespace

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderTheSun) {
    expectBaseline({.scene = "builtin:showcase",
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   "sun");
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderALargeSun) {
    expectBaseline({.scene = "builtin:showcase",
                    .angle = 4.0f,
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   "large-sun");
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderTheSpot) {
    expectBaseline({.scene = "builtin:spot",
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   "spot");
}

TEST_F(QualityTest, EveryCompareRowKeepsItsErrorUnderALargeSpot) {
    expectBaseline({.scene = "builtin:spot",
                    .radius = 1.0f,
                    .width = 512,
                    .height = 288,
                    .shadowMapSize = 1024,
                    .samples = 64},
                   "large-spot");
}
