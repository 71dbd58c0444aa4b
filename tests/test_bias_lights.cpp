// Acne and peter-panning of the `hard` technique with each bias alone, for a sun (high and low)
// and a spot, against the point-light ground truth on the same pixels. Each light type takes its
// own path through the bias (a perspective light's normal offset grows with distance, its
// receiver plane comes from a projective Jacobian), so each has its own rows, and each bias is
// set where it only partly works (the knee of its curve): a change to its maths moves the count.
// The stored values are measurements (lavapipe, 640x360, map 2048) in
// tests/baselines/bias/SETUP.json; see storedTolerance() for how far they may move. `make
// baselines` stores them afresh (docs/testing.md, "Baselines").
//
// Other devices: a knee is where a bias is as large as the depth error it meets, so where it
// sits follows the device's rasterizer and depth rounding, which Vulkan bounds only loosely; a
// row whose maths is exact on a plane (no bias, the receiver plane alone, the adaptive offset
// alone) compares equal depths, a tie that rounding decides either way. There the tables only
// bind lavapipe (CI's device, bit-identical run after run); elsewhere a knee must stay under the
// unbiased row's acne (the low sun's slope 0.25 removes half of it on lavapipe and on an H200),
// a tie is free, and every leak and every complete setting (the defaults, the lift) keeps its
// stored value, which holds on any device.
#include "baseline_store.h"
#include "truth_fixture.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct BiasRow {
    const char* config;
    std::vector<std::pair<std::string, std::string>> sets;
};

const std::vector<std::pair<std::string, std::string>> kNoBias = {{"bias.mode", "fixed"},
                                                                  {"bias.constant", "0"},
                                                                  {"bias.slope", "0"},
                                                                  {"bias.normal", "0"},
                                                                  {"bias.receiver", "off"}};

std::vector<std::pair<std::string, std::string>> alone(const char* key, const char* value) {
    auto sets = kNoBias;
    for (auto& [k, v] : sets)
        if (k == key)
            v = value;
    return sets;
}

void expectRows(const TruthSetup& setup, const std::string& name, const std::string& about,
                const std::vector<BiasRow>& rows, Technique technique = Technique::Hard) {
    const Truth t = groundTruth(setup);
    BaselineTable table("bias", name, about);
    double none = -1;
    std::vector<std::pair<std::string, double>> knees; // checked against `none` on other devices
    for (const BiasRow& row : rows) {
        const ErrorMetrics m = measure(t, technique, row.sets);
        const std::string what = setup.scene + ", " + row.config;
        std::printf("%-40s acne %.4f%% leak %.4f%%\n", what.c_str(), 100 * m.acne, 100 * m.leak);
        table.record(row.config, {{"acne", m.acne}, {"leak", m.leak}});
        const std::string config = row.config;
        if (config == "none")
            none = m.acne;
        const Figures* stored = table.stored(config);
        if (stored == nullptr || table.writing())
            continue;
        const bool tie = config == "none" || config.starts_with("receiver ") ||
                         config == "adaptive offset alone";
        const bool complete = config.find("defaults") != std::string::npos ||
                              config.find("lift") != std::string::npos;
        if (onCpuDevice() || complete)
            expectStored(what + " acne", m.acne, stored->at("acne"), storedTolerance(), 1e-4);
        else if (!tie)
            knees.emplace_back(what, m.acne);
        expectStored(what + " leak", m.leak, stored->at("leak"), storedTolerance(), 1e-4);
    }
    for (const auto& [what, acne] : knees) {
        if (none >= 0) {
            EXPECT_LT(acne, none) << what << ": a bias at its knee still removes acne";
        }
    }
    if (none >= 0) {
        EXPECT_GT(none, 0.4) << setup.scene << ": without bias half the lit pixels show acne";
    }
}

