// The prefiltered family's visibility: `vsm` [Donnelly and Lauritzen 2006], `esm` [Annen et al.
// 2008; Salvi 2008] and `evsm` [Lauritzen and McCool 2008] read their blurred maps
// (shaders/include/moments_blur.glsl) bilinearly at the receiver and bound or estimate the lit
// fraction (filter_math.h). The CPU mirror is src/reference/filter_reference.cpp.
#ifndef PENUMBRA_SHADOW_MOMENTS_GLSL
#define PENUMBRA_SHADOW_MOMENTS_GLSL
#include "filter_math.h"

// The first `channels` channels at uv, bilinear over the four texels around it (clamp-to-edge),
// interpolated here rather than by the sampler so that the CPU reference can repeat it exactly.
vec4 momentsBilinear(sampler2DArray map, vec2 uv, uint mapSize, float layer, int channels) {
    float size = float(mapSize);
    vec2 p = uv * size - 0.5;
    vec2 base = floor(p);
    vec2 f = p - base;
    vec3 at = vec3((base + 1.0) / size, layer);
    vec4 m = vec4(0.0);
    m.x = bilinearMix(textureGather(map, at, 0), f);
    if (channels > 1) m.y = bilinearMix(textureGather(map, at, 1), f);
    if (channels > 2) m.z = bilinearMix(textureGather(map, at, 2), f);
    if (channels > 3) m.w = bilinearMix(textureGather(map, at, 3), f);
    return m;
}

// x visibility, y z the filtered moments, w the receiver's moment depth.
vec4 shadowVsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    vec2 moments = momentsBilinear(map, r.uv, mapSize, r.layer, 2).xy;
    float t = momentDepth(view, r.depth);
    float p = chebyshevUpperBound(moments, t, frame.vsmParams.x);
    return vec4(snapToExtremes(reduceLightBleeding(p, frame.vsmParams.y)), moments, t);
}

// x visibility, y the filtered e^(c z), z the receiver's moment depth.
vec4 shadowEsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    float filtered = momentsBilinear(map, r.uv, mapSize, r.layer, 1).x;
    float t = momentDepth(view, r.depth);
    return vec4(snapToExtremes(exponentialVisibility(filtered, t, frame.esmParams.x)), filtered,
                t, 0.0);
}

// x visibility, y the positive warp's filtered first moment, z the negative warp's, w the
// receiver's moment depth.
vec4 shadowEvsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    vec4 moments = momentsBilinear(map, r.uv, mapSize, r.layer, 4);
    float t = momentDepth(view, r.depth);
    float p = exponentialVarianceVisibility(moments, t, frame.evsmParams.xy, frame.evsmParams.z,
                                            frame.evsmMode.x);
    return vec4(snapToExtremes(reduceLightBleeding(p, frame.evsmParams.w)), moments.x, moments.z,
                t);
}

// x visibility, y z the filtered first two moments, w the receiver's depth in [-1, 1].
vec4 shadowMsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    vec4 moments = momentsBilinear(map, r.uv, mapSize, r.layer, 4);
    if (frame.msmParams.z == 16.0) moments = msmLoad16(moments);
    float d = 2.0 * momentDepth(view, r.depth) - 1.0;
    float v = clamp(1.0 - momentOcclusion(moments, d, frame.msmParams.x), 0.0, 1.0);
    return vec4(snapToExtremes(v), moments.x, moments.y, d);
}

#endif
