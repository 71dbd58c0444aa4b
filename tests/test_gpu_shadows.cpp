// End-to-end GPU tests of the `hard` technique on the built-in scenes (lavapipe + validation).
#include "gpu_fixture.h"
#include "penumbra/error.h"
#include "penumbra/reference.h"
#include "report/light_mask.h"
#include "report/metrics.h"
#include "scene/builtin_scenes.h"

#include <glm/glm.hpp>

#include <cstdio>
#include <cstring>
#include <limits>

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct Centroids {
    glm::dvec2 expected{0.0}, rendered{0.0};
    size_t expectedCount = 0, renderedCount = 0;
};

// The sphere's shadow on the ground, twice: analytically (the ray from each ground pixel toward
// the light hits the sphere) and as rendered (visibility < 0.5), restricted to ground pixels
// whose light ray passes near the sphere so other casters' shadows stay out.
Centroids sphereShadowCentroids(const RenderResult& r, const Light& light) {
    Centroids c;
    const glm::vec3 center = builtin::kSphereCenter;
    for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x) {
            const size_t i = size_t{y} * r.width + x;
            if (!onGround(r, i))
                continue;
            const glm::vec3 p = pixelVec(r.position, i);
            const glm::vec3 toLight = light.type == LightType::Directional
                                          ? -glm::normalize(light.direction)
                                          : glm::normalize(light.position - p);
            const float d = rayPointDistance(p, toLight, center);
            if (d > builtin::kSphereRadius + 0.5f)
                continue;
            const glm::dvec2 pixel(x + 0.5, y + 0.5);
            if (d < builtin::kSphereRadius)
                c.expected += pixel, ++c.expectedCount;
            if (r.visibility[0][i] < 0.5f)
                c.rendered += pixel, ++c.renderedCount;
        }
    if (c.expectedCount)
        c.expected /= static_cast<double>(c.expectedCount);
    if (c.renderedCount)
        c.rendered /= static_cast<double>(c.renderedCount);
    return c;
}

// The rendered shadow has the analytic one's size (within 5%) and centroid (within 2 pixels).
void expectSphereShadowWhereProjected(const RenderResult& r, const Light& light) {
    const Centroids c = sphereShadowCentroids(r, light);
    std::printf("sphere shadow: %zu expected / %zu rendered pixels, centroid error %.3f px\n",
                c.expectedCount, c.renderedCount, glm::length(c.rendered - c.expected));
    ASSERT_GT(c.expectedCount, 2000u);
    // Measured (lavapipe, 1280x720, map 2048): counts within 0.3%, centroids 0.044 px (sun) and
    // 0.054 px (spot) apart.
    EXPECT_NEAR(static_cast<double>(c.renderedCount), static_cast<double>(c.expectedCount),
                0.01 * static_cast<double>(c.expectedCount));
    EXPECT_LT(glm::length(c.rendered - c.expected), 0.25)
        << "rendered (" << c.rendered.x << ", " << c.rendered.y << ") expected (" << c.expected.x
        << ", " << c.expected.y << ")";
}

} // namespace

TEST_F(BiasTest, GrazingPlaneIsAcneFreeWithDefaultBias) {
    const Scene scene = loadScene("builtin:grazing");
    const RenderResult r = render(scene, {.width = 640, .height = 360});
    size_t lit = 0;
    const double acne = grazingAcneFraction(r, scene, 0.15f, &lit);
    std::printf("grazing, default bias: %zu lit plane pixels, acne fraction %.5f\n", lit, acne);
    EXPECT_GT(lit, 640u * 360u / 4) << "the plane should fill much of the view";
    EXPECT_LE(acne, 1e-5) << "acne fraction with default bias"; // measured: 0 of 194,525
}

TEST_F(BiasTest, GrazingPlaneShowsAcneWithoutBias) {
    const Scene scene = loadScene("builtin:grazing");
    RenderOptions o{.width = 640, .height = 360};
    o.parameters.assign("bias.mode=fixed");
    o.parameters.assign("bias.constant=0");
    o.parameters.assign("bias.slope=0");
    o.parameters.assign("bias.normal=0");
    o.parameters.assign("bias.receiver=off");
    const RenderResult r = render(scene, o);
    size_t lit = 0;
    const double acne = grazingAcneFraction(r, scene, 0.15f, &lit);
    std::printf("grazing, zero bias: acne fraction %.4f\n", acne);
    EXPECT_GT(acne, 0.45) << "zero bias must show acne"; // measured: 0.499
}

TEST_F(ShadowTest, SphereShadowSitsWhereTheDirectionalLightProjectsIt) {
    expectSphereShadowWhereProjected(render(loadScene("builtin:showcase"), {}),
                                     loadScene("builtin:showcase").lights[0]);
}

