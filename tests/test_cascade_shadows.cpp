// Cascaded shadow maps against the ray-traced truth on builtin:field (a sun over an 800-unit
// ground, objects 2 to 180 units ahead): cascades against one map near the camera, no acne at
// cascade borders for any filter, kernels that keep their world size in farther cascades.
#include "truth_fixture.h"

#include <algorithm>

using namespace penumbra;
using namespace penumbra::test;

namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;

Sets withCascades(int count, Sets sets = {}) {
    sets.emplace_back("csm.cascades", std::to_string(count));
    return sets;
}

// Counted pixels whose camera view distance lies in [from, to).
ErrorMetrics errorBetween(const Truth& t, const RenderResult& r, float from, float to) {
    const Camera c = t.scene.camera("");
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    std::vector<uint8_t> mask = t.mask;
    for (size_t i = 0; i < mask.size(); ++i) {
        const float z = glm::dot(pixelVec(t.gbuffer.position, i) - c.position, forward);
        mask[i] = mask[i] && z >= from && z < to;
    }
    const MetricLayer layer{r.visibility[0], t.reference.visibility[0], mask};
    return computeMetrics(r.width, r.height, std::span(&layer, 1));
}

const Truth& field() {
    static const Truth t =
        groundTruth({.scene = "builtin:field", .width = 384, .height = 384, .samples = 32});
    return t;
}

} // namespace

TEST_F(QualityTest, FourCascadesAtLeastHalveTheErrorNearTheCamera) {
    const Truth& t = field();
    for (const auto& [technique, sets] :
         std::vector<std::pair<Technique, Sets>>{{Technique::Hard, {}}, {Technique::Pcss, {}}}) {
        const RenderResult one = renderRow(t, technique, withCascades(1, sets));
        const RenderResult four = renderRow(t, technique, withCascades(4, sets));
        const ErrorMetrics nearOne = errorBetween(t, one, 0.0f, 25.0f);
        const ErrorMetrics nearFour = errorBetween(t, four, 0.0f, 25.0f);
        const ErrorMetrics all = errorOf(t, four);
        std::printf("%s within 25 units: rmse one map %.4f, 4 cascades %.4f (%llu px); 4 "
                    "cascades everywhere: misclassified away from edges %.3f%%\n",
                    techniqueName(technique).data(), nearOne.rmse, nearFour.rmse,
                    static_cast<unsigned long long>(nearFour.pixels),
                    100 * all.misclassifiedOutsideEdges);
        EXPECT_GT(nearFour.pixels, 20000u);
        EXPECT_LT(nearFour.rmse, 0.5 * nearOne.rmse) << techniqueName(technique);
        EXPECT_LT(all.misclassifiedOutsideEdges, 0.003) << techniqueName(technique);
        ASSERT_EQ(four.lights[0].views.size(), 4u);
        for (const ShadowViewInfo& v : four.lights[0].views)
            EXPECT_TRUE(v.cascade);
    }
}

// A kernel set in texels of the first cascade keeps its world size in the farther ones: far
// away a 7x7 box shrinks to about one texel, and stays as close to the truth as a single tap.
TEST_F(QualityTest, CascadeKernelsKeepTheirWorldSize) {
    const Truth& t = field();
    const RenderResult hard = renderRow(t, Technique::Hard, withCascades(4));
    const RenderResult box =
        renderRow(t, Technique::Pcf, withCascades(4, {{"pcf.filter", "box"}, {"pcf.size", "7"}}));
    const ErrorMetrics farHard = errorBetween(t, hard, 60.0f, 1e9f);
    const ErrorMetrics farBox = errorBetween(t, box, 60.0f, 1e9f);
    std::printf("beyond 60 units: rmse hard %.4f, box7 %.4f (%llu px)\n", farHard.rmse, farBox.rmse,
                static_cast<unsigned long long>(farBox.pixels));
    EXPECT_LT(farBox.rmse, 1.3 * farHard.rmse);
    const std::vector<ShadowViewInfo>& views = box.lights[0].views;
    for (size_t i = 1; i < views.size(); ++i)
        EXPECT_NEAR(views[i].kernelScale, views[0].texelWorldSize / views[i].texelWorldSize, 1e-5);
}

// With nothing to cast a shadow, the ground is lit everywhere: across every cascade border and
// blend band, for every filter.
TEST_F(BiasTest, CascadedSunOverAnEmptyFieldIsLitEverywhere) {
    Scene scene = loadScene("builtin:field");
    scene.indices.resize(6); // the ground alone
    const RenderResult g = render(scene, {.width = 192, .height = 192});
    const std::vector<uint8_t> mask = lightMask(scene.lights[0], g);
    for (const auto& [technique, sets] : std::vector<std::pair<Technique, Sets>>{
             {Technique::Hard, {}},
             {Technique::Pcf, {{"pcf.filter", "box"}, {"pcf.size", "15"}}},
             {Technique::Pcf, {{"pcf.filter", "poisson"}, {"pcf.radius", "12"}}},
             {Technique::Pcss, {}},
             {Technique::SecondDepth, {}}}) {
        RenderOptions o{.width = 192, .height = 192, .shadowMapSize = 1024, .technique = technique};
        for (const auto& [key, value] : withCascades(4, sets))
            o.parameters.set(key, value);
        o.parameters.set("csm.blend", "0.3");
        const RenderResult r = render(scene, o);
        size_t counted = 0, dark = 0;
        for (size_t i = 0; i < mask.size(); ++i)
            if (mask[i]) {
                ++counted;
                dark += r.visibility[0][i] < 1.0f;
            }
        EXPECT_GT(counted, 15000u);
        EXPECT_EQ(dark, 0u) << techniqueName(technique) << (sets.empty() ? "" : sets[0].second);
    }
}
