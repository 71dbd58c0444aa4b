// The ground truth against closed-form answers (a sphere above a plane), the sampling maths,
// and its handling of hostile geometry. CPU only: the G-buffer is a synthetic grid.
#include "penumbra/reference.h"
#include "plane_grid.h"
#include "reference/analytic.h"
#include "reference/sampling.h"
#include "scene/mesh_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using namespace penumbra;
using penumbra::test::planeGrid;

namespace {

constexpr glm::vec3 kCenter{0.0f, 2.0f, 0.0f};
constexpr float kRadius = 1.0f;
constexpr uint32_t kGrid = 128;

Scene sphereOverPlane(const Light& light) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("grey", glm::vec3(0.5f));
    mb.quad({-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, {-20, 0, -20}, m);
    mb.sphere(kCenter, kRadius, m, 512, 256); // fine: the inscribed mesh stays within 2e-5 of it
    scene.lights.push_back(light);
    return scene;
}

glm::dvec3 at(const RenderResult& g, size_t i) {
    return {g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]};
}

// Analytic visibility of every grid pixel, for the light's sampled cone.
std::vector<double> analyticVisibility(const RenderResult& g, const Light& light) {
    std::vector<double> v(size_t{g.width} * g.height);
    for (size_t i = 0; i < v.size(); ++i) {
        const LightCone cone = coneTowards(light, at(g, i));
        const double alpha = cone.single ? 0.0 : std::acos(1.0 - cone.oneMinusCosAlpha);
        v[i] = analytic::coneVisibilityPastSphere(at(g, i), cone.axis, alpha, glm::dvec3(kCenter),
                                                  kRadius);
    }
    return v;
}

} // namespace

TEST(Analytic, CapIntersectionMatchesMonteCarlo) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double a1 = 0.3, a2 = 0.2, gamma = 0.35;
    const glm::dvec3 c2(std::sin(gamma), 0, std::cos(gamma)); // cap 1 is centred on +z
    int inside = 0, both = 0;
    for (int i = 0; i < 400000; ++i) { // uniform directions in cap 1
        const double z = 1.0 - u(rng) * (1.0 - std::cos(a1)), phi = 6.283185307179586 * u(rng);
        const double s = std::sqrt(1.0 - z * z);
        const glm::dvec3 d(s * std::cos(phi), s * std::sin(phi), z);
        ++inside;
        both += glm::dot(d, c2) >= std::cos(a2);
    }
    const double expected = analytic::capIntersection(a1, a2, gamma) / analytic::capArea(a1);
    EXPECT_NEAR(static_cast<double>(both) / inside, expected, 3e-3);
    EXPECT_DOUBLE_EQ(analytic::capIntersection(a1, a2, 0.6), 0.0);                      // disjoint
    EXPECT_NEAR(analytic::capIntersection(a1, a2, 0.05), analytic::capArea(a2), 1e-12); // nested
}

TEST(Sampling, ConeSamplesStayInsideTheConeAndCoverItUniformly) {
    Light light{.type = LightType::Directional,
                .direction = glm::normalize(glm::vec3(0.2f, -1, 0.1f)),
                .angularDiameter = 20.0f};
    const LightCone cone = coneTowards(light, {0, 0, 0});
    const double cosAlpha = 1.0 - cone.oneMinusCosAlpha;
    EXPECT_NEAR(std::acos(cosAlpha), glm::radians(10.0), 1e-9);
    double meanCos = 0;
    const uint32_t n = 4096;
    for (uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 d = sampleDirection(cone, hammersley(i, n, {0.3, 0.7}));
        EXPECT_GE(glm::dot(d, cone.axis), cosAlpha - 1e-12);
        meanCos += glm::dot(d, cone.axis) / n;
    }
    EXPECT_NEAR(meanCos, 1.0 - 0.5 * cone.oneMinusCosAlpha, 1e-5); // uniform in solid angle
    // A tiny sun keeps its exact size: no float cancellation in 1 - cos.
    light.angularDiameter = 0.01f;
    EXPECT_NEAR(coneTowards(light, {0, 0, 0}).oneMinusCosAlpha, 1.0 - std::cos(glm::radians(0.005)),
                1e-15);
}

