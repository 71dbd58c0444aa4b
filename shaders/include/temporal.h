// The `temporal` layer (src/shadows/temporal.cpp, shaders/temporal.comp): a light's visibility
// averaged over frames, its history reprojected through the G-buffer's motion vectors, dropped
// where the surface under a pixel is not the one it was (disocclusion, from depth and normal),
// and kept within what this frame's neighbourhood allows (clamping). The parameter block and the
// maths, compiled as GLSL and as C++ (the CPU reference and the tests).
// clang-format off
#ifndef PENUMBRA_TEMPORAL_H
#define PENUMBRA_TEMPORAL_H
#include "technique_block.h"

PENUMBRA_GPU_BEGIN

#define TEMPORAL_CLAMP_NONE 0u     // temporal.clamp: the history as it was
#define TEMPORAL_CLAMP_MINMAX 1u   // ... within the 3x3 neighbourhood's smallest and largest
#define TEMPORAL_CLAMP_VARIANCE 2u // ... within its mean +- temporal.gamma deviations

struct TemporalParams {    // std140, the layer's block (LAYER_PARAMS)
    uint frames;           // temporal.frames: the longest history averaged
    uint clampMode;        // temporal.clamp: TEMPORAL_CLAMP_*
    float gamma;           // temporal.gamma: the variance clamp's half-width, in deviations
    float depthTolerance;  // temporal.depthTolerance: a history texel's largest relative depth
                           // difference from where the pixel's surface was
    float normalTolerance; // temporal.normalTolerance: the smallest cosine between its normal
                           // and the pixel's
    float reset;           // temporal.reset: the history starts again where this frame leaves
                           // its mean by more than this many of its deviations (0: never)
    uint pad0, pad1;
};

// A short history's own spread says little (one frame has none): the reset rule
// (pooledDeviation) pools it with a spread seen around the pixel this frame, counted as this many
// frames [after Schied et al. 2017, who use the neighbourhood's spread alone under 4 frames].
#define TEMPORAL_PRIOR_FRAMES 1.0f
// Changes of visibility below this (half of an 8-bit step) never start a history again: a
// noise-free technique's history is exact, and float rounding must not reset it.
#define TEMPORAL_RESET_FLOOR (1.0f / 512.0f)
// A history texel (RGBA32UI): x its mean's bits, y its mean square's, z the surface's NDC
// depth's, w its face normal (octahedral, 11 bits a coordinate) and its length in frames (10
// bits, temporal.frames <= 256; 0: no history).
#define TEMPORAL_NORMAL_STEPS 2047u

// The weight of this frame's visibility against a history of `historyLength` frames: the
// average of every frame so far (1 / (n + 1)) until temporal.frames, then an exponential
// average of that length.
SHARED float temporalWeight(float historyLength, uint frames) {
    return 1.0f / min(historyLength + 1.0f, float(max(frames, 1u)));
}

// Whether a history texel (its NDC depth and unit normal) shows the surface a pixel shows now,
// whose depth then was `expectedDepth` (its motion vector's z) and whose normal is `normal`.
// NDC depth is reverse-Z: for a perspective camera its relative difference is the relative
// difference in distance.
SHARED bool sameSurface(float historyDepth, vec3 historyNormal, float expectedDepth, vec3 normal,
                        float depthTolerance, float normalTolerance) {
    return abs(historyDepth - expectedDepth) <= depthTolerance * max(historyDepth, expectedDepth) &&
           dot(historyNormal, normal) >= normalTolerance;
}

// The range the history's visibility is clamped into, from the 3x3 neighbourhood of this
// frame's visibility: its smallest and largest (lo, hi), or its mean and mean square (mean,
// meanSquare) for the variance rule [Salvi 2016]; everything for TEMPORAL_CLAMP_NONE.
SHARED vec2 temporalClampRange(uint mode, float gamma, float lo, float hi, float mean,
                               float meanSquare) {
    if (mode == TEMPORAL_CLAMP_MINMAX) return vec2(lo, hi);
    if (mode == TEMPORAL_CLAMP_VARIANCE) {
        float deviation = sqrt(max(meanSquare - mean * mean, 0.0f));
        return vec2(mean - gamma * deviation, mean + gamma * deviation);
    }
    return vec2(-1e30f, 1e30f);
}

SHARED uint packHistoryNormal(vec2 octahedral, uint historyLength) {
    uvec2 q = uvec2(floor((clamp(octahedral, -1.0f, 1.0f) * 0.5f + 0.5f) *
                              float(TEMPORAL_NORMAL_STEPS) + 0.5f));
    return q.x | (q.y << 11u) | (min(historyLength, 1023u) << 22u);
}

SHARED vec2 historyOctahedral(uint packed) {
    uvec2 q = uvec2(packed & TEMPORAL_NORMAL_STEPS, (packed >> 11u) & TEMPORAL_NORMAL_STEPS);
    return vec2(q) / float(TEMPORAL_NORMAL_STEPS) * 2.0f - 1.0f;
}

SHARED uint historyLengthOf(uint packed) { return packed >> 22u; }

// The deviation the reset rule allows a history (mean, mean square, length in frames): its spread
// over time pooled with `prior`, a variance seen around the pixel this frame, that counted as
// TEMPORAL_PRIOR_FRAMES frames.
SHARED float pooledDeviation(vec3 history, float prior) {
    float spread = max(history.y - history.x * history.x, 0.0f);
    return sqrt((history.z * spread + TEMPORAL_PRIOR_FRAMES * max(prior, 0.0f)) /
                (history.z + TEMPORAL_PRIOR_FRAMES));
}

