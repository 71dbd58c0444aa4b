// The scalar maths of the shadow filters, written once and compiled twice: as GLSL by the
// shaders (shadow_pcf.glsl, shadow_pcss.glsl, visibility.comp) and as C++ with GLM by the CPU
// references (src/reference/filter_reference.cpp), so both run the same code. A bug written here
// reaches both sides at once: the parity tests cannot see it, the closed-form tests
// (tests/test_filter_closed_forms.cpp) and the ground truth can.
// Rules for both languages: float literals carry an f, conversions are explicit, `OUT(T)` and
// `OUT_ARRAY(T, name, n)` mark out parameters, `INOUT(T)` in-out ones, `IN(T)` passes a struct
// (by value in GLSL, by
// reference in C++).
// clang-format off
#ifndef PENUMBRA_FILTER_MATH_H
#define PENUMBRA_FILTER_MATH_H
#include "gpu_types.h"

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace penumbra::gpu {
using glm::ivec2;
using glm::ivec4;
using glm::uvec4;
using glm::vec4;
using glm::uvec2;
using glm::vec2;
using glm::vec3;
using glm::abs;
using glm::asin;
using glm::ceil;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::floor;
using glm::fract;
using glm::length;
using glm::log2;
using glm::max;
using glm::min;
using glm::mix;
using glm::sin;
using glm::sqrt;
#define OUT(T) T&
#define INOUT(T) T&
#define OUT_ARRAY(T, name, n) T (&name)[n]
#define IN(T) const T&
#define SHARED inline
#else
#define OUT(T) out T
#define INOUT(T) inout T
#define OUT_ARRAY(T, name, n) out T name[n]
#define IN(T) T
#define SHARED
#endif

#define PCF_MAX_SIZE 15
#define VSSM_MAX_SUBDIVISION 4    // vssm.subdivision's and msm-soft.subdivision's largest value
#define VSSM_NO_BLOCKERS 1e-4f    // a blocking fraction at most this: nothing in the way
#define VSSM_MIN_CELL 2.0f        // texels: no sub-kernel is cut narrower
// The half-width of the box with the variance of a disc of unit radius (sqrt(3) / 2): the box
// the summed-area members filter a penumbra of radius r over is this times r.
#define VSSM_BOX_PER_RADIUS 0.8660254f

// The comparison of one texel [Williams 1978]: lit (1) when the receiver's depth, corrected by
// receiver-plane bias to the texel's centre (`offset` = texel centre - receiver, in uv), lies at or
// in front of the stored depth. The correction is clamped to `dzRange`.
SHARED float receiverDepthAt(float depth, vec2 gradient, vec2 offset, vec2 dzRange) {
    return depth + clamp(dot(gradient, offset), dzRange.x, dzRange.y);
}

SHARED float depthTest(float receiver, float stored) { return receiver <= stored ? 1.0f : 0.0f; }

// A tap's reference depth under bias.mode=adaptive [Dou et al. 2014]: the receiver-plane depth
// at the texel's centre (the paper's adaptive offset, for every tap of a kernel), its correction
// clamped to dzRange, lifted towards the light by what the surface's curvature can bring within
// the tap's distance |offset| (uv): min(curve.x |offset|^2, curve.y |offset|), light depth (see
// adaptiveBiasTerms). curve = 0 leaves receiverDepthAt's value.
SHARED float tapDepth(float depth, vec2 gradient, vec2 offset, vec2 dzRange, vec2 curve) {
    float s2 = dot(offset, offset);
    return receiverDepthAt(depth, gradient, offset, dzRange) -
           min(curve.x * s2, curve.y * sqrt(s2));
}

// A comparison tap of the texture unit (pcf.filter=hardware) tests its four texels against one
// depth: under bias.mode=adaptive the receiver comes nearer the light by its plane's largest rise
// over the tap's footprint (texel centres within a texel of it on each axis, `size` texels per
// uv), at most `limit` (bias.receiverClamp): the receiver's own slope-scaled bias.
SHARED float footprintLift(vec2 gradient, float size, float limit) {
    return min((abs(gradient.x) + abs(gradient.y)) / size, limit);
}

// The per-receiver terms of bias.mode=adaptive, from the receiver's geometry: texelWorld, a
// shadow-map texel's world size at the receiver (across the light's rays); mapSize, texels per
// uv; depthPerWorld, the light depth's change per world unit along the ray; cosine, N.L of the
// receiver's own triangle; curvature, how fast the surface's normal turns (radians per world
// unit; 0: flat); epsilonTexels (bias.adaptive) and curvatureScale (bias.curvature); gradient,
// the receiver plane's |d depth / d uv|. Returns x: the constant lift (light depth), the
// paper's adaptive epsilon, here a fraction of a texel's footprint along the ray (texelWorld /
// cosine) so that it scales with the map's resolution and the surface's slope; yz: curve for
// tapDepth: a surface of curvature k leaves its tangent plane by k L^2 / 2 over a distance L
// along it, L = s / cosine for a distance s across the rays, which the ray sees stretched by
// 1 / cosine again (y, per uv^2), never more than the tap's own distance across the rays (z, per
// uv: a 45-degree bound); w: the plane's reach, how far its correction is trusted (|gradient|
// times the distance across the rays where the surface has turned by one radian,
// cosine / curvature), the clamp that adapts to curvature (1e30: flat). curvatureScale scales
// the curvature in both.
SHARED vec4 adaptiveBiasTerms(float texelWorld, float mapSize, float depthPerWorld, float cosine,
                              float curvature, float epsilonTexels, float curvatureScale,
                              float gradient) {
    float c = clamp(cosine, 0.05f, 1.0f);
    float worldPerUv = texelWorld * mapSize;
    float lift = depthPerWorld * epsilonTexels * texelWorld / c;
    float k = curvature * curvatureScale;
    float curve = 0.5f * depthPerWorld * k * worldPerUv * worldPerUv / (c * c * c);
    float cap = depthPerWorld * worldPerUv;
    float reach = k > 0.0f ? gradient * c / (k * worldPerUv) : 1e30f;
    return vec4(lift, curve, cap, reach);
}

// A bilinear comparison tap from its four tests in textureGather order (x (i, j+1), y (i+1, j+1),
// z (i+1, j), w (i, j)) and the tap's sub-texel fraction.
SHARED float bilinearMix(vec4 t, vec2 f) {
    return mix(mix(t.w, t.z, f.x), mix(t.x, t.y, f.x), f.y);
}

// Texel weights of an n-tap kernel (box: 1/n; Gaussian with sigma, normalised) after bilinear
// taps with sub-texel fraction f: texel k of the (n+1)-wide footprint gets
// c(k) = g(k)(1 - f) + g(k-1) f.
SHARED void footprintWeights(uint filterKind, int n, float sigma, float f,
                             OUT_ARRAY(float, c, PCF_MAX_SIZE + 1)) {
    float g[PCF_MAX_SIZE];
    float h = 0.5f * float(n - 1), sum = 0.0f;
    for (int i = 0; i < n; ++i) {
        float x = float(i) - h;
        g[i] = filterKind == FILTER_GAUSSIAN ? exp(-0.5f * x * x / (sigma * sigma)) : 1.0f;
        sum += g[i];
    }
    for (int k = 0; k <= n; ++k)
        c[k] = ((k < n ? g[k] : 0.0f) * (1.0f - f) + (k > 0 ? g[k - 1] : 0.0f) * f) / sum;
}

SHARED uint hashU32(uint v) { // lowbias32, a public-domain integer hash
    v ^= v >> 16u;
    v *= 0x7feb352du;
    v ^= v >> 15u;
    v *= 0x846ca68bu;
    v ^= v >> 16u;
    return v;
}

// Per-pixel rotation of a Poisson disk, in turns [0, 1): none, a hash, or interleaved gradient
// noise [Jimenez 2014].
SHARED float rotationTurns(uint rotation, uvec2 pixel) {
    if (rotation == ROTATION_RANDOM)
        return float(hashU32(pixel.x * 0x9E3779B9u ^ hashU32(pixel.y))) * (1.0f / 4294967296.0f);
    if (rotation == ROTATION_IGN)
        return fract(52.9829189f * fract(0.06711056f * float(pixel.x) + 0.00583715f * float(pixel.y)));
    return 0.0f;
}

// `d` rotated by `turns` of a full turn, scaled by `radius`.
SHARED vec2 rotatedOffset(vec2 d, float turns, float radius) {
    float angle = 6.28318530718f * turns;
    float c = cos(angle), s = sin(angle);
    return radius * vec2(c * d.x - s * d.y, s * d.x + c * d.y);
}

// An n x n kernel (n odd) set in texels of a sun's first cascade, in a cascade whose texels are
// 1/scale times as wide (scale <= 1): the odd size nearest n x scale, at least 1, so the kernel
// keeps its world size.
SHARED int scaledKernelSize(uint n, float scale) {
    if (scale >= 1.0f) return int(n);
    int k = 2 * int(floor(0.5f * (float(n) * scale - 1.0f) + 0.5f)) + 1;
    return k < 1 ? 1 : k;
}

// How much of the next cascade a pixel at camera view distance z takes, in a cascade whose slice
// ends at `splitFar` and starts blending at `blendStart`: 0 up to the band, rising linearly to 1
// at the split, where the next cascade alone takes over (no seam on either side of the band).
SHARED float cascadeBlendWeight(float z, float blendStart, float splitFar) {
    return splitFar > blendStart ? clamp((z - blendStart) / (splitFar - blendStart), 0.0f, 1.0f)
                                 : (z > splitFar ? 1.0f : 0.0f);
}

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

// Weight of tap k (-(n-1)/2 .. (n-1)/2) of the n-tap Gaussian blur, before normalising: sigma
// = n / 6, so the taps reach three sigmas on either side.
SHARED float gaussianTap(int k, int n) {
    float sigma = max(float(n) / 6.0f, 0.3f);
    return exp(-0.5f * float(k * k) / (sigma * sigma));
}

// The G-buffer keeps two unit normals in one RGBA16F texel, each folded onto the octahedron
// |x| + |y| + |z| = 1 and its lower half unfolded over the corners [Cigolle et al. 2014].
// The lower half's fold, its own inverse: a point of the inner diamond to the corner beyond the
// edge facing it, and back.
SHARED vec2 octahedralFold(vec2 p) {
    return vec2((1.0f - abs(p.y)) * (p.x >= 0.0f ? 1.0f : -1.0f),
                (1.0f - abs(p.x)) * (p.y >= 0.0f ? 1.0f : -1.0f));
}

SHARED vec2 octahedralEncode(vec3 n) {
    vec2 p = vec2(n.x, n.y) / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z >= 0.0f ? p : octahedralFold(p);
}

SHARED vec3 octahedralDecode(vec2 e) {
    float z = 1.0f - abs(e.x) - abs(e.y);
    vec2 p = z >= 0.0f ? e : octahedralFold(e);
    vec3 n = vec3(p.x, p.y, z);
    return n / sqrt(dot(n, n));
}

// The part of a unit disc on one side of a straight edge at signed distance x from its centre
// (positive: the centre is uncovered): 1/2 + (x sqrt(1 - x^2) + asin x) / pi, clamped to [-1, 1].
SHARED float discFraction(float x) {
    x = clamp(x, -1.0f, 1.0f);
    return 0.5f + (x * sqrt(1.0f - x * x) + asin(x)) / 3.14159265f;
}

// bias.horizon: the part of a light of angular radius a (sin a = sinRadius) above a receiver's
// tangent plane, its centre at elevation h over it (sin h = N.L): the segment of a disc of radius
// a cut at distance h from its centre (a small light's disc, seen flat). The surface hides the
// rest itself, which no shadow map holds. 1 for a point-like light.
SHARED float horizonVisibility(float nDotL, float sinRadius) {
    if (sinRadius <= 0.0f) return 1.0f;
    return discFraction(asin(clamp(nDotL, -1.0f, 1.0f)) / asin(min(sinRadius, 1.0f)));
}

// A receiver that faces away from the light (N.L <= 0, N its triangle's own normal) hides the
// light itself: 0 for a point-like light, else the part of the light's disc still above its
// tangent plane. One convention for render and reference (the truth counts every ray under the
// surface as blocked), whatever a shadow map says there; 1 where the receiver faces the light.
SHARED float backFacingVisibility(float nDotL, float sinRadius) {
    if (nDotL > 0.0f) return 1.0f;
    return sinRadius <= 0.0f ? 0.0f : horizonVisibility(nDotL, sinRadius);
}

// The face of a point light's cube that holds direction `d` from the light: its major axis, in
// the order of src/core/light_space.h (+x, -x, +y, -y, +z, -z). Ties go to the earlier axis;
// the faces' guard bands make either choice correct.
SHARED uint cubeFace(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0u : 1u;
    if (a.y >= a.z) return d.y >= 0.0f ? 2u : 3u;
    return d.z >= 0.0f ? 4u : 5u;
}

// Weighted sums of exact 0/1 tests land within float round-off of 0 or 1 when every test agrees;
// fully lit must read exactly 1 (and fully shadowed 0), so round-off snaps.
SHARED float snapToExtremes(float v) { return v >= 0.99999f ? 1.0f : (v <= 0.00001f ? 0.0f : v); }

// PCSS [Fernando 2005; seed 001] geometry of one shadow view (docs/techniques.md). Light view
// distance of a normalised light depth (inverse of the seeds' depth mappings).
SHARED float viewDistance(IN(ShadowViewData) view, float depth) {
    float n = view.frustum.x, f = view.frustum.y;
    return view.texel.y > 0.5f ? n * f / (f - depth * (f - n)) : n + depth * (f - n);
}

// Texels per world unit laterally at view distance z (u axis).
SHARED float texelsPerWorld(IN(ShadowViewData) view, float z, uint mapSize) {
    float worldPerUv = view.frustum.z * (view.texel.y > 0.5f ? z : 1.0f);
    return float(mapSize) / worldPerUv;
}

// Search radius (texels): the light seen from the receiver, cut by the near plane, where the
// nearest possible blocker lies. Perspective: R (z_r - n) / z_r at the near plane;
// orthographic: (z_r - n) tan(half angle).
SHARED float blockerSearchRadius(IN(ShadowViewData) view, float zReceiver, uint mapSize) {
    float n = view.frustum.x, size = view.texel.w;
    float world = view.texel.y > 0.5f ? size * (zReceiver - n) / zReceiver : (zReceiver - n) * size;
    return world * texelsPerWorld(view, view.texel.y > 0.5f ? n : 1.0f, mapSize);
}

// The summed-area soft members' blocker search (vssm, msm-soft): momentDepth puts every blocker
// nearer the light than the view's moment range at the range's start, so the search reaches no
// further towards the light than that (a sun's cascade: its receivers' depths, not the scene's).
SHARED float momentSearchRadius(IN(ShadowViewData) view, float zReceiver, uint mapSize) {
    ShadowViewData nearest = view;
    nearest.frustum.x = momentDepthDistance(view, 0.0f);
    return blockerSearchRadius(nearest, zReceiver, mapSize);
}

// Penumbra radius (texels at the receiver): perspective, the seed's
// w = (d_receiver - d_blocker) w_light / d_blocker with distances along the light; orthographic,
// (z_r - z_b) tan(half angle).
SHARED float penumbraRadius(IN(ShadowViewData) view, float zReceiver, float zBlocker, uint mapSize) {
    float size = view.texel.w;
    float world = view.texel.y > 0.5f ? (zReceiver - zBlocker) * size / zBlocker
                                      : (zReceiver - zBlocker) * size;
    return world * texelsPerWorld(view, zReceiver, mapSize);
}

// Receiver-plane depth bias [Tuft 2010; seed 000]: the receiver's light depth as a linear function
// of shadow-map (u, v) on its tangent plane. `light`: from the surface normal. The three rows of
// d(u, v, depth)/d(world) at `world` for the projective map S; the plane's normal in (u, v, depth)
// space is J^-T N, and J^-T is the cofactor matrix of J over det J (see techniques.md).
SHARED vec2 receiverGradientFromNormal(IN(mat4) S, vec3 world, vec3 normal) {
    vec4 s = S * vec4(world, 1.0f);
    vec3 rowW = vec3(S[0][3], S[1][3], S[2][3]);
    vec3 du = (vec3(S[0][0], S[1][0], S[2][0]) - (s.x / s.w) * rowW) / s.w;
    vec3 dv = (vec3(S[0][1], S[1][1], S[2][1]) - (s.y / s.w) * rowW) / s.w;
    vec3 dz = (vec3(S[0][2], S[1][2], S[2][2]) - (s.z / s.w) * rowW) / s.w;
    float nu = dot(cross(dv, dz), normal);
    float nv = dot(cross(dz, du), normal);
    float nz = dot(cross(du, dv), normal);
    if (abs(nz) <= 1e-6f * (abs(nu) + abs(nv))) return vec2(0.0f); // edge-on to the light
    return vec2(-nu, -nv) / nz;
}

// The world-space gradient of the light depth of the projective map S at `world`.
SHARED vec3 lightDepthGradient(IN(mat4) S, vec3 world) {
    vec4 s = S * vec4(world, 1.0f);
    vec3 rowW = vec3(S[0][3], S[1][3], S[2][3]);
    return (vec3(S[0][2], S[1][2], S[2][2]) - (s.z / s.w) * rowW) / s.w;
}

// `screen`: from the light-space offsets to two neighbouring pixels (seed 000's 2x2 solve):
// [dz/du, dz/dv] = [dz/dx, dz/dy] [[du/dx, dv/dx], [du/dy, dv/dy]]^-1.
SHARED vec2 receiverGradientFromOffsets(vec3 alongX, vec3 alongY) {
    float det = alongX.x * alongY.y - alongX.y * alongY.x;
    if (abs(det) < 1e-20f) return vec2(0.0f);
    return vec2(alongX.z * alongY.y - alongY.z * alongX.y,
                alongX.x * alongY.z - alongY.x * alongX.z) / det;
}

#ifdef __cplusplus
} // namespace penumbra::gpu
#endif
#undef SHARED
#endif
// clang-format on
