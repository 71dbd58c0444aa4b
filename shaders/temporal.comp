#version 460
// The `temporal` layer (src/shadows/temporal.cpp; shaders/include/temporal.h): for one light,
// this frame's visibility (its base technique's and the layers' before this one) blended with the
// pixel's history. The history is where the pixel's surface was last frame (its motion vector),
// read bilinearly from the texels that showed the same surface (depth and normal); none, and the
// pixel starts again from this frame. The history's visibility is first clamped into the range
// this frame's 3x3 neighbourhood allows (temporal.clamp), so that a moving shadow does not
// trail. Written: this frame's history (RGBA32UI: the average's bits, its length in frames, the
// depth's bits, the face normal packed), then (SPEC_HISTORY_RESOLVE) the light's visibility.
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

    // The history: bilinear over the four texels around where the surface was, each weighed by
    // whether it showed the same surface.
    vec2 there = vec2(p) + 0.5 - moved.xy - 0.5; // the texel grid's coordinates
    ivec2 base = ivec2(floor(there));
    vec2 f = there - vec2(base);
    float weight = 0.0, average = 0.0, kept = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 t = base + ivec2(k & 1, k >> 1);
        if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(uvec2(t), size))) continue;
        uvec4 h = texelFetch(previous, ivec3(t, layer), 0);
        if (h.y == 0u) continue; // no history there
        vec3 hNormal = octahedralDecode(unpackSnorm2x16(h.w));
        if (!sameSurface(uintBitsToFloat(h.z), hNormal, moved.z, normal,
                         temporal.depthTolerance, temporal.normalTolerance))
            continue;
        float w = ((k & 1) == 1 ? f.x : 1.0 - f.x) * ((k >> 1) == 1 ? f.y : 1.0 - f.y);
        weight += w;
        average += w * uintBitsToFloat(h.x);
        kept += w * float(h.y);
    }
    float result = now;
    float frames = 1.0;
    if (weight > 1e-3) {
        average /= weight;
        kept = floor(kept / weight + 0.5);
        // The neighbourhood of this frame's visibility bounds what the history may say.
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
        vec2 range = temporalClampRange(temporal.clampMode, temporal.gamma, lo, hi, sum / n,
                                        squares / n);
        average = clamp(average, range.x, range.y);
        float alpha = temporalWeight(kept, temporal.frames);
        result = mix(average, now, alpha);
        frames = min(kept + 1.0, float(temporal.frames));
    }
    imageStore(history, at, uvec4(floatBitsToUint(result), uint(frames), floatBitsToUint(depth),
                                  packSnorm2x16(octahedralEncode(normal))));
}
