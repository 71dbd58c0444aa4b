// The `temporal` layer's maths on the CPU (shaders/include/temporal.h, compiled as C++): the
// reset rule (a texel's spread over time pooled with the neighbourhood's), one pixel's step
// (afresh, the clamp, the blend and its cap) by hand-worked cases, a history read between texels,
// and the history texel's packing.
#include "gbuffer_encoding.h"
#include "temporal.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra::gpu;

namespace {

TemporalParams params(uint32_t frames, uint32_t clampMode, float reset) {
    return {.frames = frames,
            .clampMode = clampMode,
            .gamma = 1.0f,
            .depthTolerance = 0.02f,
            .normalTolerance = 0.9f,
            .reset = reset};
}

// A neighbourhood of this frame whose range and spread allow anything and say nothing.
const vec4 kAnything(0.0f, 1.0f, 0.5f, 0.25f);

void expectNear(vec3 got, vec3 want) {
    EXPECT_NEAR(got.x, want.x, 1e-6f);
    EXPECT_NEAR(got.y, want.y, 1e-6f);
    EXPECT_EQ(got.z, want.z);
}

} // namespace

TEST(TemporalStep, NoHistoryIsThisFrameAlone) {
    expectNear(temporalStep(params(16, TEMPORAL_CLAMP_MINMAX, 3.0f), vec3(0.0f), 0.3f,
                            vec4(0.5f, 0.6f, 0.55f, 0.3f)),
               vec3(0.3f, 0.09f, 1.0f));
}

// A history of spread 0.1 (mean 0.5, mean square 0.26) over 8 frames, no noise around: a
// change of 0.25 is within 3 deviations (0.1 x sqrt(8 / 9) = 0.094: 0.28 and the floor), the
// history agrees and blends (1/9 of this frame); within 2 it does not. 0 keeps every history.
TEST(TemporalStep, TheResetRuleWeighsAChangeAgainstTheHistorysSpread) {
    const vec3 history(0.5f, 0.26f, 8.0f);
    EXPECT_TRUE(historyAgrees(params(16, TEMPORAL_CLAMP_NONE, 3.0f), history, 0.75f, 0.0f, 0.0f));
    EXPECT_TRUE(historyAgrees(params(16, TEMPORAL_CLAMP_NONE, 3.0f), history, 0.25f, 0.0f, 0.0f));
    EXPECT_FALSE(historyAgrees(params(16, TEMPORAL_CLAMP_NONE, 3.0f), history, 0.79f, 0.0f, 0.0f));
    EXPECT_FALSE(historyAgrees(params(16, TEMPORAL_CLAMP_NONE, 2.0f), history, 0.75f, 0.0f, 0.0f));
    EXPECT_FALSE(historyAgrees(params(16, TEMPORAL_CLAMP_NONE, 2.0f), history, 0.25f, 0.0f, 0.0f));
    EXPECT_TRUE(historyAgrees(params(16, TEMPORAL_CLAMP_NONE, 0.0f), vec3(1.0f, 1.0f, 8.0f), 0.0f,
                              0.0f, 0.0f));
    expectNear(temporalStep(params(16, TEMPORAL_CLAMP_NONE, 3.0f), history, 0.75f, kAnything),
               vec3(0.5f + 0.25f / 9.0f, 0.26f + (0.5625f - 0.26f) / 9.0f, 9.0f));
}

// A noise-free history (no spread, no noise) disagrees with any change beyond the floor (1/512).
TEST(TemporalStep, ANoiseFreeHistoryDisagreesWithAnyChangeBeyondTheFloor) {
    const TemporalParams p = params(16, TEMPORAL_CLAMP_NONE, 3.0f);
    const vec3 history(0.5f, 0.25f, 8.0f);
    EXPECT_TRUE(historyAgrees(p, history, 0.5f + 1.0f / 1024.0f, 0.0f, 0.0f));
    EXPECT_TRUE(historyAgrees(p, history, 0.5f - 1.0f / 1024.0f, 0.0f, 0.0f));
    EXPECT_FALSE(historyAgrees(p, history, 0.5f + 1.0f / 256.0f, 0.0f, 0.0f));
    EXPECT_FALSE(historyAgrees(p, history, 0.5f - 1.0f / 256.0f, 0.0f, 0.0f));
}

