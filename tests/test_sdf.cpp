// Technique `sdf`: the GPU-built field against the CPU reference of src/reference/distance_field.h
// (exact distances in double precision, the sign from the generalised winding number), the field's
// cache, and the traced shadows against the ray-traced truth on a sphere over a plane for every
// light type, at the bounds.
#include "analytic_scenes.h"
#include "penumbra/error.h"
#include "penumbra/reference.h"
#include "reference/distance_field.h"
#include "render/distance_field.h"
#include "truth_fixture.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// The sphere of sphereOverPlane alone (or its plane).
Scene partOf(const Scene& scene, bool sphere) {
    Scene part = scene;
    part.indices.clear();
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const bool isPlane = scene.vertices[scene.indices[3 * t]].position.y == 0.0f &&
                             scene.vertices[scene.indices[3 * t + 1]].position.y == 0.0f &&
                             scene.vertices[scene.indices[3 * t + 2]].position.y == 0.0f;
        if (isPlane != sphere)
            for (int k = 0; k < 3; ++k)
                part.indices.push_back(scene.indices[3 * t + k]);
    }
    return part;
}

// The signed distance to the square |x|, |z| <= half at y = 0 swept `thickness` up and down, as
// the field gives open geometry without holes (its slab goes on past the triangles' edges inside
// it): in closed form.
double slabDistance(const glm::dvec3& p, double half, double thickness) {
    const glm::dvec2 outside(std::abs(p.x) - half, std::abs(p.z) - half);
    const double inPlane =
        outside.x > 0 || outside.y > 0 ? glm::length(glm::max(outside, glm::dvec2(0.0))) : -1e300;
    const glm::dvec2 w(inPlane, std::abs(p.y) - thickness);
    return glm::length(glm::max(w, glm::dvec2(0.0))) + std::min(std::max(w.x, w.y), 0.0);
}

struct FieldRead {
    DistanceFieldInfo info;
    std::vector<float> voxels;
    float at(uint32_t x, uint32_t y, uint32_t z) const {
        return voxels[(size_t{z} * info.voxels.y + y) * info.voxels.x + x];
    }
    glm::dvec3 centre(uint32_t x, uint32_t y, uint32_t z) const {
        return glm::dvec3(info.origin) + (glm::dvec3(x, y, z) + 0.5) * double(info.voxelSize);
    }
};

FieldRead renderField(SceneRenderer& renderer, const std::string& resolution,
                      const std::string& thickness = "0.75") {
    RenderOptions o{.width = 32, .height = 32, .frames = 1, .technique = Technique::Sdf};
    o.parameters.set("sdf.resolution", resolution);
    o.parameters.set("sdf.thickness", thickness);
    const RenderResult r = renderer.render(o);
    FieldRead f;
    f.voxels = renderer.distanceField(f.info);
    EXPECT_TRUE(r.field.has_value());
    return f;
}

} // namespace

// Every voxel of a sphere over a plane against the CPU reference: the sphere (closed) signed, the
// plane (open) as the prism of its thickness; exact near the surfaces, within a small fraction of
// the distance far away (jump flooding may keep a near-nearest triangle).
TEST_F(FieldTest, FieldOfASphereOverAPlaneMatchesTheReference) {
    const Scene scene = sphereOverPlane(Light{.type = LightType::Directional});
    const Scene sphere = partOf(scene, true);
    ASSERT_EQ(sphere.triangleCount() + 2, scene.triangleCount()); // all but the plane's two
    SceneRenderer renderer(sharedRenderer(), scene);
    const FieldRead f = renderField(renderer, "128");
    ASSERT_EQ(f.voxels.size(), size_t{f.info.voxels.x} * f.info.voxels.y * f.info.voxels.z);
    const double thickness = 0.75 * f.info.voxelSize;
    // Voxels anywhere, and as many again around the sphere.
    std::mt19937 rng(5);
    auto pick = [&](uint32_t lo, uint32_t hi) {
        return std::uniform_int_distribution<uint32_t>(lo, hi - 1)(rng);
    };
    const glm::uvec3 sphereLow((glm::dvec3(-1.0, 0.3, -1.0) - glm::dvec3(f.info.origin)) /
                               double(f.info.voxelSize));
    const auto span = static_cast<uint32_t>(2.0 / f.info.voxelSize);
    double worstNear = 0, worstFar = 0;
    size_t inside = 0, wrongSign = 0;
    const size_t samples = 2000;
    for (size_t i = 0; i < samples; ++i) {
        const glm::uvec3 v =
            i % 2 ? glm::uvec3(pick(0, f.info.voxels.x), pick(0, f.info.voxels.y),
                               pick(0, f.info.voxels.z))
                  : sphereLow + glm::uvec3(pick(0, span), pick(0, span), pick(0, span));
        const glm::dvec3 p = f.centre(v.x, v.y, v.z);
        const FieldSample s = sampleDistanceField(sphere, p);
        const double ground = slabDistance(p, 20.0, thickness);
        const bool in = s.winding > 0.5;
        const double expected = in ? -s.distance : std::min(s.distance, ground);
        const double got = f.at(v.x, v.y, v.z);
        inside += in;
        if ((got < 0) != (expected < 0) && std::abs(expected) > 1e-4)
            ++wrongSign;
        const double error = std::abs(got - expected);
        if (std::abs(expected) < 4 * FIELD_BRICK * f.info.voxelSize)
            worstNear = std::max(worstNear, error);
        else
            worstFar = std::max(worstFar, error / std::abs(expected));
    }
    EXPECT_GT(inside, samples / 20);
    EXPECT_EQ(wrongSign, 0u) << "of " << samples;
    EXPECT_LT(worstNear, 1e-4) << "world units";
    EXPECT_LT(worstFar, 0.02) << "relative";
}