TEST(Reference, HardShadowMatchesTheAnalyticOneOutsideAOnePixelBand) {
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f))};
    const Scene scene = sphereOverPlane(sun);
    const RenderResult g = planeGrid(0.6f, 0.4f, 3.0f);
    const ReferenceResult r = computeReference(scene, g, {.samples = 64});
    const std::vector<double> truth = analyticVisibility(g, sun);
    size_t compared = 0, shadowed = 0;
    for (uint32_t y = 1; y + 1 < kGrid; ++y)
        for (uint32_t x = 1; x + 1 < kGrid; ++x) {
            const size_t i = size_t{y} * kGrid + x;
            bool band = false; // a neighbour of another class: the 1-pixel boundary band
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    band |= truth[i + dy * int(kGrid) + dx] != truth[i];
            if (band)
                continue;
            ++compared;
            shadowed += truth[i] == 0.0;
            ASSERT_EQ(r.visibility[0][i], static_cast<float>(truth[i]))
                << "pixel " << x << "," << y;
        }
    EXPECT_GT(shadowed, kGrid * kGrid / 8) << "the shadow must be in view";
    EXPECT_GT(compared - shadowed, kGrid * kGrid / 8);
    EXPECT_EQ(r.rays, uint64_t{kGrid} * kGrid) << "radius 0: one exact ray per pixel";
}

namespace {

// Mean reference visibility over 8x8 patches lying wholly in the penumbra, against the mean of
// the analytic solid-angle overlap: the worst patch difference.
double worstPenumbraPatchError(const Light& light, float cx, float cz, float extent,
                               size_t* patches) {
    const Scene scene = sphereOverPlane(light);
    const RenderResult g = planeGrid(cx, cz, extent);
    const ReferenceResult r = computeReference(scene, g, {.samples = 256});
    const std::vector<double> truth = analyticVisibility(g, light);
    double worst = 0.0;
    *patches = 0;
    for (uint32_t py = 0; py < kGrid; py += 8)
        for (uint32_t px = 0; px < kGrid; px += 8) {
            double sumRef = 0, sumTruth = 0;
            bool penumbra = true;
            for (uint32_t y = py; y < py + 8; ++y)
                for (uint32_t x = px; x < px + 8; ++x) {
                    const size_t i = size_t{y} * kGrid + x;
                    penumbra &= truth[i] > 0.02 && truth[i] < 0.98;
                    sumRef += r.visibility[0][i], sumTruth += truth[i];
                }
            if (!penumbra)
                continue;
            ++*patches;
            worst = std::max(worst, std::abs(sumRef - sumTruth) / 64.0);
        }
    return worst;
}

} // namespace

TEST(Reference, SphereLightPenumbraMatchesTheSolidAngleOverlap) {
    const Light lamp{.type = LightType::Point,
                     .position = {1.0f, 7.0f, 0.5f},
                     .radius = 1.2f,
                     .castsShadow = true};
    Light spot = lamp;
    spot.type = LightType::Spot; // point lights have no visibility image yet; spots do
    spot.direction = {0, -1, 0};
    size_t patches = 0;
    const double worst = worstPenumbraPatchError(spot, -0.4f, -0.2f, 4.5f, &patches);
    std::printf("sphere light: %zu penumbra patches, worst mean error %.4f\n", patches, worst);
    EXPECT_GT(patches, 20u);
    EXPECT_LT(worst, 0.004); // measured: 0.0017
}

TEST(Reference, DirectionalLightWithAnAngularDiameterMatchesTheOverlap) {
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f)),
                    .angularDiameter = 12.0f};
    size_t patches = 0;
    const double worst = worstPenumbraPatchError(sun, 0.6f, 0.4f, 3.5f, &patches);
    std::printf("sun cone: %zu penumbra patches, worst mean error %.4f\n", patches, worst);
    EXPECT_GT(patches, 20u);
    EXPECT_LT(worst, 0.01);
}

