// Cascaded shadow maps on the CPU: the practical split scheme, every slice inside its cascade's
// window, stabilisation (whole-texel snapping, a size that ignores the camera's turn), kernel
// scales and blend bands.
#include "core/cascades.h"
#include "core/projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace penumbra;

namespace {

const Bounds kField{.min = {-400, 0, -400}, .max = {400, 30, 400}};
const Light kSun{.type = LightType::Directional,
                 .direction = glm::normalize(glm::vec3(0.55f, -0.45f, -0.35f))};

Camera camera(glm::vec3 position, float yawDegrees) {
    const float yaw = glm::radians(yawDegrees);
    return {.position = position,
            .target = position + glm::vec3(std::sin(yaw), -0.12f, -std::cos(yaw)),
            .yfov = 0.9f,
            .znear = 0.1f,
            .zfar = 1000.0f};
}

glm::vec3 toShadow(const LightProjection& p, const glm::vec3& world) {
    const glm::vec4 s = textureMatrix() * p.viewProj * glm::vec4(world, 1.0f);
    return glm::vec3(s) / s.w;
}

} // namespace

TEST(Cascades, SplitsRunFromUniformToLogarithmic) {
    const float n = 0.5f, f = 500.0f;
    const auto uniform = cascadeSplits(n, f, 4, 0.0f);
    const auto logarithmic = cascadeSplits(n, f, 4, 1.0f);
    const auto practical = cascadeSplits(n, f, 4, 0.25f);
    ASSERT_EQ(uniform.size(), 5u);
    for (int i = 0; i <= 4; ++i) {
        const float s = static_cast<float>(i) / 4.0f;
        EXPECT_NEAR(uniform[i], n + (f - n) * s, 1e-3f);
        EXPECT_NEAR(logarithmic[i], n * std::pow(f / n, s), 1e-3f * logarithmic[i]);
        EXPECT_NEAR(practical[i], 0.25f * logarithmic[i] + 0.75f * uniform[i], 1e-3f);
    }
    EXPECT_EQ(practical.front(), n);
    EXPECT_EQ(practical.back(), f);
    EXPECT_EQ(cascadeSplits(n, f, 1, 0.9f), (std::vector<float>{n, f}));
}

TEST(Cascades, DepthRangeIsTheSceneSeenAlongTheViewAxis) {
    const Camera c = camera({0, 1.7f, 0}, 0.0f);
    const glm::vec2 range = cameraDepthRange(c, kField);
    EXPECT_FLOAT_EQ(range.x, 0.1f); // the camera stands inside the scene: its near plane
    const glm::vec3 forward = glm::normalize(c.target - c.position);
    // The farthest corner: far along the view axis, low (the camera looks slightly down).
    EXPECT_NEAR(range.y, glm::dot(glm::vec3(400, 0, -400) - c.position, forward), 1e-2f);
    Camera shortSighted = c;
    shortSighted.zfar = 50.0f;
    EXPECT_FLOAT_EQ(cameraDepthRange(shortSighted, kField).y, 50.0f);
    // Stabilised: the scene's sphere (centre (0, 15, 0), radius 566.0), rounded out to quarter
    // powers of two, whatever the camera's direction.
    const glm::vec2 stable = stableDepthRange(c, kField);
    const float radius = 0.5f * glm::length(glm::vec3(800, 30, 800));
    const float reach = glm::length(glm::vec3(0, 15, 0) - c.position) + radius;
    EXPECT_FLOAT_EQ(stable.x, 0.1f);
    EXPECT_GE(stable.y, reach);
    EXPECT_LT(stable.y, reach * std::pow(2.0f, 0.25f));
    EXPECT_FLOAT_EQ(std::fmod(4.0f * std::log2(stable.y), 1.0f), 0.0f);
    EXPECT_EQ(stableDepthRange(camera({0, 1.7f, 0}, 70.0f), kField), stable);
    // From outside the scene, its near side.
    const Camera away = {.position = {0, 0, 2000}, .target = {0, 0, 0}, .zfar = 1e5f};
    const glm::vec2 outside = stableDepthRange(away, kField);
    const float nearSide = glm::length(glm::vec3(0, -15, 2000)) - radius;
    EXPECT_LE(outside.x, nearSide);
    EXPECT_GT(outside.x, nearSide / std::pow(2.0f, 0.25f));
}

