// The shimmer metric (src/report/shimmer.h) on synthetic frames: a ground plane seen by a
// camera that moves by fractions of a pixel, with visibility fixed to the world (no shimmer),
// fixed to the screen (shimmer), changing everywhere, following or defying a changing truth.
#include "core/projection.h"
#include "report/shimmer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

using namespace penumbra;

namespace {

constexpr uint32_t kSize = 96;
constexpr float kFov = 0.8f;

struct Frame {
    std::vector<float> visibility, truth, position;
    std::vector<uint8_t> mask;
    glm::mat4 viewProj;
    glm::vec3 eye;
    ShimmerFrame view() const {
        return {.width = kSize,
                .height = kSize,
                .visibility = visibility,
                .truth = truth,
                .position = position,
                .mask = mask,
                .viewProj = viewProj,
                .cameraPosition = eye,
                .pixelAngle = 2.0f * std::tan(0.5f * kFov) / static_cast<float>(kSize)};
    }
};

// The plane y = `height` seen from `eye` looking at `target`; v(world, pixel) per pixel.
Frame groundFrame(glm::vec3 eye, glm::vec3 target,
                  const std::function<float(glm::vec3, uint32_t, uint32_t)>& v,
                  float height = 0.0f) {
    Frame f{.eye = eye};
    f.viewProj = perspectiveCameraReverseZ(kFov, 1.0f, 0.1f, 100.0f) *
                 lookAt(eye, target, glm::vec3(0, 1, 0));
    const glm::mat4 inverse = glm::inverse(f.viewProj);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const glm::vec2 ndc =
                (glm::vec2(x, y) + 0.5f) / static_cast<float>(kSize) * 2.0f - 1.0f;
            glm::vec4 a = inverse * glm::vec4(ndc, 1.0f, 1.0f),
                      b = inverse * glm::vec4(ndc, 0.5f, 1.0f);
            const glm::vec3 p0 = glm::vec3(a) / a.w, p1 = glm::vec3(b) / b.w;
            const glm::vec3 dir = p1 - p0;
            const float t = (height - p0.y) / dir.y;
            const glm::vec3 p = p0 + t * dir;
            const bool hit = std::abs(dir.y) > 1e-9f && t > 0.0f;
            for (int c = 0; c < 3; ++c)
                f.position.push_back(hit ? p[c] : NAN);
            f.visibility.push_back(hit ? v(p, x, y) : NAN);
            f.mask.push_back(hit ? 1 : 0);
        }
    return f;
}

float worldPattern(glm::vec3 p, uint32_t, uint32_t) {
    return 0.5f + 0.4f * std::sin(0.7f * p.x) * std::cos(0.5f * p.z);
}

const glm::vec3 kEye{0.0f, 3.0f, 6.0f}, kTarget{0.0f, 0.0f, -2.0f};

double shimmerOf(const std::vector<Frame>& frames, uint64_t* matched = nullptr) {
    std::vector<ShimmerFrame> views;
    for (const Frame& f : frames)
        views.push_back(f.view());
    const ShimmerResult r = measureShimmer(views);
    if (matched)
        *matched = r.matched;
    return r.shimmer;
}

} // namespace

TEST(MetricsShimmer, VisibilityFixedToTheWorldDoesNotShimmerUnderADolly) {
    std::vector<Frame> frames;
    for (float t = 0; t < 4; ++t) // 0.013 units a frame: a fraction of a pixel here
        frames.push_back(groundFrame(kEye + glm::vec3(0, 0, -0.013f * t),
                                     kTarget + glm::vec3(0, 0, -0.013f * t), worldPattern));
    uint64_t matched = 0;
    const double s = shimmerOf(frames, &matched);
    EXPECT_GT(matched, 3u * kSize * kSize / 2);
    EXPECT_LT(s, 5e-4); // measured 2.6e-4: bilinear interpolation of the smooth pattern
}

TEST(MetricsShimmer, NoiseFixedToTheScreenShimmers) {
    // A checkerboard of 0 and 1 on the pixels, whichever surface they show.
    auto checker = [](glm::vec3, uint32_t x, uint32_t y) { return float((x + y) % 2); };
    std::vector<Frame> frames;
    for (float t = 0; t < 3; ++t)
        frames.push_back(groundFrame(kEye + glm::vec3(0.004f * t, 0, -0.011f * t),
                                     kTarget + glm::vec3(0.004f * t, 0, -0.011f * t), checker));
    // The reprojected point lands a fraction w of a pixel off its previous pixel's centre:
    // interpolating the previous checkerboard there gives v + w (1 - 2v), a change of w per
    // pixel, hundreds of times what the same motion costs a pattern fixed to the world.
    const double s = shimmerOf(frames);
    EXPECT_GT(s, 0.05); // measured 0.12
    EXPECT_LT(s, 0.5);
}

TEST(MetricsShimmer, AUniformChangeIsItsSizeAndATruthThatChangesAlikeCancelsIt) {
    Frame a = groundFrame(kEye, kTarget, worldPattern);
    Frame b = groundFrame(kEye, kTarget, [](glm::vec3 p, uint32_t x, uint32_t y) {
        return worldPattern(p, x, y) + 0.2f;
    });
    EXPECT_NEAR(shimmerOf({a, b}), 0.2, 1e-5);
    // A moving light: the truth changes by the same 0.2 -> no shimmer; by nothing -> 0.2.
    a.truth = a.visibility;
    b.truth = b.visibility;
    EXPECT_NEAR(shimmerOf({a, b}), 0.0, 1e-5);
    b.truth = a.visibility;
    EXPECT_NEAR(shimmerOf({a, b}), 0.2, 1e-5);
}

TEST(MetricsShimmer, OnlyTheSameCountedSurfaceIsCompared) {
    const Frame a = groundFrame(kEye, kTarget, worldPattern);
    // The next frame sees a plane 0.05 higher: within a pixel on screen, another surface.
    const Frame raised = groundFrame(kEye, kTarget, worldPattern, 0.05f);
    uint64_t matched = 0;
    shimmerOf({a, raised}, &matched);
    EXPECT_EQ(matched, 0u);
    // Pixels the light does not reach are neither compared nor compared with.
    Frame masked = a;
    std::fill(masked.mask.begin(), masked.mask.end(), 0);
    shimmerOf({a, masked}, &matched);
    EXPECT_EQ(matched, 0u);
    shimmerOf({masked, a}, &matched);
    EXPECT_EQ(matched, 0u);
    // Unmoved and unchanged: every interior pixel matches, with no change.
    EXPECT_LT(shimmerOf({a, a}, &matched), 2e-5); // float round-off of the reprojection
    EXPECT_GT(matched, kSize * kSize / 2);
}