TEST_F(ShadowTest, SphereShadowSitsWhereTheSpotLightProjectsIt) {
    expectSphereShadowWhereProjected(render(loadScene("builtin:spot"), {}),
                                     loadScene("builtin:spot").lights[0]);
}

TEST_F(ShadowTest, PoleShadowStaysAttachedAtItsBase) {
    // Peter-panning check: ground pixels just beyond the pole's foot, on the side away from the
    // light, must be in shadow with the default bias.
    const Scene scene = loadScene("builtin:showcase");
    const RenderResult r = render(scene, {});
    const glm::vec3 toLight = -glm::normalize(scene.lights[0].direction);
    const glm::vec3 axis = glm::normalize(builtin::kPoleTip - builtin::kPoleBase);
    size_t near = 0, shadowed = 0;
    for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
        if (!onGround(r, i))
            continue;
        const glm::vec3 p = pixelVec(r.position, i);
        // Ground points whose light ray passes through the pole's core, 0.1 to 0.3 units up
        // the pole from its foot: n is the normal of the plane holding the axis and the ray.
        const glm::vec3 w = p - builtin::kPoleBase;
        const glm::vec3 n = glm::normalize(glm::cross(axis, toLight));
        const float across = std::abs(glm::dot(w, n));
        // In that plane, p + t toLight = base + s axis; dotting with perp removes t.
        const glm::vec3 perp = glm::cross(n, toLight);
        const float s = glm::dot(w, perp) / glm::dot(axis, perp);
        if (across > 0.25f * builtin::kPoleThickness || s < 0.1f || s > 0.3f)
            continue;
        ++near;
        shadowed += r.visibility[0][i] < 0.5f;
    }
    std::printf("pole foot: %zu of %zu ground pixels shadowed\n", shadowed, near);
    ASSERT_GT(near, 3u);
    EXPECT_EQ(shadowed, near);
}

TEST_F(ShadowTest, BackgroundIsNaNAndGeometryIsBinaryVisibility) {
    const Scene scene = loadScene("builtin:showcase");
    const RenderResult r = render(scene, {.width = 160, .height = 90, .shadowMapSize = 512});
    ASSERT_EQ(r.visibility.size(), 1u);
    size_t background = 0;
    for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
        const float v = r.visibility[0][i];
        if (std::isnan(v)) {
            ++background;
            EXPECT_TRUE(std::isnan(r.position[3 * i]));
            EXPECT_TRUE(std::isnan(r.normal[3 * i]));
        } else {
            EXPECT_TRUE(v == 0.0f || v == 1.0f) << v;
            EXPECT_NEAR(glm::length(pixelVec(r.normal, i)), 1.0f, 1e-3f);
        }
    }
    EXPECT_GT(background, 0u); // the sky in the top rows
    EXPECT_TRUE(std::isnan(r.visibility[0][0]));
    EXPECT_FALSE(std::isnan(r.visibility[0][size_t{r.width} * (r.height - 1)])); // ground below
}

TEST_F(ShadowTest, RefusesSizesPastTheDeviceLimit) {
    const Scene scene = loadScene("builtin:showcase");
    const uint32_t limit = sharedRenderer().device().maxImageDimension2D;
    RenderOptions o{.shadowMapSize = limit + 1};
    EXPECT_THROW(sharedRenderer().check(scene, o), InputError);
    o = {.width = limit + 1};
    EXPECT_THROW(sharedRenderer().check(scene, o), InputError);
    o = {.camera = "no such camera"};
    EXPECT_THROW(sharedRenderer().check(scene, o), InputError);
    // smrt's checkerboard list (2 bytes a pixel) past the device's storage buffers: refused,
    // naming the limit; without the checkerboard the list is not what stops it.
    const uint64_t range = sharedRenderer().device().maxStorageBufferRange;
    const auto side = static_cast<uint32_t>(std::ceil(std::sqrt(double(range) / 2.0)));
    if (side <= limit) {
        o = {.width = side, .height = side, .technique = Technique::Smrt};
        try {
            sharedRenderer().check(scene, o);
            ADD_FAILURE() << side << "x" << side << ": smrt's trace list was not refused";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("maxStorageBufferRange"), std::string::npos)
                << e.what();
            EXPECT_NE(std::string(e.what()).find("set smrt.checkerboard=false"), std::string::npos)
                << e.what(); // the parameter the fill declares
        }
        o.parameters.set("smrt.checkerboard", "false");
        try {
            sharedRenderer().check(scene, o);
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).find("maxStorageBufferRange"), std::string::npos)
                << e.what();
        }
    }
}

