// The contact layer (src/shadows/contact.cpp, shaders/contact.comp): off, it leaves every image as
// it was; on, the GPU matches its CPU reference; and against the truth, for every light type, it
// gives back the contact shadows a detaching bias takes away without adding false shadow.
#include "analytic_scenes.h"
#include "render/frame_data.h"
#include "shadows/contact.h"
#include "shadows/layer.h"
#include "truth_fixture.h"

#include <fmt/format.h>

using namespace penumbra;
using namespace penumbra::test;

namespace {

Light contactSun() {
    Light sun = sharpSun();
    sun.angularDiameter = 0.5f;
    return sun;
}
Light contactSpot() {
    Light spot = sharpSpot();
    spot.radius = 0.03f;
    return spot;
}
Light contactPoint() {
    Light point = sharpPoint();
    point.radius = 0.03f;
    return point;
}

// A shadow map's bias large enough to detach every shadow from its caster's foot.
std::vector<std::pair<std::string, std::string>> detachingBias(LightType type) {
    return {{"bias.mode", "fixed"},
            {"bias.constant", type == LightType::Directional ? "0.02"
                              : type == LightType::Spot      ? "0.02"
                                                             : "0.04"},
            {"bias.slope", "2"},
            {"bias.normal", "0"}};
}

constexpr float kContactLength = 0.3f; // world units: a third of the smaller box

RenderOptions optionsFor(Technique technique,
                         const std::vector<std::pair<std::string, std::string>>& sets,
                         float contactLength) {
    RenderOptions o{
        .width = 320, .height = 240, .shadowMapSize = 1024, .frames = 1, .technique = technique};
    for (const auto& [key, value] : sets)
        o.parameters.set(key, value);
    o.parameters.set("contact.length", fmt::format("{}", contactLength));
    return o;
}

// Whether pixel i lies within `band` pixels (Chebyshev) of one whose truth class (lit or
// shadowed) differs: a shadow's edge, where a grazing ray's fate is decided within a pixel.
bool nearTruthEdge(const std::vector<float>& truth, uint32_t w, uint32_t h, size_t i, int band) {
    const int x = int(i % w), y = int(i / w);
    const bool lit = truth[i] >= 0.5f;
    for (int v = std::max(0, y - band); v <= std::min(int(h) - 1, y + band); ++v)
        for (int u = std::max(0, x - band); u <= std::min(int(w) - 1, x + band); ++u) {
            const float t = truth[size_t(v) * w + u];
            if (!std::isnan(t) && (t >= 0.5f) != lit)
                return true;
        }
    return false;
}

bool hasPass(const RenderResult& r, std::string_view name) {
    return std::any_of(r.passes.begin(), r.passes.end(),
                       [&](const PassTime& p) { return p.pass == name; });
}

} // namespace

TEST_F(LayerTest, ContactOffLeavesTheFrameAsItWas) {
    const Scene scene = restingObjects(contactSun());
    for (Technique t : {Technique::Hard, Technique::Pcf, Technique::Pcss}) {
        const RenderResult plain = render(scene, optionsFor(t, {}, 0.0f));
        RenderOptions defaults{.width = 320, .height = 240, .shadowMapSize = 1024, .technique = t};
        const RenderResult unset = render(scene, defaults);
        EXPECT_EQ(plain.image, unset.image);
        EXPECT_FALSE(hasPass(plain, "contact"));
        EXPECT_TRUE(hasPass(plain, "composite"));
        const RenderResult on = render(scene, optionsFor(t, {}, kContactLength));
        // On, it runs after the base technique, and the composite shades on its own after it.
        EXPECT_TRUE(hasPass(on, "contact"));
        EXPECT_TRUE(hasPass(on, "visibility"));
        EXPECT_NE(on.image, plain.image);
    }
}

// The GPU's layer against its CPU reference on the same G-buffer: visibility with the layer =
// visibility without it x the reference's factor, but where a float rounding puts a sample on
// the other side of a pixel edge or of a plane.
TEST_F(LayerTest, ContactMatchesItsCpuReferenceForEveryLightType) {
    for (const Light& light : {contactSun(), contactSpot(), contactPoint()}) {
        const Scene scene = restingObjects(light);
        const RenderOptions off = optionsFor(Technique::Hard, detachingBias(light.type), 0.0f);
        const RenderOptions on =
            optionsFor(Technique::Hard, detachingBias(light.type), kContactLength);
        const RenderResult base = render(scene, off);
        const RenderResult layered = render(scene, on);
        const gpu::FrameData frame =
            render::frameData(scene.camera(""), on, 1, sharedRenderer().context());
        const std::vector<float> factor =
            shadows::contactReference({.width = base.width,
                                       .height = base.height,
                                       .position = base.position,
                                       .faceNormal = base.faceNormal},
                                      frame, light, shadows::contactParams(on.parameters));
        size_t counted = 0, differ = 0, shadowed = 0, found = 0;
        for (size_t i = 0; i < factor.size(); ++i) {
            if (std::isnan(base.visibility[0][i])) {
                EXPECT_TRUE(std::isnan(layered.visibility[0][i]));
                continue;
            }
            ++counted;
            found += factor[i] == 0.0f;
            shadowed += factor[i] == 0.0f && base.visibility[0][i] > 0.0f;
            differ += layered.visibility[0][i] != base.visibility[0][i] * factor[i];
        }
        EXPECT_LE(differ, counted / 500) << light.name << ": " << differ << " of " << counted;
        // Not vacuous: the layer finds occluders (near the objects' feet, and inside their
        // shadows), and shadows pixels the detached map left lit.
        EXPECT_GE(found, 100u) << light.name;
        EXPECT_GE(shadowed, 40u) << light.name;
        std::printf("%s: %zu of %zu pixels differ, the layer found an occluder at %zu, shadowed "
                    "%zu the map lit\n",
                    light.name.c_str(), differ, counted, found, shadowed);
    }
}

