// Cascaded shadow maps on the CPU: the practical split scheme, every slice inside its cascade's
// window, stabilisation (whole-texel snapping, a size that ignores the camera's turn), kernel
// scales and blend bands.
#include "core/cascades.h"
#include "core/projection.h"
#include "scene/mesh_builder.h"

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
    // Stabilised: rounded outwards to quarter powers of two, so that a range that moves a little
    // gives the same splits.
    const glm::vec2 stable = stableDepthRange({3.1f, 610.0f}, c);
    EXPECT_FLOAT_EQ(stable.x, std::exp2(6.0f / 4.0f));  // 2.83 <= 3.1 < 3.36
    EXPECT_FLOAT_EQ(stable.y, std::exp2(38.0f / 4.0f)); // 588 < 610 <= 724
    EXPECT_EQ(stableDepthRange({3.3f, 700.0f}, c), stable);
    EXPECT_NE(stableDepthRange({3.4f, 610.0f}, c), stable);
    // Within the camera's own planes.
    EXPECT_FLOAT_EQ(stableDepthRange({0.05f, 900.0f}, c).x, 0.1f);
    EXPECT_FLOAT_EQ(stableDepthRange({0.5f, 900.0f}, c).y, 1000.0f);
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
                // Past the scene there is nothing to shadow (and a cascade may stop at the
                // scene's own box there); a tenth of the way in, the guard band must hold.
                if (std::abs(world.x) > 360 || std::abs(world.z) > 360 || world.y < 3 ||
                    world.y > 27)
                    continue;
                const glm::vec3 s = toShadow(p, world);
                EXPECT_GE(std::min(s.x, s.y), inner - 1e-4f) << "cascade " << i;
                EXPECT_LE(std::max(s.x, s.y), 1.0f - inner + 1e-4f) << "cascade " << i;
                // ... and every receiver's depth in the moment techniques' range, with room for
                // the normal offset (a guard band's width of texels) on either side.
                const float margin =
                    static_cast<float>(guard) * p.texelWorldSize / (p.farPlane - p.nearPlane);
                EXPECT_GE(s.z, p.receiverDepths.x + margin) << "cascade " << i;
                EXPECT_LE(s.z, p.receiverDepths.y - margin) << "cascade " << i;
            }
            // The range is the slice's, a small part of the scene's for the near cascades (the
            // moments' precision is spread over it): measured 0.020 of it for the first.
            const float part = p.receiverDepths.y - p.receiverDepths.x;
            EXPECT_GT(part, 0.0f);
            if (i == 0) {
                std::printf("stabilize %d: cascade 0's receivers span %.4f of its depth range\n",
                            stabilize, part);
                EXPECT_LT(part, 0.05f) << "cascade 0";
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
    // What the camera sees changes a little as it moves and turns (visibleDepthRange()).
    const auto before = fitCascades(kSun, kField, camera({0, 1.7f, 0}, 0.0f), 1.0f, 1024, settings,
                                    6, {14.0f, 560.0f});
    const auto moved = fitCascades(kSun, kField, camera({0.013f, 1.7f, -0.021f}, 0.0f), 1.0f, 1024,
                                   settings, 6, {13.9f, 561.0f});
    const auto turned = fitCascades(kSun, kField, camera({0, 1.7f, 0}, 17.0f), 1.0f, 1024, settings,
                                    6, {14.2f, 548.0f});
    for (size_t i = 0; i < before.size(); ++i) {
        const float texel = before[i].texelWorldSize;
        // The window's size ignores the turn, and its corner sits on the texel grid.
        EXPECT_NEAR(turned[i].texelWorldSize, texel, 1e-4f * texel) << "cascade " << i;
        EXPECT_NEAR(moved[i].texelWorldSize, texel, 1e-4f * texel) << "cascade " << i;
        for (const auto* p : {&before[i], &moved[i], &turned[i]}) {
            // An axis along which the cascade outgrew the scene keeps the scene's fixed extent;
            // every other one sits on the grid.
            const bool fixedX = p->window.y - p->window.x < 0.999f * texel * 1024.0f;
            const bool fixedY = p->window.w - p->window.z < 0.999f * texel * 1024.0f;
            EXPECT_FALSE(fixedX && fixedY) << "cascade " << i;
            const float x = p->window.x / texel, y = p->window.z / texel;
            if (!fixedX)
                EXPECT_NEAR(x, std::round(x), 2e-3f) << "cascade " << i;
            else
                EXPECT_EQ(p->window.x, before[i].window.x) << "cascade " << i;
            if (!fixedY)
                EXPECT_NEAR(y, std::round(y), 2e-3f) << "cascade " << i;
            else
                EXPECT_EQ(p->window.z, before[i].window.z) << "cascade " << i;
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
        if (p.window.w - p.window.z < 0.999f * (p.window.y - p.window.x))
            continue; // cut to the scene's extent along y (the last one here)
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
    const auto a = fitCascades(kSun, kField, camera({0, 1.7f, 0}, 0.0f), 1.0f, 1024, tight, 6,
                               {14.0f, 560.0f});
    const auto b = fitCascades(kSun, kField, camera({0, 1.7f, 0}, 17.0f), 1.0f, 1024, tight, 6,
                               {14.0f, 560.0f});
    EXPECT_GT(std::abs(a[1].texelWorldSize - b[1].texelWorldSize), 1e-3f * a[1].texelWorldSize);
    // And it is tighter: smaller texels than the bounding sphere's.
    EXPECT_LT(a[0].texelWorldSize, before[0].texelWorldSize);
}

// A band that follows the light's size holds the light's cone over the scene's depth once it has
// widened the window, with no texel to spare; never more than its cap, and the fixed texels
// beyond it.
TEST(Cascades, ALightsGuardBandHoldsItsConeWithNoTexelToSpare) {
    const float n = 1024.0f;
    for (float half : {0.5f, 7.0f, 120.0f})
        for (float depth : {1.0f, 40.0f, 900.0f})
            for (float size : {0.0f, 0.002f, 0.0175f, 0.2f}) {
                const GuardBand band(400u, size, 4u);
                const float g = band.cascadeTexels(half, depth, n);
                const float reach = depth * size;
                const auto holds = [&](float texels) {
                    // The widened window's texel, and the cone's reach in those texels.
                    return reach / (2.0f * half / (n - 2.0f * (texels + 4.0f))) <= texels + 1e-3f;
                };
                if (g >= 256.0f) { // a quarter of the map: the cap
                    EXPECT_EQ(g, 256.0f);
                    continue;
                }
                EXPECT_TRUE(holds(g - 4.0f)) << half << " " << depth << " " << size;
                if (g > 4.0f)
                    EXPECT_FALSE(holds(g - 5.0f)) << half << " " << depth << " " << size;
                else
                    EXPECT_EQ(reach, 0.0f);
            }
    EXPECT_EQ(GuardBand(20u, 0.1f, 4u).cascadeTexels(1.0f, 1000.0f, n), 20.0f); // capped
    EXPECT_EQ(GuardBand(20u).cascadeTexels(1.0f, 0.0f, n), 20.0f); // not following: the cap
    // Cascades fitted with it: finer texels under a small sun than with the widest band.
    const Camera c = camera({3, 1.7f, -2}, 20.0f);
    const CascadeSettings settings{.count = 4, .lambda = 0.9f, .blend = 0.1f};
    const auto widest = fitCascades(kSun, kField, c, 1.5f, 1024, settings, 260u);
    const auto small =
        fitCascades(kSun, kField, c, 1.5f, 1024, settings, GuardBand(260u, 0.0f, 4u));
    for (size_t i = 0; i < widest.size(); ++i) // the far ones may hold the whole scene
        EXPECT_LE(small[i].texelWorldSize, widest[i].texelWorldSize * 1.0001f) << i;
    EXPECT_LT(small[0].texelWorldSize, 0.6f * widest[0].texelWorldSize);
}

// The band a light's cone needs spans the scene's depth along the light, not where the scene
// lies: moving the scene and the camera together leaves every cascade's texel as it was, and a
// scene ten times as high (a third deeper along this sun) needs a wider band: coarser texels.
TEST(Cascades, ALightsGuardBandFollowsTheScenesDepthWhereverItLies) {
    const GuardBand band(260u, 0.005f, 4u); // a sun 0.6 degrees across
    const Bounds yard{.min = {-20, 0, -20}, .max = {20, 3, 20}};
    const glm::vec2 seen(0.5f, 60.0f); // what the camera sees: the same slices throughout
    for (bool stabilize : {true, false}) {
        const CascadeSettings settings{
            .count = 4, .lambda = 0.9f, .blend = 0.1f, .stabilize = stabilize};
        const Camera c = camera({3, 1.7f, -2}, 20.0f);
        const auto here = fitCascades(kSun, yard, c, 1.5f, 1024, settings, band, seen);
        for (const glm::vec3 by : {400.0f * kSun.direction, glm::vec3(-300, 120, 250)}) {
            Camera moved = c;
            moved.position += by, moved.target += by;
            const auto there = fitCascades(kSun, {.min = yard.min + by, .max = yard.max + by},
                                           moved, 1.5f, 1024, settings, band, seen);
            ASSERT_EQ(there.size(), here.size());
            for (size_t i = 0; i < here.size(); ++i)
                EXPECT_NEAR(there[i].texelWorldSize, here[i].texelWorldSize,
                            1e-3f * here[i].texelWorldSize)
                    << i << (stabilize ? " stabilized" : "");
        }
        const Bounds deeper{.min = yard.min, .max = {yard.max.x, 30.0f, yard.max.z}};
        const auto deep = fitCascades(kSun, deeper, c, 1.5f, 1024, settings, band, seen);
        EXPECT_GT(deep[0].texelWorldSize, 1.01f * here[0].texelWorldSize)
            << (stabilize ? "stabilized" : "");
    }
}

TEST(Cascades, NoCascadeIsCoarserThanOneMapOverTheScene) {
    // A small scene seen from close by: the far slices are wider than the whole scene.
    const Bounds small{.min = {-2, 0, -2}, .max = {2, 1, 2}};
    const Camera c{
        .position = {0, 1.5f, 2.5f}, .target = {0, 0.5f, 0}, .yfov = 0.75f, .znear = 0.1f};
    const LightProjection whole = fitDirectional(kSun, small, 1024);
    for (bool stabilize : {true, false}) {
        const auto cascades = fitCascades(
            kSun, small, c, 1.5f, 1024,
            {.count = 4, .lambda = 0.9f, .blend = 0.1f, .stabilize = stabilize}, 6, {1.2f, 5.5f});
        EXPECT_LT(cascades.front().texelWorldSize, 0.8f * whole.texelWorldSize);
        for (const LightProjection& p : cascades)
            EXPECT_LE(p.texelWorldSize, whole.texelWorldSize * 1.001f) << p.splitNear;
        // The last one holds the scene's box exactly, along both axes (the one map's window).
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 corner{k & 1 ? 2 : -2, k & 2 ? 1 : 0, k & 4 ? 2 : -2};
            const glm::vec3 a = toShadow(cascades.back(), corner), b = toShadow(whole, corner);
            EXPECT_NEAR(a.x, b.x, 1e-3f);
            EXPECT_NEAR(a.y, b.y, 1e-3f);
        }
        EXPECT_NEAR(cascades.back().texelWorldSize, whole.texelWorldSize,
                    1e-3f * whole.texelWorldSize);
    }
}

namespace {

Scene quads(std::initializer_list<std::array<glm::vec3, 4>> list) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t grey = mb.material("grey", glm::vec3(0.7f));
    for (const auto& q : list)
        mb.quad(q[0], q[1], q[2], q[3], grey);
    return s;
}

} // namespace

