// bias.mode=adaptive's maths (shaders/include/bias.h: adaptiveBiasTerms, tapDepth,
// lightDepthGradient), which the visibility pass and the CPU reference share, against answers
// derived independently: a circle's departure from its tangent line measured along the light's
// rays, a projection's depth derivative by finite differences.
#include "core/light_space.h"
#include "core/projection.h"
#include "bias.h"

#include <gtest/gtest.h>

#include <cmath>

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

} // namespace