// The acceptance bounds on a sphere over a plane, for each light type: the soft region's
// RMSE under 0.6x a 7x7 box PCF's and under 0.07, acne under 0.1%, leak under 1%.
TEST_F(QualityTest, DistanceFieldShadowsMatchTheTruthForEveryLightType) {
    const Light lights[] = {acceptanceSpot(0.5f), acceptanceSun(6.0f), acceptancePoint(0.3f)};
    for (const Light& light : lights) {
        const Truth t =
            groundTruth(sphereOverPlane(light),
                        {.width = 192, .height = 192, .shadowMapSize = 2048, .samples = 64});
        const double box7 = softRegionRmse(
            t, renderRow(t, Technique::Pcf, {{"pcf.filter", "box"}, {"pcf.size", "7"}}));
        const RenderResult r = renderRow(t, Technique::Sdf, {});
        const double rmse = softRegionRmse(t, r);
        const ErrorMetrics m = errorOf(t, r);
        std::printf("%s: soft-region rmse pcf box7 %.4f, sdf %.4f (%.2fx); acne %.3f%%, leak "
                    "%.3f%%, misclassified %.3f%%\n",
                    light.name.c_str(), box7, rmse, rmse / box7, 100 * m.acne, 100 * m.leak,
                    100 * m.misclassified);
        EXPECT_LT(rmse, 0.6 * box7) << light.name;
        EXPECT_LT(rmse, 0.07) << light.name;
        EXPECT_LT(m.acne, 0.001) << light.name;
        EXPECT_LT(m.leak, 0.01) << light.name;
    }
}

// The tracer on the GPU against its CPU mirror (traceFieldVisibility) over the same field, read
// back, at every ground pixel: the same steps, so the same visibility up to the sampler's
// interpolation precision.
TEST_F(FieldTest, TracerMatchesItsCpuMirrorOverTheSameField) {
    const Light lights[] = {acceptanceSun(6.0f), acceptancePoint(0.3f)};
    for (const Light& light : lights) {
        const Scene scene = sphereOverPlane(light);
        SceneRenderer renderer(sharedRenderer(), scene);
        RenderOptions o{.width = 96, .height = 96, .frames = 1, .technique = Technique::Sdf};
        o.parameters.set("sdf.resolution", "128");
        const RenderResult r = renderer.render(o);
        FieldGrid grid;
        DistanceFieldInfo info;
        grid.values = renderer.distanceField(info);
        grid.origin = info.origin;
        grid.voxel = info.voxelSize;
        grid.size = info.voxels;
        size_t n = 0, far = 0, soft = 0;
        double sum = 0;
        for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
            if (!onGround(r, i))
                continue;
            const float cpu = traceFieldVisibility(
                grid, light, pixelVec(r.position, i), {0, 1, 0},
                traceSettingsOf(shadows::moduleOf(Technique::Sdf), o.parameters));
            const double d = std::abs(cpu - r.visibility[0][i]);
            ++n;
            sum += d;
            far += d > 0.02;
            soft += cpu > 0.02f && cpu < 0.98f;
        }
        std::printf("%s: %zu ground pixels (%zu in penumbrae), mean |gpu - cpu| %.5f, %zu over "
                    "0.02\n",
                    light.name.c_str(), n, soft, sum / double(n), far);
        ASSERT_GT(n, 3000u);
        EXPECT_GT(soft, 50u) << light.name;
        EXPECT_LT(sum / double(n), 2e-4) << light.name;
        EXPECT_LT(double(far), 0.01 * double(n)) << light.name;
    }
}