// The prior (the neighbourhood's variance for a texel, 0.09 here: 0.3) counts as one frame's:
// pooled with no spread over time it is 0.3 / sqrt(2) at one frame and 0.3 / 2 at three. A
// change of 0.5 is within 3 of the first (0.64), not of the second (0.45).
TEST(TemporalStep, AShortHistoryAlsoWeighsThePrior) {
    const TemporalParams p = params(16, TEMPORAL_CLAMP_NONE, 3.0f);
    EXPECT_TRUE(historyAgrees(p, vec3(0.5f, 0.25f, 1.0f), 1.0f, 0.09f, 0.0f));
    EXPECT_FALSE(historyAgrees(p, vec3(0.5f, 0.25f, 3.0f), 1.0f, 0.09f, 0.0f));
    // 0.2 over time and 0.3 around at one frame: sqrt((0.04 + 0.09) / 2) = 0.255, 3 of it 0.76.
    const vec3 spread(0.5f, 0.29f, 1.0f);
    EXPECT_TRUE(historyAgrees(p, spread, 0.5f + 0.75f, 0.09f, 0.0f));
    EXPECT_FALSE(historyAgrees(p, spread, 0.5f - 0.77f, 0.09f, 0.0f));
    // A noise-free history of two frames disagrees with a full change whatever the neighbourhood
    // (visibility's variance is at most 1/4).
    EXPECT_FALSE(historyAgrees(p, vec3(1.0f, 1.0f, 2.0f), 0.0f, 0.25f, 0.0f));
}

// The residuals' variance: none from fewer than two places.
TEST(TemporalStep, TheResidualsNoiseIsTheirVariance) {
    EXPECT_NEAR(residualNoise(0.1f + 0.3f, 0.01f + 0.09f, 2.0f), 0.01f, 1e-7f);
    EXPECT_NEAR(residualNoise(3 * 0.2f, 3 * 0.04f, 3.0f), 0.0f, 1e-7f);
    EXPECT_EQ(residualNoise(0.5f, 0.25f, 1.0f), 0.0f);
}

// The neighbourhoods' means: the history's deviation (0.1 x sqrt(8 / 9) = 0.094 here) over
// sqrt(pairs). With 9 places and k = 2, a difference of 0.06 agrees, 0.07 does not; with one
// place 0.18 agrees.
TEST(TemporalStep, TheNeighbourhoodsMeansAllowTheirOwnDeviation) {
    const TemporalParams p = params(16, TEMPORAL_CLAMP_NONE, 2.0f);
    const vec3 history(0.5f, 0.26f, 8.0f);
    EXPECT_TRUE(neighbourhoodsAgree(p, history, 0.4f, 0.46f, 9.0f, 0.0f, 0.0f, 0.0f));
    EXPECT_FALSE(neighbourhoodsAgree(p, history, 0.4f, 0.47f, 9.0f, 0.0f, 0.0f, 0.0f));
    EXPECT_FALSE(neighbourhoodsAgree(p, history, 0.47f, 0.4f, 9.0f, 0.0f, 0.0f, 0.0f));
    EXPECT_TRUE(neighbourhoodsAgree(p, history, 0.4f, 0.58f, 1.0f, 0.0f, 0.0f, 0.0f));
    EXPECT_TRUE(neighbourhoodsAgree(params(16, TEMPORAL_CLAMP_NONE, 0.0f), history, 0.0f, 1.0f,
                                    9.0f, 0.0f, 0.0f, 0.0f));
}

