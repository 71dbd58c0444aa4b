// The receiver as a shadow-map technique reads it, and the taps the PCF family builds its kernels
// from [Reeves et al. 1987]: the comparison of one texel with receiver-plane bias, the bilinear
// comparison tap (the four texels around a point compared with the receiver, each at its centre,
// and the four results interpolated: seed 000's 4-tap, texel centres at (i + 1/2) / size), grids
// of them and Poisson disks of them. The scalar maths (the test, the weights, rotations) is
// kernels.h and bias.h, which the CPU references compile too; src/shadows/cpu_filters.cpp
// mirrors these loops. The including pass declares the frame block as `frame` (the Poisson disk).
#ifndef PENUMBRA_RECEIVER_GLSL
#define PENUMBRA_RECEIVER_GLSL
#include "bias.h"
#include "kernels.h"
#include "map_reads.glsl"

struct Receiver {
    vec2 uv;        // shadow-map texture coordinates
    float depth;    // d(p), light depth in [0, 1]
    vec2 gradient;  // d depth / d uv on the receiver's plane (zero: no receiver-plane bias)
    float layer;    // the shadow view's layer in the maps (virtual: its first page-table entry)
    float kernelScale; // kernels in texels of the first cascade, in this view's texels
    vec2 uvDx, uvDy;   // the pixel's footprint: uv's change across it along x and y (mip)
    // bias.mode=adaptive (adaptiveBiasTerms): the per-tap curvature lift (tapDepth) and the
    // receiver's own range for the plane's correction, within the frame's dzRange.
    vec2 curve, planeRange;
    float creaseLimit; // the crease rule's steepest plane, d depth / d uv (creaseTests; 0: off)
};

// The receiver's fields that bias.mode=adaptive leaves alone otherwise.
void noAdaptiveTerms(inout Receiver r) {
    r.curve = vec2(0.0);
    r.planeRange = vec2(-1e30, 1e30);
    r.creaseLimit = 0.0;
}

float texelTest(Receiver r, float stored, vec2 texelUv, vec2 dzRange) {
    vec2 range = vec2(max(dzRange.x, r.planeRange.x), min(dzRange.y, r.planeRange.y));
    return depthTest(tapDepth(r.depth, r.gradient, texelUv - r.uv, range, r.curve), stored);
}

// Tests of the 2x2 texels whose first texel is `base`, in textureGather order:
// x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j). One gather fetches all four depths.
vec4 gatherTests(sampler2DArray map, ivec2 base, float size, Receiver r, vec2 dzRange) {
    vec4 d = gatherDepths(map, base, size, r.layer);
    vec2 c = (vec2(base) + 0.5) / size;
    float t = 1.0 / size;
    vec4 tests = vec4(texelTest(r, d.x, c + vec2(0.0, t), dzRange),
                      texelTest(r, d.y, c + vec2(t, t), dzRange),
                      texelTest(r, d.z, c + vec2(t, 0.0), dzRange), texelTest(r, d.w, c, dzRange));
    return creaseTests(tests, d, r.uv - c - 0.5 * t, t, r.depth, r.creaseLimit,
                       CREASE_MARGIN_TEXELS * t * r.curve.y);
}

// One bilinear comparison tap at `texelPos` (texel units: the map spans [0, size]).
float bilinearTap(sampler2DArray map, vec2 texelPos, float size, Receiver r, vec2 dzRange) {
    vec2 p = texelPos - 0.5;
    vec2 base = floor(p);
    vec2 f = p - base;
    return bilinearMix(gatherTests(map, ivec2(base), size, r, dzRange), f);
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

vec2 poissonPoint(uint i) {
    vec4 pair = frame.poisson[i / 2u];
    return (i % 2u) == 0u ? pair.xy : pair.zw;
}

// n bilinear taps on the Poisson disk scaled to `radius` texels, rotated by `turns`.
float poissonTaps(sampler2DArray map, Receiver r, uint mapSize, uint n, float radius, float turns,
                  vec2 dzRange) {
    vec2 centre = r.uv * float(mapSize);
    float sum = 0.0;
    for (uint i = 0u; i < n; ++i)
        sum += bilinearTap(map, centre + rotatedOffset(poissonPoint(i), turns, radius),
                           float(mapSize), r, dzRange);
    return sum / float(n);
}

#endif