// A closed plate 3 x 3 and 0.03 thick, 1 above the ground, under a sun of 4 degrees straight down:
// the umbra is the plate's square less the penumbra's inner half (1 x tan 2 degrees, 0.035) each
// side. Inside a plate a few voxels deep, how deep the ray runs says nothing of how wide the plate
// is: the umbra must be dark at a coarse field and the automatic one alike, and lit beyond the
// penumbra's outer half.
TEST_F(FieldTest, AThinPlateHidesTheWholeLightUnderIt) {
    Scene scene;
    MeshBuilder mb(scene);
    const float g = 2.5f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, mb.material("ground", glm::vec3(0.7f)));
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0, 1, 0}), {3.0f, 0.03f, 3.0f}),
           mb.material("plate", glm::vec3(0.7f)));
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = {0, -1, 0},
                            .angularDiameter = 4.0f});
    scene.cameras.push_back({.name = "slanted",
                             .position = {0, 4, 4},
                             .target = {0, 0, 0},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 50.0f});
    SceneRenderer renderer(sharedRenderer(), scene);
    for (const char* resolution : {"256", "0"}) { // the plate 1.5 voxels thick, and 2
        RenderOptions o{.width = 96, .height = 96, .frames = 1, .technique = Technique::Sdf};
        o.parameters.set("sdf.resolution", resolution);
        const RenderResult r = renderer.render(o);
        size_t umbra = 0, lit = 0, leaking = 0, dark = 0;
        for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
            if (!onGround(r, i))
                continue;
            const glm::vec3 p = pixelVec(r.position, i);
            const float out = std::max(std::abs(p.x), std::abs(p.z)) - 1.5f; // past the edge
            if (out < -0.035f - 0.02f)
                ++umbra, leaking += r.visibility[0][i] > 0.1f;
            else if (out > 0.035f + 0.02f)
                ++lit, dark += r.visibility[0][i] < 0.9f;
        }
        ASSERT_GT(umbra, 500u);
        ASSERT_GT(lit, 500u);
        EXPECT_LE(leaking, umbra / 200) << "resolution " << resolution << ": " << leaking << " of "
                                        << umbra << " umbra pixels over 0.1";
        EXPECT_LE(dark, lit / 200) << "resolution " << resolution;
    }
}

// Built once per scene and field setting: another technique, camera, light size or tracing
// parameter reuses it; another resolution or thickness rebuilds it.
TEST_F(FieldTest, FieldIsBuiltOncePerSceneAndFieldSetting) {
    const Scene scene =
        sphereOverPlane(Light{.type = LightType::Directional,
                              .direction = glm::normalize(glm::vec3(0.3f, -1, 0.2f)),
                              .angularDiameter = 2.0f});
    SceneRenderer renderer(sharedRenderer(), scene);
    RenderOptions o{.width = 32, .height = 32, .frames = 1, .technique = Technique::Sdf};
    o.parameters.set("sdf.resolution", "64");
    auto built = [&](const RenderOptions& options, const SceneRenderer::FrameState& state = {}) {
        const RenderResult r = renderer.render(options, state);
        EXPECT_TRUE(r.field.has_value());
        return r.field && r.field->built;
    };
    EXPECT_TRUE(built(o));
    EXPECT_FALSE(built(o));
    // The build's GPU time is its passes' (seed, flood, resolve; each timed, so above zero).
    SceneRenderer fresh(sharedRenderer(), scene);
    const RenderResult first = fresh.render(o);
    ASSERT_TRUE(first.field.has_value());
    ASSERT_EQ(first.field->buildPasses.size(), 3u);
    double passes = 0.0;
    for (const PassTime& pass : first.field->buildPasses) {
        EXPECT_GT(pass.medianMs, 0.0) << pass.pass;
        passes += pass.medianMs;
    }
    EXPECT_NEAR(first.field->buildGpuMs, passes, 1e-9 * passes);
    RenderOptions other = o;
    other.technique = Technique::Pcss;
    EXPECT_FALSE(renderer.render(other).field.has_value());
    EXPECT_FALSE(built(o)); // back from another technique
    Camera moved = scene.cameras[0];
    moved.position += glm::vec3(1.0f, 0.5f, 0.0f);
    EXPECT_FALSE(built(o, {.camera = moved}));
    RenderOptions traced = o;
    traced.parameters.set("sdf.steps", "32");
    traced.parameters.set("sdf.k", "12");
    traced.lightAngleOverride = 5.0f;
    EXPECT_FALSE(built(traced));
    RenderOptions finer = o;
    finer.parameters.set("sdf.resolution", "96");
    EXPECT_TRUE(built(finer));
    RenderOptions thicker = finer;
    thicker.parameters.set("sdf.thickness", "1.5");
    EXPECT_TRUE(built(thicker));
    EXPECT_FALSE(built(thicker));
}