TEST(Reference, DropsTheSameInvalidTrianglesAsTheRasterizer) {
    const Light sun{.type = LightType::Directional, .direction = {0, -1, 0}};
    Scene clean = sphereOverPlane(sun);
    Scene hostile = clean;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const uint32_t base = static_cast<uint32_t>(hostile.vertices.size());
    auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        for (const glm::vec3& p : {a, b, c})
            hostile.vertices.push_back({p, {0, 1, 0}, 0});
    };
    add({0, 5, 0}, {nan, 5, 0}, {0, 5, 1});   // NaN vertex
    add({0, 5, 0}, {1e30f, 5, 0}, {0, 5, 1}); // past kMaxCoordinate
    add({0, 5, 0}, {1, 5, 0}, {2, 5, 0});     // no area
    hostile.indices.insert(hostile.indices.end(),
                           {base, base + 1, base + 2, base + 3, base + 4, base + 5, base + 6,
                            base + 7, base + 8, base, base + 1, 999999}); // index out of range
    Scene sanitized = hostile;
    EXPECT_EQ(dropInvalidTriangles(sanitized), 4u);
    EXPECT_EQ(sanitized.triangleCount(), clean.triangleCount());
    EXPECT_TRUE(std::isfinite(sanitized.bounds().max.x));

    const RenderResult g = planeGrid(0.0f, 0.0f, 4.0f);
    const ReferenceResult a = computeReference(clean, g, {.samples = 4});
    const ReferenceResult b = computeReference(hostile, g, {.samples = 4});
    EXPECT_EQ(b.triangles, clean.triangleCount());
    EXPECT_EQ(a.visibility, b.visibility);
}

TEST(Reference, EmbreeFailuresAreClearErrorsNotCrashes) {
    const Light sun{.type = LightType::Directional, .direction = {0, -1, 0}};
    const Scene scene = sphereOverPlane(sun);
    try {
        computeReference(scene, planeGrid(0, 0, 1), {.embreeConfig = "threads=abc"});
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("embree: ", 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find("threads=abc"), std::string::npos);
    }
}

TEST(Reference, SanitationKeepsTheLastValidValueAndDropsTheFirstInvalid) {
    // Each row: a triangle on the boundary of one rule (kept) and one just past it (dropped).
    auto dropped = [](std::vector<glm::vec3> positions, std::vector<uint32_t> indices) {
        Scene s;
        for (const glm::vec3& p : positions)
            s.vertices.push_back({p, {0, 1, 0}, 0});
        s.indices = std::move(indices);
        const size_t n = dropInvalidTriangles(s);
        EXPECT_EQ(s.triangleCount() + n, 1u);
        return n;
    };
    const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 0, 1), d(5, 5, 5);
    // Indices: the last vertex is index count - 1; the count itself is past the end.
    EXPECT_EQ(dropped({a, b, c, d}, {0, 1, 3}), 0u);
    EXPECT_EQ(dropped({a, b, c}, {0, 1, 3}), 1u);
    EXPECT_EQ(dropped({a, b, c}, {3, 1, 2}), 1u);
    EXPECT_EQ(dropped({a, b, c}, {0, 3, 2}), 1u);
    // Coordinates: kMaxCoordinate itself is usable, the next float is not.
    const float cap = kMaxCoordinate, past = std::nextafter(kMaxCoordinate, INFINITY);
    EXPECT_EQ(dropped({a, {cap, 0, 0}, {0, 0, cap}}, {0, 1, 2}), 0u);
    EXPECT_EQ(dropped({a, {past, 0, 0}, {0, 0, cap}}, {0, 1, 2}), 1u);
    EXPECT_EQ(dropped({a, {-cap, 0, 0}, {0, 0, -past}}, {0, 1, 2}), 1u);
    // Area: the thinnest sliver float can hold is a triangle; a straight line is not.
    EXPECT_EQ(dropped({a, b, {2, 0, 1e-30f}}, {0, 1, 2}), 0u);
    EXPECT_EQ(dropped({a, b, {2, 0, 0}}, {0, 1, 2}), 1u);
    // A trailing partial triangle counts as dropped.
    Scene s;
    s.vertices = {{a, {0, 1, 0}, 0}, {b, {0, 1, 0}, 0}, {c, {0, 1, 0}, 0}};
    s.indices = {0, 1, 2, 0};
    EXPECT_EQ(dropInvalidTriangles(s), 1u);
    EXPECT_EQ(s.triangleCount(), 1u);
}