// Where a fixed bias detaches the shadows from the objects resting on the plane, the layer gives
// back the contact shadows: half the leak near the contacts at least (pixels whose occluder the
// truth finds within the layer's length), no acne beyond the technique's blur added, and no
// worse elsewhere.
TEST_F(LayerTest, ContactGivesBackDetachedShadowsAgainstTheTruth) {
    for (const Light& light : {contactSun(), contactSpot(), contactPoint()}) {
        for (Technique technique : {Technique::Hard, Technique::Pcf}) {
            const Truth t =
                groundTruth(restingObjects(light),
                            {.width = 320, .height = 240, .shadowMapSize = 1024, .samples = 32});
            const auto sets = detachingBias(light.type);
            auto run = [&](float length) {
                return sharedRenderer().render(t.scene, optionsFor(technique, sets, length));
            };
            const RenderResult without = run(0.0f), with = run(kContactLength);
            const std::vector<float>& truth = t.reference.visibility[0];
            const std::vector<float>& occluder = t.reference.occluderDistance[0];
            size_t near = 0, leakWithout = 0, leakWith = 0;
            double farWithout = 0, farWith = 0;
            size_t far = 0, falseLit = 0, farDark = 0, farDarkFixed = 0;
            for (size_t i = 0; i < truth.size(); ++i) {
                if (!t.mask[i] || std::isnan(truth[i]))
                    continue;
                if (occluder[i] <= kContactLength && truth[i] < 0.5f) {
                    ++near;
                    leakWithout += without.visibility[0][i] >= 0.5f;
                    leakWith += with.visibility[0][i] >= 0.5f;
                } else if (!(occluder[i] <= kContactLength) &&
                           !nearTruthEdge(truth, t.setup.width, t.setup.height, i, 2)) {
                    ++far;
                    const bool darkened = with.visibility[0][i] < without.visibility[0][i] - 0.01f;
                    falseLit += darkened && truth[i] > 0.5f;
                    farDark += darkened && truth[i] <= 0.5f;
                    farDarkFixed += darkened && truth[i] <= 0.5f && occluder[i] < 1e30f;
                    farWithout += std::pow(without.visibility[0][i] - truth[i], 2.0);
                    farWith += std::pow(with.visibility[0][i] - truth[i], 2.0);
                }
            }
            const std::string what = fmt::format("{} {}", light.name, techniqueName(technique));
            std::printf("%s: near-contact leak %zu -> %zu of %zu; RMSE elsewhere %.5f -> %.5f "
                        "(darkened: %zu truth lit, %zu truth dark, %zu with an occluder)\n",
                        what.c_str(), leakWithout, leakWith, near,
                        std::sqrt(farWithout / double(far)), std::sqrt(farWith / double(far)),
                        falseLit, farDark, farDarkFixed);
            ASSERT_GT(near, 200u) << what << ": too few contact-shadow pixels to judge";
            // The bias detaches the shadows (else the test shows nothing) ...
            EXPECT_GT(leakWithout, near / 10) << what;
            // ... and the layer gives back at least half of what it took.
            EXPECT_LE(2 * leakWith, leakWithout) << what;
            // Elsewhere (away from the contacts and the truth's shadow edges, where a grazing
            // ray's fate is decided within a pixel): no worse.
            EXPECT_LE(std::sqrt(farWith / double(far)), std::sqrt(farWithout / double(far)) + 1e-4)
                << what;
            EXPECT_LE(falseLit, far / 10000) << what << ": false shadow elsewhere";
            const ErrorMetrics a = errorBeyondBlur(t, without, technique, sets);
            const ErrorMetrics b = errorBeyondBlur(t, with, technique, sets);
            EXPECT_LE(b.acneBeyondBlur, a.acneBeyondBlur + 1e-4) << what;
        }
    }
}
