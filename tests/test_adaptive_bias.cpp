// bias.mode=adaptive's maths (shaders/include/bias.h: adaptiveBiasTerms, tapDepth,
// lightDepthGradient), which the visibility pass and the CPU reference share, against answers
// derived independently: a circle's departure from its tangent line measured along the light's
// rays, a projection's depth derivative by finite differences; the crease rule (creaseTests,
// creaseLimit) on planes built in (u, v, depth) and against rays to every point of a light.
#include "bias.h"
#include "core/light_space.h"
#include "core/projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace penumbra;

namespace {

constexpr float kFar = 1e30f;

TEST(AdaptiveBias, WithoutCurveATapIsTheReceiverPlaneDepth) {
    const glm::vec2 g(0.3f, -0.2f), range(-0.05f, 0.05f);
    for (glm::vec2 offset : {glm::vec2(0.0f), glm::vec2(0.01f, 0.02f), glm::vec2(-0.3f, 0.1f)})
        EXPECT_EQ(gpu::tapDepth(0.5f, g, offset, range, glm::vec2(0.0f)),
                  gpu::receiverDepthAt(0.5f, g, offset, range));
}

TEST(AdaptiveBias, ATapIsLiftedByTheSmallerOfItsCurveAndItsCap) {
    const glm::vec2 curve(4.0f, 0.1f); // the quadratic wins under |offset| = 0.025
    const float base = 0.5f;
    const glm::vec2 near(0.012f, 0.016f); // |offset| 0.02: lift 4 * 0.0004
    EXPECT_NEAR(gpu::tapDepth(base, glm::vec2(0.0f), near, {-1, 1}, curve), base - 0.0016f, 1e-7);
    const glm::vec2 far(0.03f, 0.04f); // |offset| 0.05: capped, 0.1 * 0.05
    EXPECT_NEAR(gpu::tapDepth(base, glm::vec2(0.0f), far, {-1, 1}, curve), base - 0.005f, 1e-7);
    // The plane's correction is clamped before the lift comes off.
    EXPECT_NEAR(gpu::tapDepth(base, glm::vec2(10.0f, 0.0f), near, {-0.05f, 0.05f}, curve),
                base + 0.05f - 0.0016f, 1e-6);
}

TEST(AdaptiveBias, AFlatReceiverIsLiftedByItsTexelFootprintAlongTheRay) {
    const float texel = 0.01f, size = 2048, perWorld = 0.05f;
    for (float cosine : {1.0f, 0.5f, 0.2f}) {
        const glm::vec4 t =
            gpu::adaptiveBiasTerms(texel, size, perWorld, cosine, 0.0f, 0.25f, 1.0f, 3.0f);
        EXPECT_NEAR(t.x, perWorld * 0.25f * texel / cosine, 1e-9) << cosine;
        EXPECT_EQ(t.y, 0.0f);                            // no curvature: no quadratic lift
        EXPECT_NEAR(t.z, perWorld * texel * size, 1e-6); // the 45-degree cap, per uv
        EXPECT_EQ(t.w, kFar);                            // a flat plane is trusted anywhere
    }
    // Edge-on receivers are held at cosine 0.05, not divided by zero.
    EXPECT_NEAR(gpu::adaptiveBiasTerms(texel, size, perWorld, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f).x,
                perWorld * texel / 0.05f, 1e-7);
}

// A circle of radius R lit straight down (rays along -y), the receiver at angle theta from the
// top: how far the circle lies below the receiver's tangent line, along the ray, at a horizontal
// distance s uphill or downhill. The quadratic lift must match it to second order, for
// every slope.
double circleDeparture(double R, double theta, double s) {
    const double x0 = R * std::sin(theta), y0 = R * std::cos(theta);
    const double slope = -std::tan(theta); // dy/dx of the upper half at x0
    const double x = x0 + s;
    return (y0 + slope * s) - std::sqrt(R * R - x * x);
}

TEST(AdaptiveBias, TheCurveLiftIsTheCirclesDepartureFromItsTangent) {
    const double R = 0.2; // curvature 5 per world unit
    const float texel = 0.001f, size = 1024, perWorld = 1.0f;
    const double worldPerUv = double(texel) * size;
    for (double theta : {0.0, 0.4, 0.8, 1.1}) {
        const glm::vec4 t = gpu::adaptiveBiasTerms(texel, size, perWorld, float(std::cos(theta)),
                                                   float(1.0 / R), 0.0f, 1.0f, 0.0f);
        for (double s : {0.002, -0.002, 0.004}) {
            const double lift = t.y * (s / worldPerUv) * (s / worldPerUv);
            const double departure = circleDeparture(R, theta, s);
            // Second order: the third-order term is about s / R * tan(theta) of it (times 2.3
            // at most here); a wrong power of the cosine is off by 1 / cos(1.1) = 2.2.
            const double third = 3.0 * std::abs(s) / R * std::tan(theta);
            EXPECT_NEAR(lift, departure, (0.01 + third) * departure) << theta << " " << s;
        }
    }
}

TEST(AdaptiveBias, ThePlanesReachIsWhereTheSurfaceHasTurnedOneRadian) {
    const float texel = 0.002f, size = 512, curvature = 4.0f, gradient = 0.7f;
    for (float cosine : {1.0f, 0.6f}) {
        const glm::vec4 t =
            gpu::adaptiveBiasTerms(texel, size, 1.0f, cosine, curvature, 0.0f, 1.0f, gradient);
        // One radian along the surface is 1 / curvature; across the rays, cosine of that; in
        // uv, over texel * size; the correction there is the plane's gradient times it.
        EXPECT_NEAR(t.w, gradient * (cosine / curvature) / (texel * size), 1e-5) << cosine;
    }
    // bias.curvature scales the measured curvature: 0 turns both curvature terms off.
    const glm::vec4 off =
        gpu::adaptiveBiasTerms(texel, size, 1.0f, 0.8f, curvature, 0.0f, 0.0f, gradient);
    EXPECT_EQ(off.y, 0.0f);
    EXPECT_EQ(off.w, kFar);
    const glm::vec4 twice =
        gpu::adaptiveBiasTerms(texel, size, 1.0f, 0.8f, curvature, 0.0f, 2.0f, gradient);
    const glm::vec4 once =
        gpu::adaptiveBiasTerms(texel, size, 1.0f, 0.8f, curvature, 0.0f, 1.0f, gradient);
    EXPECT_NEAR(twice.y, 2.0f * once.y, 1e-6f * once.y);
    EXPECT_NEAR(twice.w, 0.5f * once.w, 1e-6f * once.w);
}

TEST(AdaptiveBias, LightDepthGradientIsTheProjectionsDerivative) {
    const glm::mat4 view = lookAt({1.0f, 6.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    for (bool perspective : {false, true}) {
        const glm::mat4 proj = perspective
                                   ? perspectiveLight(glm::radians(60.0f), 1.0f, 0.5f, 20.0f)
                                   : orthographic(-4, 4, -4, 4, 0.5f, 20.0f);
        const glm::mat4 S = textureMatrix() * proj * view;
        const glm::vec3 p(0.3f, 0.2f, -0.4f);
        const glm::vec3 g = gpu::lightDepthGradient(S, p);
        const auto depth = [&](glm::vec3 q) {
            const glm::dvec4 s = glm::dmat4(S) * glm::dvec4(glm::dvec3(q), 1.0);
            return s.z / s.w;
        };
        for (int axis = 0; axis < 3; ++axis) {
            glm::vec3 h(0.0f);
            h[axis] = 1e-3f;
            EXPECT_NEAR(g[axis], (depth(p + h) - depth(p - h)) / 2e-3,
                        2e-3 * std::abs(g[axis]) + 1e-6)
                << (perspective ? "perspective " : "orthographic ") << axis;
        }
    }
}

// Four gathered depths (textureGather's order: x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j))
// of the plane depth(u, v) = at + g . (uv - centre), texels `texel` apart round `centre`.
glm::vec4 planeGather(float at, glm::vec2 g, float texel) {
    const float h = 0.5f * texel;
    return {at + g.x * -h + g.y * h, at + g.x * h + g.y * h, at + g.x * h + g.y * -h,
            at + g.x * -h + g.y * -h};
}

constexpr float kTexel = 1.0f / 1024.0f;
const glm::vec4 kBlocked(0.0f);

TEST(AdaptiveBias, CreaseAWallRisingFromTheReceiversFloorTestsLit) {
    // The floor: depth 0.5 at the receiver (uv 0), rising 0.2 per uv. A wall from the crease
    // at u = 0.01 comes towards the light at 3 per uv; a gather on it at u = 0.015.
    const float crease = 0.5f + 0.2f * 0.01f;
    const float u = 0.015f;
    const glm::vec4 wall = planeGather(crease - 3.0f * (u - 0.01f), {-3.0f, 0.0f}, kTexel);
    // Continued to the receiver the wall lies 0.03 + 0.002 behind it: lit, whatever the taps said.
    EXPECT_EQ(gpu::creaseTests(kBlocked, wall, {-u, 0.0f}, kTexel, 0.5f, 10.0f, 1e-3f),
              glm::vec4(1.0f));
    // The same wall 0.05 nearer the light everywhere passes in front of the receiver: kept.
    const glm::vec4 nearer = wall - 0.05f;
    EXPECT_EQ(gpu::creaseTests(kBlocked, nearer, {-u, 0.0f}, kTexel, 0.5f, 10.0f, 1e-3f), kBlocked);
    // A plate parallel to the map over the floor: its plane is in front.
    const glm::vec4 plate = planeGather(0.3f, {0.0f, 0.0f}, kTexel);
    EXPECT_EQ(
        gpu::creaseTests(glm::vec4(0, 1, 0, 1), plate, {-u, 0.0f}, kTexel, 0.5f, 10.0f, 1e-3f),
        glm::vec4(0, 1, 0, 1));
}

TEST(AdaptiveBias, CreaseAPlaneSteeperThanTheLimitOrWithinTheMarginKeepsItsTests) {
    const glm::vec2 offset(-0.01f, 0.004f);
    const glm::vec2 g(-3.0f, 4.0f); // |g| = 5
    // The plane's depth at the receiver: 0.6 + g . offset = 0.6 + 0.03 + 0.016 = 0.646.
    const glm::vec4 d = planeGather(0.6f, g, kTexel);
    EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.64f, 5.01f, 0.0f), glm::vec4(1.0f));
    EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.64f, 4.99f, 0.0f), kBlocked);
    EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.64f, 0.0f, 0.0f), kBlocked);
    // Behind by 0.006: a margin of 0.005 lets it count, 0.007 does not; at the receiver's own
    // depth plus the margin exactly it counts (at or behind).
    EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.64f, 10.0f, 0.005f), glm::vec4(1.0f));
    EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.64f, 10.0f, 0.007f), kBlocked);
    EXPECT_EQ(gpu::creaseTests(kBlocked, planeGather(0.5f, {0.0f, 0.0f}, kTexel), offset, kTexel,
                               0.25f, 10.0f, 0.25f),
              glm::vec4(1.0f));
}