TEST_F(QualityTest, HardMatchesTheRadiusZeroGroundTruthOutsideEdges) {
    Scene scene = loadScene("builtin:showcase");
    const RenderResult r = render(
        scene, {.width = 512, .height = 512, .shadowMapSize = 2048, .lightAngleOverride = 0.0f});
    applyLightSizeOverrides(scene, -1.0f, 0.0f);
    const ReferenceResult truth = computeReference(scene, r, {.samples = 1});
    ASSERT_EQ(truth.visibility.size(), 1u);
    const std::vector<uint8_t> mask = lightMask(scene.lights[r.lights[0].sceneLight], r);
    const MetricLayer layer{r.visibility[0], truth.visibility[0], mask};
    const ErrorMetrics m = computeMetrics(r.width, r.height, std::span(&layer, 1));
    std::printf("hard vs radius-0 truth: rmse %.4f, misclassified %.4f%%, outside edges %.4f%%, "
                "acne %.4f%%, leak %.4f%% over %llu pixels\n",
                m.rmse, 100 * m.misclassified, 100 * m.misclassifiedOutsideEdges, 100 * m.acne,
                100 * m.leak, static_cast<unsigned long long>(m.pixels));
    EXPECT_GT(m.pixels, 512u * 512u / 3);
    // Measured: rmse 0.0313, misclassified 0.098%, none outside the edge band.
    EXPECT_LT(m.misclassifiedOutsideEdges, 1e-4);
    EXPECT_LT(m.rmse, 0.036);
    EXPECT_LT(m.misclassified, 0.00115);
}

TEST_F(ShadowTest, RasterizerDropsInvalidTrianglesLikeTheGroundTruth) {
    const Scene clean = loadScene("builtin:showcase");
    Scene hostile = clean;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const uint32_t base = static_cast<uint32_t>(hostile.vertices.size());
    for (const glm::vec3& p : {glm::vec3(0, 3, 0), glm::vec3(nan, 3, 0), glm::vec3(0, 3, 1),
                               glm::vec3(1e30f, 9, 0), glm::vec3(0, 2, 0), glm::vec3(1, 2, 0)})
        hostile.vertices.push_back({p, {0, 1, 0}, 0});
    hostile.indices.insert(hostile.indices.end(),
                           {base, base + 1, base + 2, base + 3, base + 4, base + 5});
    const RenderOptions o{.width = 160, .height = 120, .shadowMapSize = 512};
    const RenderResult a = render(clean, o);
    const RenderResult b = render(hostile, o);

    ASSERT_EQ(a.visibility.size(), b.visibility.size());
    // Same bounds, same light fit, same pixels: the invalid triangles never reached the GPU.
    EXPECT_EQ(0, std::memcmp(a.visibility[0].data(), b.visibility[0].data(),
                             a.visibility[0].size() * sizeof(float)));
    EXPECT_EQ(a.image, b.image);
}

TEST_F(ShadowTest, PixelsOutsideTheSpotsFrustumReadUnoccluded) {
    // Nothing in the shadow map can shadow a point the map does not cover: its visibility is 1
    // (the composite's cone then decides how much light reaches it).
    const Scene scene = loadScene("builtin:spot");
    const RenderResult r = render(scene, {.width = 320, .height = 180, .shadowMapSize = 512});
    size_t outside = 0, inside = 0, shadowedInside = 0;
    for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
        const glm::vec3 p = pixelVec(r.position, i);
        if (!std::isfinite(p.x))
            continue;
        const glm::vec4 s = r.lights[0].views[0].worldToShadow * glm::vec4(p, 1.0f);
        const glm::vec2 uv = glm::vec2(s) / s.w;
        if (s.w <= 0.0f || uv.x < -0.01f || uv.x > 1.01f || uv.y < -0.01f || uv.y > 1.01f) {
            ++outside;
            EXPECT_EQ(r.visibility[0][i], 1.0f) << "pixel " << i << " outside the frustum";
        } else {
            ++inside;
            shadowedInside += r.visibility[0][i] < 0.5f;
        }
    }
    std::printf("spot: %zu pixels outside its frustum, %zu inside (%zu shadowed)\n", outside,
                inside, shadowedInside);
    EXPECT_GT(outside, 2000u);
    EXPECT_GT(shadowedInside, 1000u);
}

