// The moment family's maths, compiled as GLSL and as C++ like kernels.h: the depth the moments
// are taken of, Chebyshev's bound and light-bleeding reduction (vsm, savsm, vssm), exponential
// warps (esm, evsm), mip footprints (vsm.filter=mip), fixed-point summed-area tables (savsm,
// vssm, msm-soft) and the Hamburger four-moment reconstruction (msm, msm-soft).
// clang-format off
#ifndef PENUMBRA_MOMENTS_H
#define PENUMBRA_MOMENTS_H
#include "light_geometry.h"

PENUMBRA_GPU_BEGIN

#define VSSM_MAX_SUBDIVISION 4    // vssm.subdivision's and msm-soft.subdivision's largest value
#define VSSM_NO_BLOCKERS 1e-4f    // a blocking fraction at most this: nothing in the way
#define VSSM_MIN_CELL 2.0f        // texels: no sub-kernel is cut narrower
#define VSSM_NARROW_SEARCH 4.0f   // texels: the search's half-width where the light's box finds none
#define VSSM_REFINE_STEPS 2       // searches over the penumbra's box (vssm.refine)
// The half-width of the box with the variance of a disc of unit radius (sqrt(3) / 2): the box
// the summed-area members filter a penumbra of radius r over is this times r.
#define VSSM_BOX_PER_RADIUS 0.8660254f

// Variance shadow maps [Donnelly and Lauritzen 2006] (docs/techniques.md, "vsm"). The depth the
// moments are taken of: linear in the light's view distance, 0 at the near plane and 1 at the
// far one (the orthographic depth itself; a perspective view's hyperbolic depth would crowd its
// far half into a sliver where variances vanish), then spread over the part of that range the
// view's receivers lie in (ShadowViewData::moments: a sun's cascade, a slice of a range that
// spans the whole scene), casters in front of it at 0.
SHARED float momentDepth(IN(ShadowViewData) view, float depth) {
    float linear = depth;
    if (view.texel.y >= 0.5f) {
        float n = view.frustum.x, f = view.frustum.y;
        linear = (n * f / (f - depth * (f - n)) - n) / (f - n);
    }
    return clamp((linear - view.moments.x) / (1.0f - view.moments.x - view.moments.y), 0.0f,
                 1.0f);
}

// One-tailed Chebyshev bound on the fraction of the filtered depths at or beyond receiver depth
// t: 1 where t is not beyond their mean, else sigma^2 / (sigma^2 + (t - mu)^2), with the
// variance held at least `minVariance` (numeric noise on a flat surface must not read as shadow).
SHARED float chebyshevUpperBound(vec2 moments, float t, float minVariance) {
    float mean = moments.x;
    if (t <= mean) return 1.0f;
    float variance = max(moments.y - mean * mean, minVariance);
    float d = t - mean;
    return variance / (variance + d * d);
}

// Light-bleeding reduction [Lauritzen 2007]: bounds up to `amount` count as shadow, the rest
// rescaled to [0, 1] (0 leaves p as it is).
SHARED float reduceLightBleeding(float p, float amount) {
    return clamp((p - amount) / (1.0f - amount), 0.0f, 1.0f);
}

// vsm.filter=mip [Donnelly and Lauritzen 2006, section 4; the anisotropic footprint of the
// Vulkan specification's texel filtering]: the levels of a full mip chain over a size^2 map.
SHARED uint mipLevelCount(uint size) {
    uint levels = 1u;
    while ((size >> levels) > 0u) levels += 1u;
    return levels;
}

// The footprint of a pixel in a mip chain whose level 0 is size^2, from the shadow-map uv's
// change across one pixel along x and y: x the level (fractional, 0 .. maxLevel), y the taps
// spread along the footprint's longer axis (1 .. maxTaps; its length over its width), zw that
// axis in uv. Each tap filters (major / taps) texels, so the level is log2 of that. A footprint
// within one texel takes one tap: the bilinear read already spans more than it.
SHARED vec4 mipFootprint(vec2 uvDx, vec2 uvDy, float size, float maxTaps, float maxLevel) {
    float lx = length(uvDx) * size;
    float ly = length(uvDy) * size;
    float major = max(lx, ly);
    float minor = min(lx, ly);
    float taps = major <= 1.0f ? 1.0f
                               : clamp(ceil(major / max(minor, 1e-6f) - 1e-3f), 1.0f, maxTaps);
    float level = clamp(log2(max(major / taps, 1e-6f)), 0.0f, maxLevel);
    vec2 axis = lx >= ly ? uvDx : uvDy;
    return vec4(level, taps, axis.x, axis.y);
}