// minmax clamps the history's mean into this frame's neighbourhood (0.2 .. 0.4) and keeps its
// spread about the clamped mean; variance into mean +- gamma deviations.
TEST(TemporalStep, TheClampBoundsTheHistoryAndKeepsItsSpread) {
    const vec4 around(0.2f, 0.4f, 0.3f, 0.09f + 0.0025f); // deviation 0.05
    const vec3 history(1.0f, 1.01f, 8.0f);                // spread 0.1
    const float kept = 0.4f, keptSquare = 0.16f + 0.01f;
    expectNear(temporalStep(params(16, TEMPORAL_CLAMP_MINMAX, 0.0f), history, 0.3f, around),
               vec3(kept + (0.3f - kept) / 9.0f, keptSquare + (0.09f - keptSquare) / 9.0f, 9.0f));
    const float top = 0.35f, topSquare = top * top + 0.01f;
    expectNear(temporalStep(params(16, TEMPORAL_CLAMP_VARIANCE, 0.0f), history, 0.3f, around),
               vec3(top + (0.3f - top) / 9.0f, topSquare + (0.09f - topSquare) / 9.0f, 9.0f));
    const float bottom = 0.2f, bottomSquare = bottom * bottom + 0.01f;
    expectNear(
        temporalStep(params(16, TEMPORAL_CLAMP_MINMAX, 0.0f), vec3(0.0f, 0.01f, 8.0f), 0.3f,
                     around),
        vec3(bottom + (0.3f - bottom) / 9.0f, bottomSquare + (0.09f - bottomSquare) / 9.0f, 9.0f));
}

// At temporal.frames the history stops growing: this frame weighs 1/frames from then on (at
// least 1).
TEST(TemporalStep, TheHistoryStopsGrowingAtTemporalFrames) {
    const TemporalParams p = params(16, TEMPORAL_CLAMP_NONE, 0.0f);
    expectNear(temporalStep(p, vec3(1.0f, 1.0f, 16.0f), 0.0f, kAnything),
               vec3(15.0f / 16.0f, 15.0f / 16.0f, 16.0f));
    expectNear(temporalStep(p, vec3(1.0f, 1.0f, 15.0f), 0.0f, kAnything),
               vec3(15.0f / 16.0f, 15.0f / 16.0f, 16.0f));
    expectNear(
        temporalStep(params(1, TEMPORAL_CLAMP_NONE, 0.0f), vec3(1.0f, 1.0f, 1.0f), 0.0f, kAnything),
        vec3(0.0f, 0.0f, 1.0f));
    // temporal.frames=0 (the layer off, its pass not run): the reference keeps this frame alone.
    expectNear(
        temporalStep(params(0, TEMPORAL_CLAMP_NONE, 0.0f), vec3(1.0f, 1.0f, 4.0f), 0.0f, kAnything),
        vec3(0.0f, 0.0f, 1.0f));
}

// The texel's w: a face normal to 11 bits an octahedral coordinate (within 0.2 degree) and the
// length, every length temporal.frames allows.
TEST(TemporalStep, TheHistoryTexelPacksTheNormalAndTheLength) {
    for (const vec3 n : {vec3(0, 1, 0), vec3(0, 0, -1), vec3(1, 0, 0), vec3(-0.3f, 0.5f, -0.8f),
                         vec3(0.6f, -0.7f, 0.2f), vec3(-0.2f, -0.1f, 0.97f)})
        for (const uint32_t length : {0u, 1u, 2u, 255u, 256u}) {
            const vec3 unit = n / std::sqrt(dot(n, n));
            const uint32_t packed = packHistoryNormal(octahedralEncode(unit), length);
            EXPECT_EQ(historyLengthOf(packed), length);
            EXPECT_GT(dot(octahedralDecode(historyOctahedral(packed)), unit),
                      std::cos(0.2 * M_PI / 180.0))
                << n.x << " " << n.y << " " << n.z;
        }
}

// The octahedral coordinates round to the nearest of 2048 steps: back within half a step (1/2047)
// everywhere, the ends exact, the length beside them intact.
TEST(TemporalStep, TheHistoryNormalRoundsToTheNearestStep) {
    const float halfStep = 1.0f / float(TEMPORAL_NORMAL_STEPS);
    for (int i = 0; i <= 1000; ++i) {
        const float o = -1.0f + 2.0f * float(i) / 1000.0f;
        const uint32_t packed = packHistoryNormal(vec2(o, -o), 7u);
        const vec2 back = historyOctahedral(packed);
        EXPECT_LE(std::abs(back.x - o), halfStep * 1.0001f) << o;
        EXPECT_LE(std::abs(back.y + o), halfStep * 1.0001f) << o;
        EXPECT_EQ(historyLengthOf(packed), 7u) << o;
    }
    EXPECT_EQ(historyOctahedral(packHistoryNormal(vec2(-1.0f, 1.0f), 0u)), vec2(-1.0f, 1.0f));
}