TEST_F(ShadowTest, ASceneRendererGivesWhatAFreshRenderGivesWhateverCameBefore) {
    // One upload, then renders that change the technique (and its shadow maps), the sizes, the
    // light size, the camera and the parameters, and come back: each result must be the one a
    // fresh render of the same options gives, bit for bit (no stale target, no stale ring slot).
    Scene scene = loadScene("builtin:showcase");
    scene.cameras.push_back({.name = "side", .position = {9, 3, 2}, .target = {0, 0.5f, 0}});
    std::vector<RenderOptions> sequence;
    auto add = [&](RenderOptions o, std::vector<const char*> sets) {
        o.frames = 1;
        for (const char* s : sets)
            o.parameters.assign(s);
        sequence.push_back(o);
    };
    add({.width = 96, .height = 64, .shadowMapSize = 256}, {});
    add({.width = 96, .height = 64, .shadowMapSize = 256, .technique = Technique::SecondDepth}, {});
    add({.width = 80, .height = 60, .shadowMapSize = 512, .technique = Technique::Pcf},
        {"pcf.filter=poisson"});
    add({.width = 80,
         .height = 60,
         .shadowMapSize = 512,
         .camera = "side",
         .technique = Technique::Pcss,
         .lightAngleOverride = 6.0f},
        {"composite.shadowIntensity=0.5"});
    add({.width = 96, .height = 64, .shadowMapSize = 256}, {});
    SceneRenderer persistent(sharedRenderer(), scene);
    for (size_t i = 0; i < sequence.size(); ++i) {
        const RenderResult a = persistent.render(sequence[i]);
        const RenderResult b = sharedRenderer().render(scene, sequence[i]);
        EXPECT_EQ(a.image, b.image) << "render " << i;
        ASSERT_EQ(a.visibility.size(), b.visibility.size()) << "render " << i;
        EXPECT_EQ(0, std::memcmp(a.visibility[0].data(), b.visibility[0].data(),
                                 a.visibility[0].size() * sizeof(float)))
            << "render " << i;
        EXPECT_EQ(
            0, std::memcmp(a.position.data(), b.position.data(), a.position.size() * sizeof(float)))
            << "render " << i;
    }
}

TEST_F(ShadowTest, EveryLightFiltersItsOwnShadowView) {
    // Five lights, four with a shadow map (the sun and the spot a view each, the bulb six cube
    // faces: layers of the technique's maps), one without: each light's visibility must be what
    // a render with that light alone gives, bit for bit, for a technique whose maps have post
    // passes (second-depth) and one that reads the view's geometry (PCSS).
    Scene all = loadScene("builtin:showcase");
    all.lights.push_back({.name = "bulb", .type = LightType::Point, .position = {2, 4, 2}});
    all.lights.push_back(loadScene("builtin:spot").lights[0]);
    all.lights.push_back({.name = "low sun",
                          .type = LightType::Directional,
                          .direction = glm::normalize(glm::vec3(-0.8f, -0.5f, -0.2f)),
                          .angularDiameter = 3.0f});
    all.lights.push_back(
        {.name = "fill", .type = LightType::Point, .position = {-2, 3, 4}, .castsShadow = false});
    for (const Technique technique : {Technique::SecondDepth, Technique::Pcss}) {
        const RenderOptions o{
            .width = 128, .height = 96, .shadowMapSize = 512, .technique = technique};
        const RenderResult r = render(all, o);
        ASSERT_EQ(r.visibility.size(), 4u);
        EXPECT_EQ(r.lights[4].visibilityIndex, -1);
        for (const LightShadow& s : r.lights) {
            if (s.visibilityIndex < 0)
                continue;
            Scene alone = all;
            alone.lights = {all.lights[s.sceneLight]};
            const RenderResult single = render(alone, o);
            EXPECT_EQ(0, std::memcmp(r.visibility[s.visibilityIndex].data(),
                                     single.visibility[0].data(),
                                     single.visibility[0].size() * sizeof(float)))
                << techniqueName(technique) << ", light " << s.sceneLight;
        }
    }
}

// Odd image sizes: the readback packs 4-byte and 16-byte images into one buffer, and each copy's
// offset must be a multiple of its texel block (the CLI fuzzer found 33x33 breaking it). Every
// output must also read back where it belongs: the position of the middle pixel is on the scene
// and the visibility of a background pixel is NaN, for a sun, a spot and a bulb's cube faces.
TEST_F(ShadowTest, OddImageSizesReadBackEveryOutputInPlace) {
    for (const Scene& scene : {builtin::showcase(), builtin::spot(), builtin::room()})
        for (const auto& [w, h] : {std::pair{33u, 33u}, std::pair{31u, 17u}}) {
            const RenderResult r = render(scene, {.width = w, .height = h, .shadowMapSize = 64});
            ASSERT_EQ(r.image.size(), size_t{w} * h * 4);
            const size_t middle = size_t{h / 2} * w + w / 2;
            EXPECT_TRUE(std::isfinite(pixelVec(r.position, middle).x)) << scene.name;
            EXPECT_NEAR(glm::length(pixelVec(r.normal, middle)), 1.0f, 1e-3f) << scene.name;
            for (const std::vector<float>& v : r.visibility) {
                ASSERT_EQ(v.size(), size_t{w} * h);
                for (size_t i = 0; i < v.size(); ++i)
                    ASSERT_EQ(std::isnan(v[i]), std::isnan(r.position[3 * i]))
                        << scene.name << " " << w << "x" << h << " pixel " << i;
            }
        }
}