TEST(Reference, ShadowRaysEndAtTheLightAndReceiversInsideItAreLit) {
    // A spherical light (radius 1) whose centre is half a radius above the ground, and a roof
    // over everything. The roof lies beyond the light: it must not shadow anything. Receivers
    // inside the light see all of it; those just outside see the part above their horizon (the
    // ground hides the rest), so they are partly lit.
    const Light lamp{.type = LightType::Spot,
                     .position = {0.0f, 0.5f, 0.0f},
                     .direction = {0, -1, 0},
                     .radius = 1.0f};
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("grey", glm::vec3(0.5f));
    mb.quad({-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, {-20, 0, -20}, m);
    scene.lights.push_back(lamp);
    Scene roofed = scene;
    MeshBuilder(roofed).quad({-9, 4, -9}, {9, 4, -9}, {9, 4, 9}, {-9, 4, 9}, m);
    const RenderResult g = planeGrid(0.0f, 0.0f, 5.0f);
    const ReferenceResult open = computeReference(scene, g, {.samples = 64});
    const ReferenceResult roof = computeReference(roofed, g, {.samples = 64});
    EXPECT_EQ(open.visibility, roof.visibility) << "a roof beyond the light shadows nothing";
    size_t inside = 0, near = 0;
    for (size_t i = 0; i < size_t{g.width} * g.height; ++i) {
        const glm::dvec3 p = at(g, i);
        const double d = glm::length(p - glm::dvec3(lamp.position)) / lamp.radius;
        const float v = open.visibility[0][i];
        if (d <= 0.999) {
            ++inside;
            EXPECT_EQ(v, 1.0f) << "inside the light at " << p.x << ", " << p.z;
        } else if (d > 1.001 && d <= 2.0) {
            ++near;
            EXPECT_GT(v, 0.0f) << "outside the light at " << p.x << ", " << p.z;
            EXPECT_LT(v, 1.0f) << "outside the light at " << p.x << ", " << p.z;
        }
    }
    std::printf("receivers inside the light: %zu, within two radii: %zu\n", inside, near);
    EXPECT_GT(inside, 100u);
    EXPECT_GT(near, 100u);
}

// One exact ray for a light without a size, and for a receiver inside a sphere light (fully lit);
// a cone of rays otherwise, its angle from the sphere's radius.
TEST(Sampling, APointLightOrAReceiverInsideTheLightGetsOneRay) {
    const Light bulb{.type = LightType::Point, .position = {0, 2, 0}, .radius = 0.5f};
    const Light point{.type = LightType::Point, .position = {0, 2, 0}};
    EXPECT_TRUE(coneTowards(point, {0, 0, 0}).single);
    EXPECT_FALSE(coneTowards(bulb, {0, 0, 0}).single);
    EXPECT_NEAR(coneTowards(bulb, {0, 0, 0}).oneMinusCosAlpha, 1.0 - std::sqrt(1.0 - 0.0625),
                1e-12);
    const LightCone within = coneTowards(bulb, {0, 2.3, 0});
    EXPECT_TRUE(within.inside);
    EXPECT_TRUE(within.single);
    EXPECT_FALSE(std::isnan(within.oneMinusCosAlpha));
}

TEST(Sampling, HammersleyPointsAreAZeroMNetInBaseTwo) {
    // For n = 2^m unshifted points, every box [a/2^k, (a+1)/2^k) x [b/2^(m-k), (b+1)/2^(m-k))
    // holds exactly one point, for every k: the property that makes the truth's penumbrae
    // converge fast and without bias.
    for (uint32_t m : {0u, 2u, 5u, 8u}) {
        const uint32_t n = 1u << m;
        std::vector<glm::dvec2> points;
        for (uint32_t i = 0; i < n; ++i)
            points.push_back(hammersley(i, n, glm::dvec2(0.0)));
        for (uint32_t k = 0; k <= m; ++k) {
            std::vector<int> count(n, 0);
            for (const glm::dvec2& p : points) {
                ASSERT_GE(p.x, 0.0);
                ASSERT_LT(p.x, 1.0);
                ASSERT_GE(p.y, 0.0);
                ASSERT_LT(p.y, 1.0);
                const auto a = static_cast<uint32_t>(p.x * double(1u << k));
                const auto b = static_cast<uint32_t>(p.y * double(1u << (m - k)));
                ++count[(a << (m - k)) | b];
            }
            for (uint32_t box = 0; box < n; ++box)
                ASSERT_EQ(count[box], 1) << "n " << n << ", split " << k << ", box " << box;
        }
    }
    // The first coordinate sits at the centres of its n strata: the set's mean is 1/2, so a
    // light's disc is sampled without a drift of half a stratum towards one side.
    for (uint32_t n : {1u, 7u, 256u}) {
        double sum = 0.0;
        for (uint32_t i = 0; i < n; ++i)
            sum += hammersley(i, n, glm::dvec2(0.0)).x;
        EXPECT_NEAR(sum / n, 0.5, 1e-12) << n;
    }
    // A shift moves every point by the same amount, modulo 1 (Cranley-Patterson rotation).
    const glm::dvec2 shift(0.3, 0.85);
    for (uint32_t i = 0; i < 16; ++i) {
        const glm::dvec2 expected = glm::fract(hammersley(i, 16, glm::dvec2(0.0)) + shift);
        EXPECT_NEAR(hammersley(i, 16, shift).x, expected.x, 1e-12);
        EXPECT_NEAR(hammersley(i, 16, shift).y, expected.y, 1e-12);
    }
}

// A G-buffer's positions carry the rasterizer's depth error, which differs between devices:
// on an H100 the ground's positions came out up to 3e-4 off, some under the surface. Under a
// sun 5 degrees above the horizon a shadow ray leaving a point just under the ground meets the
// ground again unless it first travels far enough to clear its error; the truth then showed
// false shadow wherever the error's sign was negative (60% of the shadowed pixels of
// builtin:grazing).
TEST(Reference, GrazingRaysFromPositionsJustUnderTheSurfaceDoNotHitIt) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("grey", glm::vec3(0.5f));
    mb.quad({-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, {-20, 0, -20}, m);
    for (float elevation : {5.0f, 1.0f}) {
        const float a = glm::radians(elevation);
        scene.lights = {Light{.type = LightType::Directional,
                              .direction = glm::vec3(std::cos(a), -std::sin(a), 0.0f)}};
        RenderResult g = planeGrid(0.0f, 0.0f, 30.0f);
        for (size_t i = 0; i < size_t{kGrid} * kGrid; ++i) { // a relative error of 5e-5 below
            const glm::vec3 p = glm::vec3(at(g, i));
            g.position[3 * i + 1] = -5e-5f * std::max({std::abs(p.x), std::abs(p.z), 1.0f});
        }
        const ReferenceResult r = computeReference(scene, g, {.samples = 1});
        size_t dark = 0;
        for (float v : r.visibility[0])
            dark += v < 1.0f;
        EXPECT_EQ(dark, 0u) << "sun " << elevation << " degrees up";
    }
}

// The same scene at a thousandth and a thousand times its size reads the same truth: the rays'
// start past their own surface scales with the scene, not with a fixed floor (an absolute 1e-4,
// 64 times that on a grazing ray, skipped a sphere of radius 0.001 where it rests on its plane).
TEST(Reference, ASceneReadsTheSameTruthAtEveryScale) {
    const auto truthAt = [](float s) {
        Scene scene;
        MeshBuilder mb(scene);
        const uint32_t m = mb.material("grey", glm::vec3(0.5f));
        mb.quad({-20 * s, 0, 20 * s}, {20 * s, 0, 20 * s}, {20 * s, 0, -20 * s},
                {-20 * s, 0, -20 * s}, m);
        mb.sphere({0, s, 0}, s, m, 256, 128); // resting on the plane
        scene.lights = {Light{.type = LightType::Directional,
                              .direction = glm::normalize(glm::vec3(0.5f, -0.6f, 0.2f))}};
        RenderResult g = planeGrid(0.0f, 0.0f, 3.0f * s);
        return computeReference(scene, g, {.samples = 1}).visibility[0];
    };
    const std::vector<float> unit = truthAt(1.0f);
    size_t dark = 0;
    for (float v : unit)
        dark += v < 0.5f;
    EXPECT_GT(dark, size_t{kGrid} * kGrid / 20) << "a shadow to compare";
    for (float s : {1e-3f, 1e3f}) {
        const std::vector<float> scaled = truthAt(s);
        size_t differ = 0;
        for (size_t i = 0; i < unit.size(); ++i)
            differ += (unit[i] < 0.5f) != (scaled[i] < 0.5f);
        EXPECT_LE(differ, 2u) << "scale " << s; // a grid pixel on an edge, by float rounding
    }
}
