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
    uint pad0, pad1, pad2;
};

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

PENUMBRA_GPU_END

PENUMBRA_LAYER_BLOCK(TemporalBlock, TemporalParams, temporal)

#endif
// clang-format on
