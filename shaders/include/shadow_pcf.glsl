// Percentage-closer filtering [Reeves et al. 1987] and its variants. Every kernel is built from
// one primitive, the bilinear comparison tap: the four texels around a point are compared with
// the receiver (at each texel's centre, with receiver-plane bias) and the four results are
// interpolated (seed 000's 4-tap, with texel centres at (i + 1/2) / size).
// src/reference/filter_reference.cpp mirrors this file on the CPU, operation for operation.
// The including shader declares, first, the FrameData uniform block as `frame` (passing the
// 768-byte block by value would copy it per call) and the specialization constant FILTER
// (== frame.filterMode.x), so each kernel compiles alone: a runtime switch over every kernel
// made even the simplest one 2x slower on lavapipe.
#ifndef PENUMBRA_SHADOW_PCF_GLSL
#define PENUMBRA_SHADOW_PCF_GLSL
#include "gpu_types.h"

struct Receiver {
    vec2 uv;        // shadow-map texture coordinates
    float depth;    // d(p), light depth in [0, 1]
    vec2 gradient;  // d depth / d uv on the receiver's plane (zero: no receiver-plane bias)
    float layer;    // the shadow view's layer in the maps
};

float texelTest(Receiver r, float stored, vec2 texelUv, vec2 dzRange) {
    float dz = clamp(dot(r.gradient, texelUv - r.uv), dzRange.x, dzRange.y);
    return r.depth + dz <= stored ? 1.0 : 0.0;
}

// Tests of the 2x2 texels whose first texel is `base`, in textureGather order:
// x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j). One gather fetches all four depths.
vec4 gatherTests(sampler2DArray map, ivec2 base, float size, Receiver r, vec2 dzRange) {
    vec4 d = textureGather(map, vec3((vec2(base) + 1.0) / size, r.layer), 0);
    vec2 c = (vec2(base) + 0.5) / size;
    float t = 1.0 / size;
    return vec4(texelTest(r, d.x, c + vec2(0.0, t), dzRange),
                texelTest(r, d.y, c + vec2(t, t), dzRange),
                texelTest(r, d.z, c + vec2(t, 0.0), dzRange),
                texelTest(r, d.w, c, dzRange));
}

// One bilinear comparison tap at `texelPos` (texel units: the map spans [0, size]).
float bilinearTap(sampler2DArray map, vec2 texelPos, float size, Receiver r, vec2 dzRange) {
    vec2 p = texelPos - 0.5;
    vec2 base = floor(p);
    vec2 f = p - base;
    vec4 t = gatherTests(map, ivec2(base), size, r, dzRange);
    return mix(mix(t.w, t.z, f.x), mix(t.x, t.y, f.x), f.y);
}

#define PCF_MAX_SIZE 15

// Texel weights of an n-tap kernel (box: 1/n; Gaussian with sigma, normalised) after bilinear
// taps with sub-texel fraction f: texel k of the (n+1)-wide footprint gets
// c(k) = g(k)(1 - f) + g(k-1) f.
void footprintWeights(uint filterKind, int n, float sigma, float f, out float c[PCF_MAX_SIZE + 1]) {
    float g[PCF_MAX_SIZE];
    float h = 0.5 * float(n - 1), sum = 0.0;
    for (int i = 0; i < n; ++i) {
        g[i] = filterKind == FILTER_GAUSSIAN
                   ? exp(-0.5 * (float(i) - h) * (float(i) - h) / (sigma * sigma))
                   : 1.0;
        sum += g[i];
    }
    for (int k = 0; k <= n; ++k)
        c[k] = ((k < n ? g[k] : 0.0) * (1.0 - f) + (k > 0 ? g[k - 1] : 0.0) * f) / sum;
}

// An n x n grid of bilinear taps, one texel apart, centred on the receiver (n odd; n = 1 is
// the bilinear variant). All taps share the sub-texel fraction, so the sum is separable over
// the (n+1) x (n+1) footprint: ((n + 1) / 2)^2 gathers instead of 4 n^2 point fetches.
float pcfGrid(sampler2DArray map, Receiver r, uint mapSize, uint filterKind, int n, float sigma,
              vec2 dzRange) {
    float size = float(mapSize);
    vec2 p = r.uv * size - 0.5;
    vec2 base = floor(p);
    vec2 f = p - base;
    float cx[PCF_MAX_SIZE + 1], cy[PCF_MAX_SIZE + 1];
    footprintWeights(filterKind, n, sigma, f.x, cx);
    footprintWeights(filterKind, n, sigma, f.y, cy);
    ivec2 first = ivec2(base) - (n - 1) / 2;
    float sum = 0.0;
    for (int ky = 0; ky <= n; ky += 2)
        for (int kx = 0; kx <= n; kx += 2) {
            vec4 t = gatherTests(map, first + ivec2(kx, ky), size, r, dzRange);
            sum += (t.w * cx[kx] + t.z * cx[kx + 1]) * cy[ky] +
                   (t.x * cx[kx] + t.y * cx[kx + 1]) * cy[ky + 1];
        }
    return sum;
}

