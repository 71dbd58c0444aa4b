// sdf.refuse (src/reference/field_refusal.h): generated scenes whose field cannot hold their
// casters are refused under every light type, with the reason; scenes it holds are not; 0 turns
// the refusal off; other techniques are never audited. The scenes are the corpus's (docs/scenes.md,
// "Generated scenes"), chosen from its measurement at 320x180 (docs/techniques.md, sdf, "The
// audit") far from the limits: refused ones at 2.5-5.7x hard's RMSE or leaking 3% of their
// umbra, kept ones at 0.2-0.8x without leak or acne.
#include "gpu_fixture.h"
#include "penumbra/error.h"
#include "reference/field_refusal.h"
#include "reference/visibility_audit.h"
#include "report/light_mask.h"

#include <fmt/format.h>

#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct Case {
    const char* scene;
    const char* light;
    const char* refused; // what the reason must say; null: kept
    float angle = -1.0f; // --light-angle: the audit's rays must see the sun it was rendered with
};

// sdf at its defaults (sdf.refuse 1.2), or with `refuse`.
RenderOptions sdfOptions(const char* refuse = nullptr) {
    RenderOptions o{.width = 256,
                    .height = 144,
                    .shadowMapSize = 1024,
                    .frames = 1,
                    .technique = Technique::Sdf};
    if (refuse)
        o.parameters.set("sdf.refuse", refuse);
    return o;
}

} // namespace

TEST_F(FieldTest, SdfRefusesTheViewsItsFieldCannotHoldUnderEveryLightType) {
    const char* rmse = "as much as the hard technique's";
    const std::vector<Case> cases = {
        {"builtin:gen/long?seed=2", "sun of 1.9 degrees", rmse},
        {"builtin:gen/plates?seed=4", "spot of radius 0.165", rmse},
        {"builtin:gen/clutter?seed=2", "bulb without size", rmse},
        // Half hard's RMSE, but light through 3% of the umbra at the rim of a shelf's shadow.
        {"builtin:gen/interior?seed=2", "spot of radius 0.2", "of the umbra"},
        {"builtin:gen/spheres?seed=2", "sun of 0.5 degrees", nullptr},
        {"builtin:gen/spheres?seed=9", "spot of radius 0.34", nullptr},
        {"builtin:gen/curved?seed=1", "bulb without size", nullptr},
        {"builtin:gen/spheres?seed=2", "sun widened to 4 degrees", nullptr, 4.0f},
    };

    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(c.scene) + ", " + c.light);
        const Scene scene = loadScene(c.scene);
        SceneRenderer renderer(sharedRenderer(), scene);
        RenderOptions options = sdfOptions();
        options.lightAngleOverride = c.angle;
        const RenderResult result = renderer.render(options);
        std::string figures, reason;
        try {
            refuseUnheldField(renderer, options, result,
                              [&](const std::string& line) { figures = line; });
        } catch (const InputError& e) {
            reason = e.what();
        }
        std::printf("%s: %s%s\n", c.scene, figures.c_str(), reason.empty() ? "" : " (refused)");
        EXPECT_NE(figures.find("sdf audit: RMSE"), std::string::npos) << figures;
        if (!c.refused) {
            EXPECT_EQ(reason, "");
            continue;
        }
        EXPECT_NE(reason.find(c.refused), std::string::npos) << reason;
        EXPECT_NE(reason.find(scene.name), std::string::npos) << reason;
        EXPECT_NE(reason.find("sdf refuses this view"), std::string::npos) << reason;
        EXPECT_NE(reason.find("sdf.refuse=0"), std::string::npos) << reason;
        // sdf.refuse=0 renders it anyway, without the audit's cost.
        bool audited = false;
        EXPECT_NO_THROW(refuseUnheldField(renderer, sdfOptions("0"), result,
                                          [&](const std::string&) { audited = true; }));
        EXPECT_FALSE(audited);
        // Only sdf is audited: the same view with pcss is not even measured.
        RenderOptions pcss = options;
        pcss.technique = Technique::Pcss;
        EXPECT_NO_THROW(refuseUnheldField(renderer, pcss, renderer.render(pcss),
                                          [&](const std::string&) { audited = true; }));
        EXPECT_FALSE(audited);
    }
}

// The audit counts what compare counts under a spot: the pixels its cone reaches (lightMask), not
// the rest of the view, where sdf and hard agree with the truth and would thin both errors out.
TEST_F(FieldTest, SdfAuditCountsOnlyWhatTheSpotReaches) {
    const Scene scene = loadScene("builtin:gen/spheres?seed=9"); // a spot of radius 0.34
    SceneRenderer renderer(sharedRenderer(), scene);
    const RenderOptions options = sdfOptions();
    const RenderResult result = renderer.render(options);
    std::string figures;
    refuseUnheldField(renderer, options, result, [&](const std::string& l) { figures = l; });
    RenderOptions plain = options;
    plain.technique = Technique::Hard;
    const RenderResult hard = renderer.render(plain);
    const std::vector<std::vector<uint8_t>> masks = {lightMask(scene.lights.front(), result)};
    const VisibilityAudit masked = auditVisibility(scene, result, hard, masks),
                          whole = auditVisibility(scene, result, hard);
    EXPECT_LT(masked.pixels, whole.pixels) << "the cone leaves pixels out";
    EXPECT_NE(figures.find(fmt::format("over {} pixels", masked.pixels)), std::string::npos)
        << figures << " (masked " << masked.pixels << ", whole " << whole.pixels << ")";
}
