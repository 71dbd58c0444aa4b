// The prefiltered family's visibility: `vsm` [Donnelly and Lauritzen 2006], `esm` [Annen et al.
// 2008; Salvi 2008] and `evsm` [Lauritzen and McCool 2008] read their blurred maps
// (shaders/include/moments_blur.glsl) bilinearly at the receiver and bound or estimate the lit
// fraction (moments.h). The CPU mirrors are in
// src/shadows/vsm.cpp, esm.cpp, evsm.cpp and msm.cpp (src/shadows/cpu_moments.cpp: the blur).
#ifndef PENUMBRA_SHADOW_MOMENTS_GLSL
#define PENUMBRA_SHADOW_MOMENTS_GLSL
#include "kernels.h"
#include "light_geometry.h"
#include "moments.h"
#include "params_moments.h"
#include "technique_input.glsl"

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

// Mip level `level` of the map (size >> level texels a side) at uv, bilinear over the four
// texels around it (clamp-to-edge), the weights as momentsBilinear's.
vec4 momentsAtLevel(sampler2DArray map, vec2 uv, uint mapSize, float layer, int level) {
    int size = max(int(mapSize) >> level, 1);
    vec2 p = uv * float(size) - 0.5;
    vec2 base = floor(p);
    vec2 f = p - base;
    ivec2 b = ivec2(base);
    ivec2 last = ivec2(size - 1);
    int l = int(layer);
    vec4 t00 = texelFetch(map, ivec3(clamp(b, ivec2(0), last), l), level);
    vec4 t10 = texelFetch(map, ivec3(clamp(b + ivec2(1, 0), ivec2(0), last), l), level);
    vec4 t01 = texelFetch(map, ivec3(clamp(b + ivec2(0, 1), ivec2(0), last), l), level);
    vec4 t11 = texelFetch(map, ivec3(clamp(b + ivec2(1, 1), ivec2(0), last), l), level);
    vec4 m;
    for (int c = 0; c < 4; ++c)
        m[c] = bilinearMix(vec4(t01[c], t11[c], t10[c], t00[c]), f);
    return m;
}

// vsm.filter=mip: the mip chain over the pixel's footprint (mipFootprint), up to
// vsm.anisotropy trilinear taps along its longer axis, averaged.
vec2 momentsMip(sampler2DArray map, Receiver r, uint mapSize) {
    float maxLevel = float(mipLevelCount(mapSize) - 1u);
    vec4 footprint = mipFootprint(r.uvDx, r.uvDy, float(mapSize), vsm.anisotropy, maxLevel);
    int fine = int(floor(footprint.x));
    int coarse = min(fine + 1, int(maxLevel));
    float blend = footprint.x - float(fine);
    int taps = int(footprint.y);
    vec2 sum = vec2(0.0);
    for (int k = 0; k < taps; ++k) {
        vec2 uv = r.uv + mipTapOffset(k, taps) * footprint.zw;
        vec2 a = momentsAtLevel(map, uv, mapSize, r.layer, fine).xy;
        vec2 b = momentsAtLevel(map, uv, mapSize, r.layer, coarse).xy;
        sum += a + (b - a) * blend;
    }
    return sum / float(taps);
}

// x visibility, y z the filtered moments, w the receiver's moment depth.
vec4 shadowVsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    vec2 moments = vsm.anisotropy > 0.0 ? momentsMip(map, r, mapSize)
                                           : momentsBilinear(map, r.uv, mapSize, r.layer, 2).xy;
    float t = momentDepth(view, r.depth);
    float p = chebyshevUpperBound(moments, t, vsm.minVariance);
    return vec4(snapToExtremes(reduceLightBleeding(p, vsm.bleedReduction)), moments, t);
}

// x visibility, y the filtered e^(c z), z the receiver's moment depth.
vec4 shadowEsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    float filtered = momentsBilinear(map, r.uv, mapSize, r.layer, 1).x;
    float t = momentDepth(view, r.depth);
    return vec4(snapToExtremes(exponentialVisibility(filtered, t, esm.c)), filtered,
                t, 0.0);
}

// x visibility, y the positive warp's filtered first moment, z the negative warp's, w the
// receiver's moment depth.
vec4 shadowEvsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    vec4 moments = momentsBilinear(map, r.uv, mapSize, r.layer, 4);
    float t = momentDepth(view, r.depth);
    float p = exponentialVarianceVisibility(moments, t, vec2(evsm.positive, evsm.negative), evsm.minVariance,
                                            evsm.components);
    return vec4(snapToExtremes(reduceLightBleeding(p, evsm.bleedReduction)), moments.x, moments.z,
                t);
}

// x visibility, y z the filtered first two moments, w the receiver's depth in [-1, 1].
vec4 shadowMsmDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view) {
    vec4 moments = momentsBilinear(map, r.uv, mapSize, r.layer, 4);
    if (msm.bits == 16u) moments = msmLoad16(moments);
    float d = 2.0 * momentDepth(view, r.depth) - 1.0;
    float v = clamp(1.0 - momentOcclusion(moments, d, msm.momentBias), 0.0, 1.0);
    return vec4(snapToExtremes(v), moments.x, moments.y, d);
}

vec4 evaluateVsm(TechniqueInput at) { return shadowVsmDetail(shadowMap, at.r, at.mapSize, at.view); }
vec4 evaluateEsm(TechniqueInput at) { return shadowEsmDetail(shadowMap, at.r, at.mapSize, at.view); }
vec4 evaluateEvsm(TechniqueInput at) { return shadowEvsmDetail(shadowMap, at.r, at.mapSize, at.view); }
vec4 evaluateMsm(TechniqueInput at) { return shadowMsmDetail(shadowMap, at.r, at.mapSize, at.view); }

#endif