// Every pass is timed in every frame after the warm-up, and its median is that of its frames.
TEST_F(FieldTest, EveryPassIsTimedEachFrameAndItsMedianIsTheirs) {
    const Scene scene = sphereOverPlane(Light{.type = LightType::Spot});
    SceneRenderer renderer(sharedRenderer(), scene);
    RenderOptions o{.width = 16, .height = 16, .frames = 3, .technique = Technique::Sdf};
    o.parameters.set("sdf.resolution", "32");
    const RenderResult r = renderer.render(o);
    ASSERT_GE(r.passes.size(), 3u);
    for (const PassTime& p : r.passes) {
        ASSERT_EQ(p.frameMs.size(), 3u) << p.pass;
        std::vector<double> sorted = p.frameMs;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(p.medianMs, sorted[1]) << p.pass;
    }
}

// A sun of 0.5 degrees: almost hard shadows, which the field must place: misclassified pixels
// away from edges under 0.5% (the bound), for the default field.
TEST_F(QualityTest, DistanceFieldPlacesNearlyHardShadows) {
    const Truth t = groundTruth(sphereOverPlane(acceptanceSun(0.5f)),
                                {.width = 192, .height = 192, .samples = 16});
    const RenderResult r = renderRow(t, Technique::Sdf, {});
    const ErrorMetrics m = errorOf(t, r);
    std::printf("sun 0.5 degrees: misclassified %.3f%% (%.3f%% away from edges), acne %.3f%%, "
                "leak %.3f%%\n",
                100 * m.misclassified, 100 * m.misclassifiedOutsideEdges, 100 * m.acne,
                100 * m.leak);
    EXPECT_LT(m.misclassifiedOutsideEdges, 0.005);
    EXPECT_LT(m.acne, 0.001);
    EXPECT_LT(m.leak, 0.01);
}

// Bad field settings are refused before anything is built: past the voxel cap, with the
// parameter named.
TEST_F(FieldTest, FieldPastItsCapIsRefused) {
    Scene scene = sphereOverPlane(Light{.type = LightType::Directional});
    // A cube-shaped scene: 1024 voxels on each axis is 2^30, past the 2^27 cap.
    MeshBuilder(scene).box(glm::scale(glm::mat4(1.0f), glm::vec3(40.0f)), 0);
    RenderOptions o{.width = 16, .height = 16, .frames = 1, .technique = Technique::Sdf};
    o.parameters.set("sdf.resolution", "1024");
    try {
        (void)sharedRenderer().render(scene, o);
        ADD_FAILURE() << "a field of 2^30 voxels was built";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("sdf.resolution"), std::string::npos) << e.what();
    }
}

// A field past the device's memory (PENUMBRA_DEVICE_MEMORY: what the checks assume) is refused
// by the render's check, before anything is built, naming the parameter the module declares for
// the field's resolution and what it needs; a device with room passes the same check.
TEST_F(FieldTest, FieldPastTheDevicesMemoryIsRefusedNamingItsResolution) {
    const Scene scene = sphereOverPlane(Light{.type = LightType::Directional});
    RenderOptions o{.width = 16, .height = 16, .frames = 1, .technique = Technique::Sdf};
    o.parameters.set("sdf.resolution", "256");
    EXPECT_NO_THROW(sharedRenderer().check(scene, o));
    setenv("PENUMBRA_DEVICE_MEMORY", std::to_string(1u << 20).c_str(), 1);
    std::string message;
    try {
        sharedRenderer().check(scene, o);
    } catch (const InputError& e) {
        message = e.what();
    }
    unsetenv("PENUMBRA_DEVICE_MEMORY");
    EXPECT_NE(message.find("sdf.resolution"), std::string::npos) << message;
    EXPECT_NE(message.find("256 needs"), std::string::npos) << message;
    EXPECT_NE(message.find("to build its field"), std::string::npos) << message;
}

