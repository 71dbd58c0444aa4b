// One visibility convention for render and reference on surfaces that face away from a light
// (issue 16): the surface itself hides the light, so visibility is 0 there for a point-like
// light and the part of the light's disc above the tangent plane for a light with a size. The
// scene is chosen so that a shadow map alone says "lit": a single panel whose seen side faces
// away from every light, with nothing between it and them.
#include "gpu_fixture.h"
#include "penumbra/reference.h"
#include "scene/mesh_builder.h"

#include <fmt/format.h>

namespace penumbra::test {
namespace {

// A floor and a standing panel that faces the camera (+z); the lights stand behind the panel.
Scene panelFacingAwayFrom(const Light& light) {
    Scene scene;
    scene.name = "panel facing away";
    MeshBuilder mb(scene);
    const float g = 12.0f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("floor", {0.6f, 0.6f, 0.6f}));
    mb.quad({-1.5f, 0.2f, 0.0f}, {1.5f, 0.2f, 0.0f}, {1.5f, 2.8f, 0.0f}, {-1.5f, 2.8f, 0.0f},
            mb.material("panel", {0.7f, 0.3f, 0.2f}));
    scene.lights.push_back(light);
    scene.cameras.push_back({.name = "front",
                             .position = {0.5f, 2.0f, 6.0f},
                             .target = {0.0f, 1.4f, 0.0f},
                             .yfov = 0.8f,
                             .znear = 0.1f,
                             .zfar = 60.0f});
    return scene;
}

std::vector<Light> lightsBehindThePanel() {
    const glm::vec3 spotAt{0.3f, 4.0f, -5.0f};
    return {{.name = "sun",
             .type = LightType::Directional,
             .direction = glm::normalize(glm::vec3(0.1f, -0.6f, 0.8f))},
            {.name = "sun 3 degrees",
             .type = LightType::Directional,
             .direction = glm::normalize(glm::vec3(0.1f, -0.6f, 0.8f)),
             .angularDiameter = 3.0f},
            {.name = "spot",
             .type = LightType::Spot,
             .position = spotAt,
             .direction = glm::normalize(glm::vec3(0.0f, 1.2f, 0.0f) - spotAt),
             .intensity = 40.0f,
             .outerConeAngle = 0.9f},
            {.name = "point",
             .type = LightType::Point,
             .position = {0.2f, 2.5f, -2.5f},
             .intensity = 10.0f},
            {.name = "point radius 0.3",
             .type = LightType::Point,
             .position = {0.2f, 2.5f, -2.5f},
             .intensity = 10.0f,
             .radius = 0.3f}};
}

glm::vec3 towardsLight(const Light& l, const glm::vec3& p) {
    return l.type == LightType::Directional ? -l.direction : glm::normalize(l.position - p);
}

TEST_F(ShadowTest, RenderAndReferenceAgreeWhereTheSurfaceFacesAwayFromTheLight) {
    for (const Light& light : lightsBehindThePanel()) {
        const Scene scene = panelFacingAwayFrom(light);
        const RenderResult gbuffer = render(scene, {.width = 160, .height = 120});
        const ReferenceResult truth = computeReference(scene, gbuffer, {.samples = 64});
        for (Technique t : {Technique::Hard, Technique::Pcf, Technique::Pcss, Technique::Sdf}) {
            RenderOptions o{.width = 160, .height = 120, .shadowMapSize = 512, .technique = t};
            o.parameters.set("sdf.resolution", "64"); // a coarse field is enough here
            const RenderResult r = render(scene, o);
            size_t backFacing = 0, disagree = 0;
            for (size_t i = 0; i < size_t{160} * 120; ++i) {
                const glm::vec3 p = pixelVec(gbuffer.position, i), n = pixelVec(gbuffer.normal, i);
                if (!std::isfinite(p.x) || glm::dot(n, towardsLight(light, p)) > -0.1f)
                    continue; // clearly back-facing only: the terminator is a technique's own
                ++backFacing;
                disagree += std::abs(r.visibility[0][i] - truth.visibility[0][i]) > 0.02f;
            }
            const std::string what = fmt::format("{}, {}", light.name, techniqueName(t));
            EXPECT_GT(backFacing, 2000u) << what << ": the panel must fill part of the view";
            EXPECT_EQ(disagree, 0u) << what << ": back-facing pixels where render and reference "
                                    << "visibility differ (of " << backFacing << ")";
        }
    }
}

} // namespace
} // namespace penumbra::test
