#version 460
// The `temporal` layer (src/shadows/temporal.cpp; shaders/include/temporal.h): for one light,
// this frame's visibility (its base technique's and the layers' before this one) blended with the
// pixel's history. The history is where the pixel's surface was last frame (its motion vector),
// read bilinearly from the texels that showed the same surface (depth and normal); none, and the
// pixel starts again from this frame. Where this frame leaves the history's mean by more than
// temporal.reset of its deviations over time, it starts again too (a shadow moved); else the
// history's visibility is clamped into the range this frame's 3x3 neighbourhood allows
// (temporal.clamp), so that a moving shadow does not trail (temporalStep). Written: this frame's
// history (RGBA32UI, temporal.h), then (SPEC_HISTORY_RESOLVE) the light's visibility.
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
#include "gbuffer_encoding.h"
#include "temporal.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
#include "gbuffer.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = LAYER_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = LAYER_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = LAYER_VISIBILITY, r32f) uniform image2DArray visibility;
layout(set = 0, binding = LAYER_MOTION) uniform sampler2D motion;
layout(set = 0, binding = LAYER_HISTORY_PREVIOUS) uniform usampler2DArray previous;
layout(set = 0, binding = LAYER_HISTORY, rgba32ui) uniform uimage2DArray history;
layout(push_constant) uniform Push { VisibilityPush push; };
// Two dispatches a light: the blend reads this frame's visibility around each pixel (the
// clamp), so it writes the history alone; the second copies the blend into the visibility.
layout(constant_id = SPEC_HISTORY_RESOLVE) const bool RESOLVE = false;

// This frame's visibility at p, or -1 where no surface is (background: NaN).
float current(ivec2 p, int layer) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(uvec2(p), frame.imageSize.xy)))
        return -1.0;
    float v = imageLoad(visibility, ivec3(p, layer)).r;
    return isnan(v) ? -1.0 : v;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    int layer = int(push.light.y);
    ivec3 at = ivec3(p, layer);
    float depth = texelFetch(gDepth, p, 0).r;
    if (RESOLVE) {
        if (!isBackground(depth)) // NaN stays
            imageStore(visibility, at, vec4(uintBitsToFloat(imageLoad(history, at).x)));
        return;
    }
    if (isBackground(depth)) {
        imageStore(history, at, uvec4(0u));
        return;
    }
    float now = imageLoad(visibility, at).r;
    vec4 normalTexel = texelFetch(gNormal, p, 0);
    vec3 normal = faceNormal(normalTexel);
    vec4 moved = texelFetch(motion, p, 0); // xy: here minus there (pixels), z: its depth then

    // This frame's 3x3 neighbourhood: what the history may say (the clamp), and its variance.
    float lo = now, hi = now, sum = 0.0, squares = 0.0, n = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            float v = current(p + ivec2(dx, dy), layer);
            if (v < 0.0) continue;
            lo = min(lo, v);
            hi = max(hi, v);
            sum += v;
            squares += v * v;
            n += 1.0;
        }
    vec4 around = vec4(lo, hi, sum / n, squares / n);
    float spatial = max(around.w - around.z * around.z, 0.0);

    // Where the surface was: the texel grid's coordinates there.
    vec2 there = vec2(p) + 0.5 - moved.xy - 0.5;

    // One pass over the 3x3 history texels around the one nearest where the surface was (they
    // hold the four bilinear taps around it), each used where it shows the pixel's surface:
    // - paired with this frame's visibility at the same offset from the pixel, the two
    //   neighbourhoods' means and the spread of the residuals (the reset rule's second test);
    // - a bilinear tap, weighed by whether this frame agrees with it (the first test).
    ivec2 nearest = ivec2(floor(there + 0.5));
    ivec2 base = ivec2(floor(there));
    vec2 f = there - vec2(base);
    float historySum = 0.0, currentSum = 0.0, residuals = 0.0, residualSquares = 0.0;
    float pairs = 0.0, weight = 0.0, meanSquares = 0.0, shares = 0.0, shareSquares = 0.0;
    vec3 kept = vec3(0.0); // mean, spread, length
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = nearest + ivec2(dx, dy);
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(uvec2(t), size))) continue;
            ivec2 tap = t - base;
            bool bilinear = all(greaterThanEqual(tap, ivec2(0))) && all(lessThan(tap, ivec2(2)));
            float v = current(p + ivec2(dx, dy), layer);
            if (v < 0.0 && !bilinear) continue;
            uvec4 h = texelFetch(previous, ivec3(t, layer), 0);
            uint hLength = historyLengthOf(h.w);
            if (hLength == 0u || // no history there
                !sameSurface(uintBitsToFloat(h.z), octahedralDecode(historyOctahedral(h.w)),
                             moved.z, normal, temporal.depthTolerance, temporal.normalTolerance))
                continue;
            vec3 texel = vec3(uintBitsToFloat(h.x), uintBitsToFloat(h.y), float(hLength));
            if (v >= 0.0) {
                float r = v - texel.x;
                historySum += texel.x;
                currentSum += v;
                residuals += r;
                residualSquares += r * r;
                pairs += 1.0;
            }
            if (!bilinear ||
                !historyAgrees(temporal, texel, now, spatial, length(vec2(t) - there)))
                continue;
            float w = (tap.x == 1 ? f.x : 1.0 - f.x) * (tap.y == 1 ? f.y : 1.0 - f.y);
            // The texels' spreads over time averaged (not the spread between them: a shadow's
            // edge on a moving surface is no noise).
            weight += w;
            meanSquares += w * texel.x * texel.x; // how much the taps differ ...
            shares += w / texel.z;                // ... and their noise would
            shareSquares += w * w / texel.z;
            kept += w * vec3(texel.x, texel.y - texel.x * texel.x, texel.z);
        }
    float noise = residualNoise(residuals, residualSquares, pairs);

    vec3 reprojected = vec3(0.0); // mean, mean square, length
    if (weight > 1e-3) {
        kept /= weight;
        reprojected = vec3(kept.x, kept.y + kept.x * kept.x, kept.z);
        float taps = max(meanSquares / weight - kept.x * kept.x, 0.0);
        float noiseShare = shares / weight - shareSquares / (weight * weight);
        reprojected.z = floor(resampledLength(reprojected, taps, noiseShare, spatial) + 0.5);
        if (!neighbourhoodsAgree(temporal, reprojected, historySum / max(pairs, 1.0),
                                 currentSum / max(pairs, 1.0), pairs, noise, spatial,
                                 length(vec2(nearest) - there)))
            reprojected = vec3(0.0);
    }

    vec3 result = temporalStep(temporal, reprojected, now, around);
    imageStore(history, at, uvec4(floatBitsToUint(result.x), floatBitsToUint(result.y),
                                  floatBitsToUint(depth),
                                  packHistoryNormal(octahedralEncode(normal), uint(result.z))));
}