// What a history read `distance` pixels from where the pixel's surface was may differ by
// without moving: the gradient over that distance, the gradient estimated from this frame's 3x3
// neighbourhood's variance `spatial` (values a + g x over three columns spread g sqrt(2/3)).
// Without it a camera's sub-pixel motion across a penumbra would reset the history every frame.
SHARED float reprojectionAllowance(float spatial, float distance) {
    return distance * sqrt(1.5f * max(spatial, 0.0f));
}

// The reset rule, two tests, each `<= temporal.reset deviations + reprojectionAllowance +
// TEMPORAL_RESET_FLOOR` to agree; temporal.reset = 0 keeps every history.
// First, a contradiction, for one history texel where the pixel's surface was: this frame's
// visibility `now` against the texel's mean, the prior this frame's 3x3 neighbourhood's variance
// (`spatial`: its gradient and its noise, what a pixel may plausibly show). A texel this frame
// contradicts is dropped and the history keeps the texels that agree: a noise-free technique's
// history (no spread) starts again on any change (from its second frame on whatever the
// neighbourhood: visibility's variance is at most 1/4, 2 x sqrt(1/4 / 3) < 1), and on a moving
// surface a shadow's edge does not blur.
SHARED bool historyAgrees(IN(TemporalParams) params, vec3 texel, float now, float spatial,
                          float distance) {
    if (params.reset <= 0.0f) return true;
    return abs(now - texel.x) <= params.reset * pooledDeviation(texel, spatial) +
                                     reprojectionAllowance(spatial, distance) +
                                     TEMPORAL_RESET_FLOOR;
}

// Second, a drift, for the pixel's whole history (`history`, reprojected): this frame's mean over
// the 3x3 neighbourhood against the history's mean over the same `pairs` places (those whose
// history texel shows the pixel's surface), the prior the variance of the residuals there
// (`noise`: this frame minus the history; a shadow's gradient is in both and cancels, so a
// penumbra is no noise). A mean of n values varies 1/sqrt(n) as much as one, so a soft shadow's
// drift (a caster moving) shows here frames before one pixel can tell it from noise; at rest both
// means see the same shadow.
SHARED bool neighbourhoodsAgree(IN(TemporalParams) params, vec3 history, float historyMean,
                                float currentMean, float pairs, float noise, float spatial,
                                float distance) {
    if (params.reset <= 0.0f || pairs < 1.0f) return true;
    return abs(currentMean - historyMean) <=
           params.reset * pooledDeviation(history, noise) / sqrt(pairs) +
               reprojectionAllowance(spatial, distance) + TEMPORAL_RESET_FLOOR;
}

// The residuals' variance over `pairs` places from their sum and sum of squares; none from fewer
// than two.
SHARED float residualNoise(float sum, float squares, float pairs) {
    if (pairs < 2.0f) return 0.0f;
    float mean = sum / pairs;
    return max(squares / pairs - mean * mean, 0.0f);
}

// The length a history read between texels keeps (`history`: the blend's mean, mean square and
// length n >= 1): a Kalman filter's prediction [Kalman 1960], the blend's mean uncertain by as
// much as the texels it blends differ (`taps`, their weighted variance about it), less what
// their own noise explains: a texel of length n_i varies spread / n_i, and texels of weights w_i
// (summing to 1) differ by sum w_i (1 - w_i) / n_i (`noiseShare`) times a frame's spread. That
// spread is the history's pooled with `prior` as the reset rule pools it; a history of n frames
// uncertain by u more is worth n / (1 + n u / spread) frames, u counted from the floor up (a
// noise-free history keeps n up to it). Without it a camera's or an object's sub-pixel motion
// blurs a shadow's edge a little each frame, and the history keeps the blur.
SHARED float resampledLength(vec3 history, float taps, float noiseShare, float prior) {
    float n = history.z;
    float perFrame = pooledDeviation(history, prior);
    perFrame *= perFrame;
    float unexplained = taps - noiseShare * perFrame - TEMPORAL_RESET_FLOOR * TEMPORAL_RESET_FLOOR;
    if (!(unexplained > 0.0f)) return n; // NaN too
    return n / (1.0f + n * unexplained / max(perFrame, 1e-12f));
}

// One pixel's step (the CPU reference): `history` is what the texels that show the pixel's
// surface and agree with this frame kept, reprojected (mean, mean square, length; length 0:
// none), `now` this frame's visibility and `around` its neighbourhood. The new (mean, mean
// square, length): no history, this frame alone; else the history's mean clamped into the
// neighbourhood's range (temporal.clamp), its spread kept, and this frame blended in with
// weight 1/n.
SHARED vec3 temporalStep(IN(TemporalParams) params, vec3 history, float now, vec4 around) {
    if (history.z < 0.5f) return vec3(now, now * now, 1.0f);
    float mean = history.x, meanSquare = history.y, historyLength = history.z;
    vec2 range = temporalClampRange(params.clampMode, params.gamma, around.x, around.y, around.z,
                                    around.w);
    float clamped = clamp(mean, range.x, range.y);
    meanSquare += clamped * clamped - mean * mean; // the same spread about the clamped mean
    float alpha = temporalWeight(historyLength, params.frames);
    return vec3(mix(clamped, now, alpha), mix(meanSquare, now * now, alpha),
                min(historyLength + 1.0f, float(max(params.frames, 1u))));
}

PENUMBRA_GPU_END

PENUMBRA_LAYER_BLOCK(TemporalBlock, TemporalParams, temporal)

#endif
// clang-format on
