// The summed-area soft members (`vssm`, `msm-soft`) under grazing light, against the ray-traced
// truth on generated scenes (docs/scenes.md, "Generated scenes"), one per light type: blockers
// seen edge-on and floors seen at a grazing angle spread their depths over the wide boxes a
// light's search covers, which Chebyshev's bound reads as light (docs/techniques.md, "vssm").
#include "truth_fixture.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

using namespace penumbra;
using penumbra::test::QualityTest;

namespace {

struct GrazingCase {
    const char* scene;
    const char* what;
};

// Measured at 320x180, map 1024, 256 rays a pixel (lavapipe), vssm's leak beyond blur and RMSE
// before -> after the narrow search, the receiver's spread and 4x4 sub-kernels: grazing 9 (a spot
// 0.07 wide, a ramp seen edge-on over every shadow) 65% -> 0%, 0.469 -> 0.057 (hard 0.069);
// grazing 3 (a spot of radius 0.2, blocks' long shadows) 28% -> 0.2%, 0.352 -> 0.056 (hard
// 0.076); grazing 5 (the same, the streaks 3x3 sub-kernels still lost) 10% -> 0.1%, 0.197 ->
// 0.054 (hard 0.089); grazing 1 (a 1.5-degree sun) and open 9 (a bulb) 0% before and after.
const GrazingCase kCases[] = {{"builtin:gen/grazing?seed=9", "spot, a ramp seen edge-on"},
                              {"builtin:gen/grazing?seed=3", "spot of radius 0.2, long shadows"},
                              {"builtin:gen/grazing?seed=5", "spot of radius 0.2, long streaks"},
                              {"builtin:gen/grazing?seed=1", "1.5-degree sun"},
                              {"builtin:gen/open?seed=9", "bulb of radius 0.16"}};

} // namespace

// The gate's target (0.3% leak and acne beyond blur), and at most 1.5x hard's RMSE: before, a
// grazing spot's shadows were lost whole (the RMSE 5-7x hard's). msm-soft still leaks 0.48% on
// grazing 3 (0.54% before; docs/techniques.md, "On the generated corpus"): its bound is that.
TEST_F(QualityTest, SummedAreaSoftMembersKeepShadowsUnderGrazingLight) {
    for (const GrazingCase& c : kCases) {
        const test::Truth t = test::groundTruth(
            {.scene = c.scene, .width = 320, .height = 180, .shadowMapSize = 1024, .samples = 256});
        const double hard = test::measure(t, Technique::Hard, {}).rmse;
        for (Technique technique : {Technique::Vssm, Technique::MsmSoft}) {
            const ErrorMetrics e =
                test::errorBeyondBlur(t, test::renderRow(t, technique, {}), technique, {});
            const std::string what =
                std::string(techniqueName(technique)) + " on " + c.scene + " (" + c.what + ")";
            std::printf("%s: RMSE %.4f (hard %.4f), leak beyond blur %.3f%%, acne %.3f%%\n",
                        what.c_str(), e.rmse, hard, 100 * e.leakBeyondBlur, 100 * e.acneBeyondBlur);
            EXPECT_LE(e.leakBeyondBlur, technique == Technique::Vssm ? 0.003 : 0.005) << what;
            EXPECT_LE(e.acneBeyondBlur, 0.003) << what;
            EXPECT_LE(e.rmse, 1.5 * hard) << what;
        }
    }
}