TEST(AdaptiveBias, CreaseTheGathersGradientIsItsPlanesAlongEachAxis) {
    // Gradients along u alone and v alone, each on the limit's either side: a swapped or halved
    // axis in the fit would decide differently.
    for (const glm::vec2 g : {glm::vec2(6.0f, 0.0f), glm::vec2(0.0f, 6.0f), glm::vec2(-6.0f, 0.0f),
                              glm::vec2(0.0f, -6.0f)}) {
        const glm::vec4 d = planeGather(0.5f, g, kTexel);
        const glm::vec2 offset = 0.01f * glm::normalize(g); // where the plane lies deeper
        // At the receiver the plane lies at 0.56: behind 0.55, in front of 0.57.
        EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.55f, 6.01f, 0.0f),
                  glm::vec4(1.0f))
            << g.x << "," << g.y;
        EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.57f, 6.01f, 0.0f), kBlocked);
        EXPECT_EQ(gpu::creaseTests(kBlocked, d, offset, kTexel, 0.55f, 5.99f, 0.0f), kBlocked);
        EXPECT_EQ(gpu::creaseTests(kBlocked, d, -offset, kTexel, 0.5f, 6.01f, 0.0f), kBlocked);
    }
}

TEST(AdaptiveBias, CreaseTheLimitFollowsTheLightsSize) {
    EXPECT_FLOAT_EQ(gpu::creaseLimit(0.5f, 0.0f, 20.0f), 10.0f);  // a point: bias.crease alone
    EXPECT_FLOAT_EQ(gpu::creaseLimit(0.5f, 0.01f, 20.0f), 10.0f); // cot(0.57 deg) = 100 > 20
    EXPECT_NEAR(gpu::creaseLimit(0.5f, 0.5f, 20.0f), 0.5f * std::sqrt(3.0f), 1e-6f); // cot 30
    EXPECT_FLOAT_EQ(gpu::creaseLimit(0.5f, 1.0f, 20.0f), 0.0f); // inside the light
    EXPECT_FLOAT_EQ(gpu::creaseLimit(0.5f, 0.0f, 0.0f), 0.0f);  // bias.crease=0: off
    EXPECT_FLOAT_EQ(gpu::creaseLimit(0.0f, 0.0f, 20.0f), 0.0f); // bias.mode=fixed: off
}