// bias.mode=adaptive [Dou et al. 2014]: the receiver's own plane at every tap, with no lift (the
// paper's offset alone), with the constant lift alone, and at its defaults (curvature and normal
// offset too). The offset alone is
// exact on a plane, which makes every comparison a tie that float rounding decides (acne on up
// to half the pixels: the paper's reason for its epsilon); the lift takes planes to nothing
// without peter-panning, and the curvature term halves what a 7x7 kernel still finds on the
// figure's curved, faceted limbs.
std::vector<BiasRow>
adaptiveRows(const std::vector<std::pair<std::string, std::string>>& extra = {}) {
    const std::vector<std::pair<std::string, std::string>> offsetOnly = {{"bias.mode", "adaptive"},
                                                                         {"bias.adaptive", "0"},
                                                                         {"bias.curvature", "0"},
                                                                         {"bias.normal", "0"},
                                                                         {"bias.slope", "0"}};
    auto lift = offsetOnly;
    lift[1].second = "0.25";
    std::vector<BiasRow> rows{{"adaptive offset alone", offsetOnly},
                              {"adaptive offset + lift", lift},
                              {"adaptive defaults", {{"bias.mode", "adaptive"}}}};
    for (BiasRow& row : rows)
        row.sets.insert(row.sets.end(), extra.begin(), extra.end());
    return rows;
}

} // namespace

TEST_F(BiasTest, EachBiasAloneUnderTheSun) {
    expectRows(
        {.scene = "builtin:showcase", .angle = 0.0f, .width = 640, .height = 360, .samples = 1},
        "sun", "builtin:showcase, sun of 0 degrees; hard; 640x360, map 2048",
        {{"none", kNoBias},
         {"constant 0.0002", alone("bias.constant", "0.0002")},
         {"slope 0.5", alone("bias.slope", "0.5")},
         {"normal 1", alone("bias.normal", "1")},
         {"receiver light", alone("bias.receiver", "light")},
         {"receiver screen", alone("bias.receiver", "screen")},
         {"defaults", {}}});
}

TEST_F(BiasTest, EachBiasAloneUnderTheLowSun) {
    expectRows({.scene = "builtin:grazing", .width = 640, .height = 360, .samples = 1}, "low-sun",
               "builtin:grazing, its low sun; hard; 640x360, map 2048",
               {{"none", kNoBias},
                {"constant 0.0002", alone("bias.constant", "0.0002")},
                {"slope 0.25", alone("bias.slope", "0.25")},
                {"normal 2", alone("bias.normal", "2")},
                {"receiver light", alone("bias.receiver", "light")},
                {"receiver screen", alone("bias.receiver", "screen")},
                {"defaults", {}}});
}

TEST_F(BiasTest, EachBiasAloneUnderTheSpot) {
    expectRows({.scene = "builtin:spot", .radius = 0.0f, .width = 640, .height = 360, .samples = 1},
               "spot", "builtin:spot, radius 0; hard; 640x360, map 2048",
               // Counted: the pixels inside the cone (the metrics' light mask), not the
               // frustum's square around it.
               {{"none", kNoBias},
                {"constant 0.00005", alone("bias.constant", "0.00005")},
                {"slope 0.5", alone("bias.slope", "0.5")},
                {"normal 2", alone("bias.normal", "2")},
                {"receiver light", alone("bias.receiver", "light")},
                {"receiver screen", alone("bias.receiver", "screen")},
                {"defaults", {}}});
}

TEST_F(BiasTest, AdaptiveBiasUnderEveryLightType) {
    expectRows(
        {.scene = "builtin:showcase", .angle = 0.0f, .width = 640, .height = 360, .samples = 1},
        "adaptive-sun", "builtin:showcase, sun of 0 degrees; hard; 640x360, map 2048",
        adaptiveRows());
    expectRows({.scene = "builtin:grazing", .width = 640, .height = 360, .samples = 1},
               "adaptive-low-sun", "builtin:grazing, its low sun; hard; 640x360, map 2048",
               adaptiveRows());
    expectRows({.scene = "builtin:spot", .radius = 0.0f, .width = 640, .height = 360, .samples = 1},
               "adaptive-spot", "builtin:spot, radius 0; hard; 640x360, map 2048", adaptiveRows());
    expectRows({.scene = "builtin:room", .radius = 0.0f, .width = 640, .height = 360, .samples = 1},
               "adaptive-room", "builtin:room, radius 0; hard; 640x360, map 2048", adaptiveRows());
    // Curved, faceted receivers under a wide kernel: what the curvature term is for.
    expectRows(
        {.scene = "builtin:figure", .angle = 0.0f, .width = 640, .height = 360, .samples = 1},
        "adaptive-figure", "builtin:figure, sun of 0 degrees; pcf box 7x7; 640x360, map 2048",
        adaptiveRows({{"pcf.filter", "box"}, {"pcf.size", "7"}}), Technique::Pcf);
}