// Alpha-tested casters enter the field cut down to their covered parts: a card of 8x8 squares,
// every other one a hole (0.5 units, five voxels of the default field), held over a plane under
// a parallel sun: the ground the sdf lights is the ground the truth lights; drawn opaque, the
// card lets no light through. (Holes of a voxel or two close up: the foliage's leaves need a
// finer field, docs/techniques.md.)
TEST_F(MaterialTest, DistanceFieldSeesThroughAlphaTestedHoles) {
    for (const bool masked : {true, false}) {
        Scene scene;
        MeshBuilder mb(scene);
        mb.quad({-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, {-10, 0, -10},
                mb.material("ground", glm::vec3(0.7f)));
        TextureImage checker{.name = "checker", .width = 8, .height = 8};
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x)
                checker.rgba.insert(checker.rgba.end(),
                                    {200, 200, 200, uint8_t((x + y) % 2 ? 255 : 0)});
        const uint32_t card = mb.texturedMaterial(
            "card", checker,
            {.wrapS = TextureWrap::ClampToEdge, .wrapT = TextureWrap::ClampToEdge, .nearest = true},
            masked ? AlphaMode::Mask : AlphaMode::Opaque);
        mb.quad({-2, 2, 2}, {2, 2, 2}, {2, 2, -2}, {-2, 2, -2}, card);
        scene.lights.push_back({.type = LightType::Directional,
                                .direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f))});
        scene.cameras.push_back({.position = {0.0f, 9.0f, 4.0f}, .target = {0, 0, 0}});
        const RenderResult r =
            render(scene, {.width = 160, .height = 160, .technique = Technique::Sdf});
        // The stats count the scene's triangles, and the pieces the masked card became apart.
        ASSERT_TRUE(r.field.has_value());
        EXPECT_EQ(r.field->triangles, scene.triangleCount());
        EXPECT_EQ(r.field->alphaTriangles, masked ? 2u : 0u);
        EXPECT_EQ(r.field->fieldTriangles, 2u + (masked ? r.field->alphaPieces : 2u));
        EXPECT_EQ(r.field->alphaPieces > 2u, masked);
        const ReferenceResult truth = computeReference(scene, r, {.samples = 1});
        const glm::vec3 toLight = -scene.lights[0].direction;
        size_t n = 0, gpuLit = 0, truthLit = 0, disagree = 0;
        for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
            if (!onGround(r, i))
                continue;
            const glm::vec3 hit = pixelVec(r.position, i) + (2.0f / toLight.y) * toLight;
            if (std::abs(hit.x) > 1.9f || std::abs(hit.z) > 1.9f)
                continue;
            ++n;
            gpuLit += r.visibility[0][i] > 0.5f;
            truthLit += truth.visibility[0][i] > 0.5f;
            disagree += (r.visibility[0][i] > 0.5f) != (truth.visibility[0][i] > 0.5f);
        }
        std::printf("%s card: %zu ground pixels under it, lit: sdf %.3f, truth %.3f; %.1f%% "
                    "disagree\n",
                    masked ? "alpha-tested" : "opaque", n, double(gpuLit) / double(n),
                    double(truthLit) / double(n), 100.0 * double(disagree) / double(n));
        // Measured: lit 0.507 (sdf) against 0.504 (truth), 1.2% of the pixels disagree. Before
        // open geometry kept its outline (a rounded offset), 0.327; before the pieces inside
        // a covered region ignored their inner edges, 0.591.
        ASSERT_GT(n, masked ? 2000u : 500u); // the opaque card hides part of the ground
        if (masked) {
            EXPECT_NEAR(double(truthLit) / double(n), 0.5, 0.05);
            EXPECT_NEAR(double(gpuLit) / double(n), double(truthLit) / double(n), 0.025);
            EXPECT_LT(double(disagree) / double(n), 0.04);
        } else {
            EXPECT_LT(double(gpuLit) / double(n), 0.005);
        }
    }
}
