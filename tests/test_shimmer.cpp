// The shimmer metric (src/report/shimmer.h): the mean change per counted pixel, less the truth's
// own change for a moving light.
#include "report/shimmer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace penumbra;

TEST(MetricsShimmer, MeanChangeOverPixelsCountedInBothFrames) {
    const std::vector<float> v = {1.0f, 0.5f, 0.0f, 1.0f, NAN, 0.2f};
    const std::vector<float> before = {1.0f, 0.3f, 0.6f, 0.0f, 1.0f, NAN};
    const std::vector<uint8_t> mask = {1, 1, 1, 0, 1, 1}, previousMask = {1, 1, 1, 1, 1, 1};
    // Counted: pixels 0, 1, 2 (3 is not reached now, 4 and 5 are background in one frame).
    const ShimmerPair pair{
        .visibility = v, .previous = before, .mask = mask, .previousMask = previousMask};
    const ShimmerResult r = measureShimmer(std::span(&pair, 1));
    EXPECT_EQ(r.pixels, 3u);
    EXPECT_NEAR(r.shimmer, (0.0 + 0.2 + 0.6) / 3.0, 1e-6);
    // The light no longer reaching a pixel drops it too.
    const std::vector<uint8_t> gone = {0, 1, 1, 1, 1, 1};
    const ShimmerPair dropped{
        .visibility = v, .previous = before, .mask = mask, .previousMask = gone};
    EXPECT_EQ(measureShimmer(std::span(&dropped, 1)).pixels, 2u);
}

TEST(MetricsShimmer, ATruthThatChangesAlikeCancelsAndOneThatDoesNotCounts) {
    const std::vector<float> before = {0.2f, 0.7f, 1.0f}, after = {0.4f, 0.5f, 1.0f};
    const std::vector<uint8_t> all = {1, 1, 1};
    const ShimmerPair followsTruth{.visibility = after,
                                   .previous = before,
                                   .truth = after,
                                   .previousTruth = before,
                                   .mask = all,
                                   .previousMask = all};
    EXPECT_NEAR(measureShimmer(std::span(&followsTruth, 1)).shimmer, 0.0, 1e-7);
    // The truth stood still: the whole change is shimmer; it moved the other way: twice as much.
    const ShimmerPair still{.visibility = after,
                            .previous = before,
                            .truth = before,
                            .previousTruth = before,
                            .mask = all,
                            .previousMask = all};
    EXPECT_NEAR(measureShimmer(std::span(&still, 1)).shimmer, (0.2 + 0.2) / 3.0, 1e-6);
    const ShimmerPair opposite{.visibility = after,
                               .previous = before,
                               .truth = before,
                               .previousTruth = after,
                               .mask = all,
                               .previousMask = all};
    EXPECT_NEAR(measureShimmer(std::span(&opposite, 1)).shimmer, (0.4 + 0.4) / 3.0, 1e-6);
}

TEST(MetricsShimmer, PairsPoolTheirPixels) {
    const std::vector<float> a = {0.0f, 0.0f}, b = {1.0f, 1.0f}, c = {0.0f};
    const std::vector<uint8_t> two = {1, 1}, one = {1};
    const ShimmerPair pairs[] = {
        {.visibility = a, .previous = b, .mask = two, .previousMask = two},
        {.visibility = c, .previous = c, .mask = one, .previousMask = one}};
    const ShimmerResult r = measureShimmer(pairs);
    EXPECT_EQ(r.pixels, 3u);
    EXPECT_NEAR(r.shimmer, 2.0 / 3.0, 1e-7);
    EXPECT_EQ(measureShimmer({}).shimmer, 0.0);
}

#include "report/camera_path.h"

#include <glm/gtc/matrix_transform.hpp>