TEST(Cascades, EverySliceLiesInsideItsCascadeAwayFromTheGuardBand) {
    for (bool stabilize : {true, false}) {
        const Camera c = camera({3, 1.7f, -2}, 20.0f);
        const uint32_t size = 512, guard = 9;
        const auto cascades =
            fitCascades(kSun, kField, c, 1.5f, size,
                        {.count = 4, .lambda = 0.9f, .blend = 0.2f, .stabilize = stabilize}, guard);
        ASSERT_EQ(cascades.size(), 4u);
        const glm::vec3 forward = glm::normalize(c.target - c.position);
        const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
        const glm::vec3 up = glm::cross(right, forward);
        const float tanY = std::tan(0.5f * c.yfov), tanX = 1.5f * tanY;
        const float inner = static_cast<float>(guard) / static_cast<float>(size);
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> unit(-1.0f, 1.0f), share(0.0f, 1.0f);
        for (size_t i = 0; i < cascades.size(); ++i) {
            const LightProjection& p = cascades[i];
            // Slices chain: each starts where the previous one starts blending into it, the last
            // csm.blend of the previous one's own split.
            if (i > 0) {
                const LightProjection& previous = cascades[i - 1];
                const float previousSplit = i > 1 ? cascades[i - 2].splitFar : previous.splitNear;
                EXPECT_FLOAT_EQ(p.splitNear, previous.blendStart);
                EXPECT_NEAR(previous.splitFar - previous.blendStart,
                            0.2f * (previous.splitFar - previousSplit), 1e-3f * previous.splitFar);
                EXPECT_LT(p.kernelScale, previous.kernelScale);
            }
            EXPECT_NEAR(p.kernelScale, cascades[0].texelWorldSize / p.texelWorldSize, 1e-6f);
            for (int k = 0; k < 2000; ++k) {
                const float d = p.splitNear + (p.splitFar - p.splitNear) * share(rng);
                const glm::vec3 world = c.position + forward * d + right * (unit(rng) * tanX * d) +
                                        up * (unit(rng) * tanY * d);
                const glm::vec3 s = toShadow(p, world);
                EXPECT_GE(std::min(s.x, s.y), inner - 1e-4f) << "cascade " << i;
                EXPECT_LE(std::max(s.x, s.y), 1.0f - inner + 1e-4f) << "cascade " << i;
            }
            // Every caster of the scene lies in the depth range.
            for (int k = 0; k < 8; ++k) {
                const glm::vec3 corner{k & 1 ? 400 : -400, k & 2 ? 30 : 0, k & 4 ? 400 : -400};
                const float depth = toShadow(p, corner).z;
                EXPECT_GE(depth, 0.0f);
                EXPECT_LE(depth, 1.0f);
            }
        }
        EXPECT_FLOAT_EQ(cascades.back().blendStart, cascades.back().splitFar) << "no next one";
    }
}

TEST(Cascades, StabilizedCascadesKeepTheirTexelGridAsTheCameraMovesAndTurns) {
    const CascadeSettings settings{.count = 4, .lambda = 0.9f, .blend = 0.1f, .stabilize = true};
    const auto before =
        fitCascades(kSun, kField, camera({0, 1.7f, 0}, 0.0f), 1.0f, 1024, settings, 6);
    const auto moved =
        fitCascades(kSun, kField, camera({0.013f, 1.7f, -0.021f}, 0.0f), 1.0f, 1024, settings, 6);
    const auto turned =
        fitCascades(kSun, kField, camera({0, 1.7f, 0}, 17.0f), 1.0f, 1024, settings, 6);
    for (size_t i = 0; i < before.size(); ++i) {
        const float texel = before[i].texelWorldSize;
        // The window's size ignores the turn, and its corner sits on the texel grid.
        EXPECT_NEAR(turned[i].texelWorldSize, texel, 1e-4f * texel) << "cascade " << i;
        EXPECT_NEAR(moved[i].texelWorldSize, texel, 1e-4f * texel) << "cascade " << i;
        for (const auto* p : {&before[i], &moved[i], &turned[i]}) {
            const float x = p->window.x / texel, y = p->window.z / texel;
            EXPECT_NEAR(x, std::round(x), 2e-3f) << "cascade " << i;
            EXPECT_NEAR(y, std::round(y), 2e-3f) << "cascade " << i;
        }
        // A world point lands on the same sub-texel position: the grid did not slide.
        const glm::vec3 point(1.234f, 0.0f, -3.0f * static_cast<float>(i + 1));
        const glm::vec2 a = glm::vec2(toShadow(before[i], point)) * 1024.0f;
        const glm::vec2 b = glm::vec2(toShadow(moved[i], point)) * 1024.0f;
        EXPECT_NEAR(glm::fract(a.x), glm::fract(b.x), 2e-3f) << "cascade " << i;
        EXPECT_NEAR(glm::fract(a.y), glm::fract(b.y), 2e-3f) << "cascade " << i;
    }
    // The window is the smallest sphere around the slice (plus the guard band): found here by a
    // ternary search along the view axis over the farthest slice corner.
    const Camera c = camera({0, 1.7f, 0}, 0.0f);
    const float tanY = std::tan(0.5f * c.yfov), corner = std::sqrt(2.0f) * tanY; // aspect 1
    for (const LightProjection& p : before) {
        const float a = p.splitNear, b = p.splitFar;
        auto reach = [&](float t) {
            return std::max(std::hypot(t - a, a * corner), std::hypot(b - t, b * corner));
        };
        float lo = a, hi = b;
        for (int k = 0; k < 200; ++k) {
            const float m1 = lo + (hi - lo) / 3.0f, m2 = hi - (hi - lo) / 3.0f;
            if (reach(m1) < reach(m2))
                hi = m2;
            else
                lo = m1;
        }
        const float radius = reach(0.5f * (lo + hi));
        const float half = 0.5f * (p.window.y - p.window.x) * (1024.0f - 12.0f) / 1024.0f;
        EXPECT_NEAR(half, radius, 1e-4f * radius) << "cascade " << p.splitNear;
    }
    // Without stabilisation the fit follows the slice: a turn changes the texel size.
    CascadeSettings tight = settings;
    tight.stabilize = false;
    const auto a = fitCascades(kSun, kField, camera({0, 1.7f, 0}, 0.0f), 1.0f, 1024, tight, 6);
    const auto b = fitCascades(kSun, kField, camera({0, 1.7f, 0}, 17.0f), 1.0f, 1024, tight, 6);
    EXPECT_GT(std::abs(a[1].texelWorldSize - b[1].texelWorldSize), 1e-3f * a[1].texelWorldSize);
    // And it is tighter: smaller texels than the bounding sphere's.
    EXPECT_LT(a[0].texelWorldSize, before[0].texelWorldSize);
}