// Where tap k of n sits along the footprint's axis, as a fraction of it: evenly over (-1/2, 1/2).
SHARED float mipTapOffset(int k, int n) { return (float(k) + 0.5f) / float(n) - 0.5f; }

// What a prefiltered map stores of a moment depth z, by technique (its channels, unused ones 0):
// vsm (z, z^2); esm e^(c z) [Annen et al. 2008]; evsm [Lauritzen and McCool 2008] the moments of
// both exponential warps, (e^(c+ z), e^(2 c+ z), -e^(-c- z), e^(-2 c- z)). `exponents`: esm
// (c, -), evsm (c+, c-).
#define MOMENTS_VSM 0u
#define MOMENTS_ESM 1u
#define MOMENTS_EVSM 2u
#define MOMENTS_MSM 3u
SHARED vec4 warpedMoments(uint kind, float z, vec2 exponents) {
    if (kind == MOMENTS_MSM) { // msm: the powers of the depth mapped to [-1, 1]
        float d = 2.0f * z - 1.0f, d2 = d * d;
        return vec4(d, d2, d2 * d, d2 * d2);
    }
    if (kind == MOMENTS_ESM) return vec4(exp(exponents.x * z), 0.0f, 0.0f, 0.0f);
    if (kind == MOMENTS_EVSM) {
        float p = exp(exponents.x * z), n = -exp(-exponents.y * z);
        return vec4(p, p * p, n, n * n);
    }
    return vec4(z, z * z, 0.0f, 0.0f);
}

// Exponential shadow maps: the filtered e^(c z) over e^(c t), at most 1 (a receiver in front of
// every occluder). Exact for receivers behind all the occluders they filter; near contact the
// exponential's tail makes them lighter.
SHARED float exponentialVisibility(float filtered, float t, float c) {
    return clamp(exp(-c * t) * filtered, 0.0f, 1.0f);
}

// Exponential variance shadow maps: Chebyshev's bound in each warp, the smaller one. The minimum
// variance is given in moment-depth units and carried into each warp by its slope at t (the
// warp's derivative, squared). components 2: the positive warp alone.
SHARED float exponentialVarianceVisibility(vec4 moments, float t, vec2 exponents,
                                           float minVariance, uint components) {
    float p = exp(exponents.x * t);
    float slope = exponents.x * p;
    float bound = chebyshevUpperBound(vec2(moments.x, moments.y), p, minVariance * slope * slope);
    if (components == 4u) {
        float n = -exp(-exponents.y * t);
        float nSlope = exponents.y * n;
        bound = min(bound, chebyshevUpperBound(vec2(moments.z, moments.w), n,
                                               minVariance * nSlope * nSlope));
    }
    return bound;
}

// Summed-area VSM [Lauritzen 2007]: the moments a summed-area table sums, offset to [-1/2, 1/2]
// so that sums over a whole map stay small (their signs cancel). The variance is unchanged; the
// receiver's depth takes the same offset.
SHARED vec2 offsetMoments(float z) {
    float d = z - 0.5f;
    return vec2(d, d * d);
}

// Summed-area tables in fixed point [Lauritzen 2007, GPU Gems 3 ch. 8]: what a table sums of a
// moment depth z, each channel as a number in [0, 1] quantised to `scale` steps (unused channels
// 0). MOMENTS_VSM: the offset moments (z - 1/2, (z - 1/2)^2) as z and 4 (z - 1/2)^2; MOMENTS_MSM:
// the four powers of 2 z - 1 (warpedMoments), mapped from [-1, 1]. Integer sums wrap around 2^32
// and stay exact, so a box's sum does not depend on where in the map it lies (float sums lose
// their low bits far from the table's origin).
SHARED uvec4 tableMoments(uint kind, float z, float scale) {
    vec4 unit;
    if (kind == MOMENTS_MSM) {
        unit = 0.5f * warpedMoments(MOMENTS_MSM, z, vec2(0.0f)) + 0.5f;
    } else {
        vec2 m = offsetMoments(z);
        unit = vec4(m.x + 0.5f, 4.0f * m.y, 0.0f, 0.0f);
    }
    return uvec4(floor(unit * scale + 0.5f));
}

// The moments a box's mean (steps per texel) stands for: tableMoments' inverse.
SHARED vec4 tableMean(uint kind, vec4 steps, float scale) {
    vec4 unit = steps / scale;
    if (kind == MOMENTS_MSM) return 2.0f * unit - 1.0f;
    return vec4(unit.x - 0.5f, 0.25f * unit.y, 0.0f, 0.0f);
}