TEST(Cascades, VisibleDepthRangeIsWhatTheCameraSees) {
    const float aspect = 1.5f;
    const Camera level{.position = {0, 2, 0}, .target = {0, 2, -1}, .yfov = 0.9f, .znear = 0.1f};
    const std::array<glm::vec3, 4> ground{glm::vec3(-100, 0, -100), glm::vec3(100, 0, -100),
                                          glm::vec3(100, 0, 100), glm::vec3(-100, 0, 100)};
    // The ground first shows at the bottom edge of the view, and reaches its far side.
    const glm::vec2 range = visibleDepthRange(quads({ground}), level, aspect);
    EXPECT_NEAR(range.x, 2.0f / std::tan(0.45f), 1e-3f);
    EXPECT_NEAR(range.y, 100.0f, 1e-3f);
    // Behind the camera, beside the view (either side), above it, all nearer than the ground
    // shows: nothing seen, nothing changes.
    const std::array<glm::vec3, 4> behind{glm::vec3(-1, 1, 5), glm::vec3(1, 1, 5),
                                          glm::vec3(1, 3, 5), glm::vec3(-1, 3, 5)};
    const std::array<glm::vec3, 4> beside{glm::vec3(30, 1, -1.5f), glm::vec3(31, 1, -1.5f),
                                          glm::vec3(31, 3, -1.5f), glm::vec3(30, 3, -1.5f)};
    const std::array<glm::vec3, 4> otherSide{glm::vec3(-31, 1, -1.5f), glm::vec3(-30, 1, -1.5f),
                                             glm::vec3(-30, 3, -1.5f), glm::vec3(-31, 3, -1.5f)};
    const std::array<glm::vec3, 4> above{glm::vec3(-1, 9, -2), glm::vec3(1, 9, -2),
                                         glm::vec3(1, 9, -1), glm::vec3(-1, 9, -1)};
    EXPECT_EQ(visibleDepthRange(quads({ground, behind, beside, otherSide, above}), level, aspect),
              range);
    const glm::vec2 none =
        visibleDepthRange(quads({behind, beside, otherSide, above}), level, aspect);
    EXPECT_GT(none.x, none.y);
    // A wall through the camera's plane is cut at the near plane; one past zfar at zfar.
    const std::array<glm::vec3, 4> sideWall{glm::vec3(0.5f, 0, 5), glm::vec3(0.5f, 0, -7),
                                            glm::vec3(0.5f, 4, -7), glm::vec3(0.5f, 4, 5)};
    const glm::vec2 wall = visibleDepthRange(quads({sideWall}), level, aspect);
    EXPECT_NEAR(wall.x, 0.5f / (aspect * std::tan(0.45f)), 1e-3f); // where it enters the view
    EXPECT_NEAR(wall.y, 7.0f, 1e-4f);
    Camera shortSighted = level;
    shortSighted.zfar = 40.0f;
    EXPECT_NEAR(visibleDepthRange(quads({ground}), shortSighted, aspect).y, 40.0f, 1e-4f);
    // Orthographic, looking straight down from 10 units: the ground at one distance.
    const Camera down{.position = {3, 10, 0},
                      .target = {3, 0, 0},
                      .up = {0, 0, -1},
                      .orthographic = true,
                      .ymag = 2.0f,
                      .znear = 0.1f};
    const std::array<glm::vec3, 4> overhead{glm::vec3(2, 9, -1), glm::vec3(4, 9, -1),
                                            glm::vec3(4, 9, 1), glm::vec3(2, 9, 1)};
    const glm::vec2 flat = visibleDepthRange(quads({ground, above, overhead}), down, aspect);
    EXPECT_NEAR(flat.x, 1.0f, 1e-4f); // the quad overhead, at 9 units, seen from 10
    EXPECT_NEAR(flat.y, 10.0f, 1e-4f);
}