// A history read off where the surface was (a camera's sub-pixel motion) may differ by the
// gradient over that distance: a neighbourhood spreading 0.2 (a gradient of 0.245 a pixel)
// allows 0.122 at half a pixel and nothing where the history is read in place.
TEST(TemporalStep, AHistoryReadOffItsPlaceMayDifferByTheGradient) {
    EXPECT_NEAR(reprojectionAllowance(0.04f, 0.5f), 0.5f * std::sqrt(0.06f), 1e-6f);
    EXPECT_EQ(reprojectionAllowance(0.04f, 0.0f), 0.0f);
    const TemporalParams p = params(16, TEMPORAL_CLAMP_NONE, 2.0f);
    const vec3 exact(0.5f, 0.25f, 16.0f); // no spread over time
    const float pooled = std::sqrt(0.04f / 17.0f) * 2.0f;
    EXPECT_TRUE(historyAgrees(p, exact, 0.5f + pooled + 0.12f, 0.04f, 0.5f));
    EXPECT_FALSE(historyAgrees(p, exact, 0.5f + pooled + 0.13f, 0.04f, 0.5f));
    EXPECT_FALSE(historyAgrees(p, exact, 0.5f + pooled + 0.01f, 0.04f, 0.0f));
    EXPECT_TRUE(neighbourhoodsAgree(p, exact, 0.5f, 0.62f, 9.0f, 0.0f, 0.04f, 0.5f));
    EXPECT_FALSE(neighbourhoodsAgree(p, exact, 0.5f, 0.62f, 9.0f, 0.0f, 0.04f, 0.0f));
}

// The disocclusion test: a relative depth difference up to temporal.depthTolerance (0.02), in
// either order, and a normal within temporal.normalTolerance's cosine (0.9).
TEST(TemporalStep, ASurfaceIsTheSameByItsDepthAndItsNormal) {
    const vec3 up(0.0f, 1.0f, 0.0f);
    EXPECT_TRUE(sameSurface(0.5f, up, 0.5f, up, 0.02f, 0.9f));
    EXPECT_TRUE(sameSurface(0.5f, up, 0.509f, up, 0.02f, 0.9f));
    EXPECT_TRUE(sameSurface(0.509f, up, 0.5f, up, 0.02f, 0.9f));
    EXPECT_FALSE(sameSurface(0.5f, up, 0.512f, up, 0.02f, 0.9f));
    EXPECT_FALSE(sameSurface(0.512f, up, 0.5f, up, 0.02f, 0.9f));
    const auto tilted = [](float cosine) {
        return vec3(std::sqrt(1.0f - cosine * cosine), cosine, 0.0f);
    };
    EXPECT_TRUE(sameSurface(0.5f, tilted(0.91f), 0.5f, up, 0.02f, 0.9f));
    EXPECT_FALSE(sameSurface(0.5f, tilted(0.89f), 0.5f, up, 0.02f, 0.9f));
    EXPECT_FALSE(sameSurface(0.5f, -up, 0.5f, up, 0.02f, 0.9f)); // a face seen from behind
    // The tolerance is relative to the farther (the larger reverse-Z depth): 0.0101 apart at
    // 0.51 is within 2% of 0.5101, not of 0.5; a tolerance of 0 keeps the same depth alone.
    EXPECT_TRUE(sameSurface(0.5101f, up, 0.5f, up, 0.02f, 0.9f));
    EXPECT_TRUE(sameSurface(0.5f, up, 0.5101f, up, 0.02f, 0.9f));
    EXPECT_TRUE(sameSurface(0.5f, up, 0.5f, up, 0.0f, 0.9f));
    EXPECT_FALSE(sameSurface(0.5f, up, 0.5001f, up, 0.0f, 0.9f));
}