// One integer box of a table from its corners' wrapping sums: exact while the true sum's
// magnitude stays under 2^31 (fixedPointScale), signed because a box between the corners either
// side of a fractional edge may run backwards (tableBoxSum).
SHARED vec4 boxFromCorners(uvec4 c00, uvec4 c10, uvec4 c01, uvec4 c11) {
    return vec4(ivec4(c11 - c01 - c10 + c00));
}

// Variance soft shadow maps [Yang et al. 2010] (docs/techniques.md, "vssm"): the blockers a
// (sub-)kernel's moments imply for a receiver at depth t. Chebyshev's bound p is taken as the
// fraction at t (unoccluded) and the rest as blockers at one depth z_occ, so that the mean
// mu = p t + (1 - p) z_occ: x the blocking fraction 1 - p, y (1 - p) z_occ = mu - p t. Zero where
// t is not beyond the mean (the bound says lit). Weighted by their areas, sub-kernels add up;
// the average blocker depth is y / x.
SHARED vec2 chebyshevBlockers(vec2 moments, float t, float minVariance) {
    float p = chebyshevUpperBound(moments, t, minVariance);
    if (p >= 1.0f) return vec2(0.0f);
    return vec2(1.0f - p, moments.x - p * t);
}

// A receiver's own spread over a box: `plane` x its mean depth there, y its mean square. Its
// variance, taken out of the box's second moment, leaves the spread of what is not the receiver:
// a floor seen at a grazing angle otherwise reads, through Chebyshev's bound, as light, and a
// search over it finds no blocker (docs/techniques.md, "vssm").
SHARED vec2 withoutReceiverSpread(vec2 moments, vec2 plane) {
    return vec2(moments.x, moments.y - max(plane.y - plane.x * plane.x, 0.0f));
}

// The light view distance of a moment depth (momentDepth's inverse: linear in both projections).
SHARED float momentDepthDistance(IN(ShadowViewData) view, float z) {
    float linear = view.moments.x + z * (1.0f - view.moments.x - view.moments.y);
    return view.frustum.x + linear * (view.frustum.y - view.frustum.x);
}

// Moment shadow maps [Peters and Klein 2015], Hamburger reconstruction with four moments: the
// moments b = (E x, E x^2, E x^3, E x^4) of depths in [-1, 1] are first pulled towards
// (0, 0.63, 0, 0.63) by `bias` (the paper's moment bias), which keeps the Hankel matrix
// B = [1 b1 b2; b1 b2 b3; b2 b3 b4] positive definite. The distribution with these moments that
// puts the least weight in front of a receiver at d has three atoms: d and the roots z1 < z2 of
// the quadratic whose coefficients solve B c = (1, d, d^2). Their weights follow from the first
// two moments (Lagrange: w_i = E[(x - z_j)(x - z_k)] / ((z_i - z_j)(z_i - z_k))).
SHARED vec4 biasedMoments(vec4 moments, float bias) {
    return mix(moments, vec4(0.0f, 0.63f, 0.0f, 0.63f), bias);
}

// z1 <= z2 for the biased moments b and receiver d.
SHARED vec2 hamburgerAtoms(vec4 b, float d) {
    // B = L D L^T with L unit lower triangular: solve L y = r, then D L^T c = y.
    float d1 = b.y - b.x * b.x;          // D22 (D11 = 1)
    float l21 = b.x, l31 = b.y;           // first column of L
    float l32 = (b.z - b.x * b.y) / d1;
    float d2 = b.w - b.y * b.y - l32 * l32 * d1; // D33
    vec3 y = vec3(1.0f, d - l21, 0.0f);
    y.z = d * d - l31 - l32 * y.y;
    float c3 = y.z / d2;
    float c2 = y.y / d1 - l32 * c3;
    float c1 = y.x - l21 * c2 - l31 * c3;
    // Roots of c1 + c2 x + c3 x^2 (d is not among them unless B is singular).
    float p = c2 / c3, q = c1 / c3;
    float r = sqrt(max(0.25f * p * p - q, 0.0f));
    return vec2(-0.5f * p - r, -0.5f * p + r);
}

// E[(x - u)(x - v)] over the biased moments b, over (z - u)(z - v): the weight of atom z in a
// three-atom distribution whose other atoms are u and v.
SHARED float atomWeight(vec4 b, float z, float u, float v) {
    return (b.y - b.x * (u + v) + u * v) / ((z - u) * (z - v));
}