// The rule's claim in world space, by rays: a plane at angle b to the ray from receiver P to the
// light's centre, passing behind P, with cot b within creaseLimit's slope (perUv 1), leaves every
// point of a spherical light of angular radius a on P's side: no segment from P to the light
// crosses it. Past the limit, with the plane through P, some point lies across.
TEST(AdaptiveBias, CreaseAPlaneWithinTheLimitHidesNoPointOfTheLight) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int trial = 0; trial < 200; ++trial) {
        const float distance = 1.0f + 20.0f * unit(rng);
        const float sine = 0.9f * unit(rng) * unit(rng);
        const float radius = sine * distance;
        const float slope = gpu::creaseLimit(1.0f, sine, 1e6f);
        const glm::vec3 centre(0.0f, 0.0f, distance); // P at the origin, the ray along +z
        const float turn = 6.2831853f * unit(rng);    // the plane's normal turned about the ray
        for (const float factor : {0.999f, 1.05f}) {
            const float b = std::atan(1.0f / (slope * factor));
            const float behind = factor < 1.0f ? 0.5f * unit(rng) : 0.0f;
            const glm::vec3 n(std::cos(b) * std::cos(turn), std::cos(b) * std::sin(turn),
                              std::sin(b));
            const glm::vec3 x(0.0f, 0.0f, -behind); // where the plane meets the ray
            int across = 0;
            for (int k = 0; k < 400; ++k) { // points on the light's sphere
                const float z = 2.0f * unit(rng) - 1.0f, phi = 6.2831853f * unit(rng);
                const float s = std::sqrt(1.0f - z * z);
                const glm::vec3 q =
                    centre + radius * glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
                across += glm::dot(n, q - x) < 0.0f;
            }
            if (factor < 1.0f)
                EXPECT_EQ(across, 0) << "trial " << trial << ": sin a " << sine;
            else
                EXPECT_GT(across, 0) << "trial " << trial << ": sin a " << sine;
        }
    }
}

} // namespace