// The clamp's ranges: minmax the neighbourhood's smallest and largest, variance its mean plus or
// minus temporal.gamma deviations (both sides), none everything.
TEST(TemporalStep, TheClampRangesFollowTheModeAndGamma) {
    const float mean = 0.3f, meanSquare = 0.09f + 0.0025f; // deviation 0.05
    const vec2 minmax =
        temporalClampRange(TEMPORAL_CLAMP_MINMAX, 2.0f, 0.1f, 0.7f, mean, meanSquare);
    EXPECT_EQ(minmax, vec2(0.1f, 0.7f));
    for (const float gamma : {1.0f, 2.0f, 0.5f}) {
        const vec2 range =
            temporalClampRange(TEMPORAL_CLAMP_VARIANCE, gamma, 0.1f, 0.7f, mean, meanSquare);
        EXPECT_NEAR(range.x, mean - gamma * 0.05f, 1e-6f) << gamma;
        EXPECT_NEAR(range.y, mean + gamma * 0.05f, 1e-6f) << gamma;
    }
    const vec2 none = temporalClampRange(TEMPORAL_CLAMP_NONE, 1.0f, 0.1f, 0.7f, mean, meanSquare);
    EXPECT_LT(none.x, -1e29f);
    EXPECT_GT(none.y, 1e29f);
}

// A history read between texels (a camera's or an object's sub-pixel motion) is worth fewer
// frames the more its taps differ beyond their own noise (resampledLength): texels of 16 frames
// whose means spread 0.01 a frame, blended 1/4 and 3/4 (a noise share of 2 x 3/16 / 16), differ
// by 0.375 x 0.01 / 16 from noise alone; u more than that and the floor (1/512^2) leaves
// 16 / (1 + 16 u / 0.01) frames; an edge between lit and shadowed texels leaves none; a
// noise-free history none on any difference past the floor.
TEST(TemporalStep, AHistoryReadBetweenDifferingTexelsKeepsFewerFrames) {
    const vec3 history(0.5f, 0.25f + 0.01f, 16.0f);
    const float share = 0.375f / 16.0f, explained = share * 0.01f;
    const float floor2 = TEMPORAL_RESET_FLOOR * TEMPORAL_RESET_FLOOR;
    EXPECT_EQ(resampledLength(history, 0.0f, share, 0.01f), 16.0f);
    EXPECT_EQ(resampledLength(history, explained, share, 0.01f), 16.0f);
    EXPECT_EQ(resampledLength(history, explained + 3e-6f, share, 0.01f), 16.0f); // the floor
    EXPECT_NEAR(resampledLength(history, explained + floor2 + 1e-6f, share, 0.01f), 16.0f / 1.0016f,
                1e-3f); // from the floor up, no step
    EXPECT_NEAR(resampledLength(history, explained + floor2 + 1e-4f, share, 0.01f), 16.0f / 1.16f,
                1e-3f);
    const float u = 0.001f - explained - floor2;
    EXPECT_NEAR(resampledLength(history, 0.001f, share, 0.01f), 16.0f / (1.0f + 1600.0f * u),
                1e-3f);
    EXPECT_LT(resampledLength(history, 0.25f, 0.25f / 16.0f, 0.01f), 0.05f);
    EXPECT_EQ(resampledLength(history, std::nanf(""), share, 0.01f), 16.0f);
    // Texels of 1 and 15 frames, half and half (a blend of 8): the fresh one's noise explains
    // most of a difference of 0.0026 (0.25 / 1 + 0.25 / 15 of 0.01).
    const vec3 blend(0.5f, 0.25f + 0.01f, 8.0f);
    EXPECT_EQ(resampledLength(blend, 0.0026f, 0.25f + 0.25f / 15.0f, 0.01f), 8.0f);
    EXPECT_LT(resampledLength(blend, 0.0026f, 0.5f / 8.0f, 0.01f), 4.0f);
    // A spread over time of none pooled with a prior of 0.02 as one frame: 0.005 a frame.
    const vec3 young(0.5f, 0.25f, 3.0f);
    const float youngU = 0.002f - 0.125f * 0.005f - floor2;
    EXPECT_NEAR(resampledLength(young, 0.002f, 0.125f, 0.02f), 3.0f / (1.0f + 600.0f * youngU),
                1e-4f);
    const vec3 exact(1.0f, 1.0f, 8.0f);
    EXPECT_EQ(resampledLength(exact, 0.0f, share, 0.0f), 8.0f);
    EXPECT_EQ(resampledLength(exact, 3e-6f, share, 0.0f), 8.0f);
    EXPECT_LT(resampledLength(exact, 0.01f, share, 0.0f), 1e-6f);
}