// The smallest fraction of the filtered depths in front of the receiver at d: the weight of the
// atoms in front of it.
SHARED float momentOcclusion(vec4 moments, float d, float bias) {
    vec4 b = biasedMoments(moments, bias);
    vec2 z = hamburgerAtoms(b, d);
    if (d <= z.x) return 0.0f;
    if (d <= z.y) return atomWeight(b, z.x, d, z.y); // the atom at z1 is in front
    return 1.0f - atomWeight(b, d, z.x, z.y);       // both in front: all but the receiver's own
}

// Moment soft shadows [Peters et al. 2016]: the blockers the same distribution puts in front of
// d, x their weight and y their weight times their mean depth (the atoms' first moment: with
// both in front, b1 minus the receiver's own atom's share).
SHARED vec2 momentBlockers(vec4 moments, float d, float bias) {
    vec4 b = biasedMoments(moments, bias);
    vec2 z = hamburgerAtoms(b, d);
    if (d <= z.x) return vec2(0.0f);
    if (d <= z.y) {
        float w1 = atomWeight(b, z.x, d, z.y);
        return vec2(w1, w1 * z.x);
    }
    float wd = atomWeight(b, d, z.x, z.y);
    return vec2(1.0f - wd, b.x - wd * d);
}

// msm.precision=16 [Peters and Klein 2015, "optimized moment quantization"]: the moments of
// z = (d + 1) / 2 in [0, 1] under an affine map that spreads them over [0, 1]^4 (the paper's
// matrix; a unit cube's worth of 16-bit steps then resolves what raw powers of z, crowded near
// the diagonal, would not), rounded to 16-bit unorm steps here so that every device stores the
// same values. msmLoad16 undoes it (the inverse matrix, computed and checked in
// tests/test_filter_math.cpp) and returns the moments of d.
SHARED vec4 msmStore16(vec4 dMoments) {
    vec4 b = dMoments; // E d, E d^2, E d^3, E d^4 -> E z^k with z = (d + 1) / 2
    vec4 z = vec4(0.5f * (b.x + 1.0f), 0.25f * (b.y + 2.0f * b.x + 1.0f),
                  0.125f * (b.z + 3.0f * b.y + 3.0f * b.x + 1.0f),
                  0.0625f * (b.w + 4.0f * b.z + 6.0f * b.y + 4.0f * b.x + 1.0f));
    mat4 forward = mat4(-2.07224649f, 13.7948857237f, 0.105877704f, 9.7924062118f,
                        32.23703778f, -59.4683975703f, -1.9077466311f, -33.7652110555f,
                        -68.571074599f, 82.0359750338f, 9.3496555107f, 47.9456096605f,
                        39.3703274134f, -35.364903257f, -6.6543490743f, -23.9728048165f);
    vec4 q = forward * z + vec4(0.035955884801f, 0.0f, 0.0f, 0.0f);
    return floor(clamp(q, 0.0f, 1.0f) * 65535.0f + 0.5f) / 65535.0f;
}

SHARED vec4 msmLoad16(vec4 stored) {
    mat4 inverse = mat4(2.2277441459e-01f, 1.5496792612e-01f, 1.4519889456e-01f, 1.6312744299e-01f,
                        7.7197286078e-02f, 1.3946294265e-01f, 2.1202021568e-01f, 2.5914322664e-01f,
                        7.9269866366e-01f, 7.9634158379e-01f, 7.2586944639e-01f, 6.5390924967e-01f,
                        3.1941755461e-02f, -1.7228231730e-01f, -2.7580148115e-01f, -3.3761317341e-01f);
    vec4 z = inverse * (stored - vec4(0.035955884801f, 0.0f, 0.0f, 0.0f));
    return vec4(2.0f * z.x - 1.0f, 4.0f * z.y - 4.0f * z.x + 1.0f,
                8.0f * z.z - 12.0f * z.y + 6.0f * z.x - 1.0f,
                16.0f * z.w - 32.0f * z.z + 24.0f * z.y - 8.0f * z.x + 1.0f);
}

// The summed-area soft members' blocker search (vssm, msm-soft): momentDepth puts every blocker
// nearer the light than the view's moment range at the range's start, so the search reaches no
// further towards the light than that (a sun's cascade: its receivers' depths, not the scene's).
SHARED float momentSearchRadius(IN(ShadowViewData) view, float zReceiver, uint mapSize) {
    ShadowViewData nearest = view;
    nearest.frustum.x = momentDepthDistance(view, 0.0f);
    return blockerSearchRadius(nearest, zReceiver, mapSize);
}

PENUMBRA_GPU_END

#endif
// clang-format on