uint hashU32(uint v) { // lowbias32, as src/reference/sampling.cpp
    v ^= v >> 16; v *= 0x7feb352du; v ^= v >> 15; v *= 0x846ca68bu; v ^= v >> 16;
    return v;
}

// Per-pixel rotation of the Poisson disk, in turns [0, 1).
float rotationTurns(uint rotation, uvec2 pixel) {
    if (rotation == ROTATION_RANDOM) return float(hashU32(pixel.x * 0x9E3779B9u ^ hashU32(pixel.y))) * (1.0 / 4294967296.0);
    if (rotation == ROTATION_IGN) // interleaved gradient noise [Jimenez 2014]
        return fract(52.9829189 * fract(0.06711056 * float(pixel.x) + 0.00583715 * float(pixel.y)));
    return 0.0;
}

vec2 poissonPoint(uint i) {
    vec4 pair = frame.poisson[i / 2u];
    return (i % 2u) == 0u ? pair.xy : pair.zw;
}

// n bilinear taps on the Poisson disk scaled to `radius` texels, rotated by `turns`.
float poissonTaps(sampler2DArray map, Receiver r, uint mapSize, uint n, float radius, float turns,
                  vec2 dzRange) {
    float angle = 6.28318530718 * turns;
    float c = cos(angle), s = sin(angle);
    vec2 centre = r.uv * float(mapSize);
    float sum = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec2 d = poissonPoint(i);
        vec2 offset = radius * vec2(c * d.x - s * d.y, s * d.x + c * d.y);
        sum += bilinearTap(map, centre + offset, float(mapSize), r, dzRange);
    }
    return sum / float(n);
}

float pcfPoisson(sampler2DArray map, Receiver r, uint mapSize, uvec2 pixel, vec2 dzRange) {
    return poissonTaps(map, r, mapSize, frame.filterMode.z, frame.filterParams.x,
                       rotationTurns(frame.filterMode.w, pixel), dzRange);
}

// [Isidoro 2006] edge-only PCF: four taps at the kernel's corners; when they agree fully
// (all lit or all shadowed) the pixel is taken to be away from any edge.
bool pcfProbeDecides(sampler2DArray map, Receiver r, uint mapSize, vec2 dzRange, out float result) {
    float reach = FILTER == FILTER_POISSON ? frame.filterParams.x * 0.70710678
                                                       : 0.5 * float(frame.filterMode.y - 1u);
    vec2 centre = r.uv * float(mapSize);
    float sum = bilinearTap(map, centre + vec2(-reach, -reach), float(mapSize), r, dzRange) +
                bilinearTap(map, centre + vec2(reach, -reach), float(mapSize), r, dzRange) +
                bilinearTap(map, centre + vec2(-reach, reach), float(mapSize), r, dzRange) +
                bilinearTap(map, centre + vec2(reach, reach), float(mapSize), r, dzRange);
    result = sum * 0.25;
    return sum == 0.0 || sum == 4.0;
}

// Weighted sums of exact 0/1 tests land within float round-off of 0 or 1 when every test
// agrees; fully lit must read exactly 1 (and fully shadowed 0), so round-off snaps.
float snapToExtremes(float v) { return v >= 0.99999 ? 1.0 : (v <= 0.00001 ? 0.0 : v); }

float shadowPcfUnsnapped(sampler2DArray map, sampler2DArrayShadow mapCompare, Receiver r, uint mapSize,
                         uvec2 pixel) {
    const uint filterKind = FILTER;
    vec2 dzRange = frame.biasParams.xy;
    if (filterKind == FILTER_HARDWARE) {
        // One comparison-sampler tap (SampleCmpLevelZero). Without linear depth filtering
        // (lavapipe) the same bilinear comparison is done by hand.
        // A comparison sampler compares every texel with one reference depth, so receiver-plane
        // bias cannot apply per texel here; the by-hand version drops it the same way.
        if (frame.biasMode.y != 0u) return texture(mapCompare, vec4(r.uv, r.layer, r.depth));
        Receiver noPlane = r;
        noPlane.gradient = vec2(0.0);
        return bilinearTap(map, r.uv * float(mapSize), float(mapSize), noPlane, dzRange);
    }
    float early;
    if (frame.filterParams.z != 0.0 && filterKind != FILTER_BILINEAR &&
        pcfProbeDecides(map, r, mapSize, dzRange, early))
        return early;
    if (filterKind == FILTER_POISSON) return pcfPoisson(map, r, mapSize, pixel, dzRange);
    int n = filterKind == FILTER_BILINEAR ? 1 : int(frame.filterMode.y);
    return pcfGrid(map, r, mapSize, filterKind, n, frame.filterParams.y, dzRange);
}

float shadowPcf(sampler2DArray map, sampler2DArrayShadow mapCompare, Receiver r, uint mapSize, uvec2 pixel) {
    return snapToExtremes(shadowPcfUnsnapped(map, mapCompare, r, mapSize, pixel));
}

#endif