TEST(MetricsShimmer, PathsMoveTheCameraOrTheSunByTheirStep) {
    const Camera camera{.position = {0, 2, 8}, .target = {1, 0, -2}};
    const std::vector<Light> lights = {
        {.type = LightType::Directional, .direction = glm::normalize(glm::vec3(0.3f, -1, 0.2f))},
        {.type = LightType::Spot, .position = {1, 5, 1}}};
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    const auto dolly = pathFrames(CameraPath::Dolly, camera, lights, 3, 0.02f);
    ASSERT_EQ(dolly.size(), 3u);
    for (size_t t = 0; t < 3; ++t) {
        const auto k = static_cast<float>(t);
        const glm::vec3 moved = dolly[t].camera.position - camera.position;
        EXPECT_NEAR(glm::length(moved - forward * (0.02f * k)), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(dolly[t].camera.target - camera.target - moved), 0.0f, 1e-5f);
    }
    // Angles in double from atan2: acos of a float near 1 has no digits left at 0.05 degrees.
    auto degreesBetween = [](glm::vec3 a, glm::vec3 b) {
        const glm::dvec3 x(a), y(b);
        return glm::degrees(std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y)));
    };
    const auto orbit = pathFrames(CameraPath::Orbit, camera, lights, 3, 0.02f);
    const glm::vec3 from = camera.position - camera.target;
    for (size_t t = 0; t < 3; ++t) {
        const double k = static_cast<double>(t);
        const glm::vec3 to = orbit[t].camera.position - camera.target;
        EXPECT_NEAR(glm::length(to), glm::length(from), 1e-4f);
        EXPECT_NEAR(to.y, from.y, 1e-5f); // about the vertical axis
        EXPECT_NEAR(degreesBetween(glm::vec3(to.x, 0, to.z), glm::vec3(from.x, 0, from.z)),
                    kOrbitDegreesPerFrame * k, 1e-4);
        EXPECT_EQ(orbit[t].camera.target, camera.target);
    }
    const auto sun = pathFrames(CameraPath::Sun, camera, lights, 3, 0.02f);
    const glm::vec3 d = lights[0].direction;
    for (size_t t = 0; t < 3; ++t) {
        const double k = static_cast<double>(t);
        const glm::vec3 turned = sun[t].lights[0].direction;
        EXPECT_NEAR(turned.y, d.y, 1e-6f);
        EXPECT_NEAR(degreesBetween(glm::vec3(turned.x, 0, turned.z), glm::vec3(d.x, 0, d.z)),
                    kSunDegreesPerFrame * k, 1e-4);
        EXPECT_EQ(sun[t].lights[1].direction, lights[1].direction) << "only suns turn";
        EXPECT_EQ(sun[t].camera.position, camera.position);
    }
    CameraPath path{};
    EXPECT_TRUE(cameraPathFromName("orbit", path));
    EXPECT_EQ(path, CameraPath::Orbit);
    EXPECT_FALSE(cameraPathFromName("spiral", path));
}

TEST(MetricsFlicker, ChangeOfTheErrorWhereTheTruthHeldStill) {
    // Pixel 0: truth still, the error flips from +0.1 to -0.1 (flicker 0.2). Pixel 1: truth
    // still, the error constant (0). Pixel 2: the truth moved by 0.5 (left out, however the
    // technique followed it). Pixel 3: the truth moved by 2e-6, past the threshold (left out);
    // pixel 4 by 1e-7, within it (counted: an error change of 0.3 - 1e-7).
    const std::vector<float> truthBefore = {0.5f, 1.0f, 0.0f, 0.25f, 0.75f};
    const std::vector<float> truthAfter = {0.5f, 1.0f, 0.5f, 0.250002f, 0.7500001f};
    const std::vector<float> before = {0.6f, 0.9f, 0.0f, 0.25f, 0.75f};
    const std::vector<float> after = {0.4f, 0.9f, 0.9f, 0.9f, 1.05f};
    const std::vector<uint8_t> all(5, 1);
    const ShimmerPair pair{.visibility = after,
                           .previous = before,
                           .truth = truthAfter,
                           .previousTruth = truthBefore,
                           .mask = all,
                           .previousMask = all};
    const ShimmerResult r = measureFlicker(std::span(&pair, 1));
    EXPECT_EQ(r.pixels, 3u);
    EXPECT_NEAR(r.shimmer, (0.2 + 0.0 + (0.3 - 1e-7)) / 3.0, 1e-6);
    // Shimmer with a truth counts every pixel, the moved ones too.
    EXPECT_EQ(measureShimmer(std::span(&pair, 1)).pixels, 5u);
    // Masks and background drop pixels as they do for shimmer.
    const std::vector<uint8_t> firstGone = {0, 1, 1, 1, 1};
    const ShimmerPair masked{.visibility = after,
                             .previous = before,
                             .truth = truthAfter,
                             .previousTruth = truthBefore,
                             .mask = all,
                             .previousMask = firstGone};
    EXPECT_EQ(measureFlicker(std::span(&masked, 1)).pixels, 2u);
    EXPECT_NEAR(measureFlicker(std::span(&masked, 1)).shimmer, (0.0 + (0.3 - 1e-7)) / 2.0, 1e-6);
}
