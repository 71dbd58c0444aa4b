// The summed-area members of the prefiltered family: `savsm` [Lauritzen 2007, GPU Gems 3 ch. 8],
// `vssm` [Yang et al. 2010] and `msm-soft` [Peters et al. 2016] read a table of fixed-point
// moments that shaders/include/sat_scan.glsl builds, as exact box means of any size at a
// constant cost. The CPU mirrors are in
// src/shadows/savsm.cpp, vssm.cpp and msm_soft.cpp (src/shadows/cpu_tables.cpp: the table); the derivations are in docs/techniques.md.
#ifndef PENUMBRA_SHADOW_SAT_GLSL
#define PENUMBRA_SHADOW_SAT_GLSL
#include "kernels.h"
#include "bias.h"
#include "light_geometry.h"
#include "moments.h"
#include "params_tables.h"
#include "technique_input.glsl"

// The table's sum up to integer corner c: texel c - 1 (0 along the first row and column).
uvec4 tableCorner(usampler2DArray table, ivec2 c, float layer) {
    if (c.x <= 0 || c.y <= 0) return uvec4(0u);
    return texelFetch(table, ivec3(c - 1, int(layer)), 0);
}

// The exact sum (in steps) of the table's texels over [lo, hi] (texel units, inside the map),
// fractional edges included: the sum is linear in each edge within a texel, so it is the
// integer boxes between the corners either side of each edge, weighted by where the edge falls
// between them, each box exact (boxFromCorners) before it is weighted.
vec4 tableBoxSum(usampler2DArray table, vec2 lo, vec2 hi, int size, float layer) {
    ivec2 a = min(ivec2(floor(lo)), ivec2(size - 1)), b = min(ivec2(floor(hi)), ivec2(size - 1));
    vec2 fa = lo - vec2(a), fb = hi - vec2(b);
    ivec4 xs = ivec4(a.x, a.x + 1, b.x, b.x + 1), ys = ivec4(a.y, a.y + 1, b.y, b.y + 1);
    vec4 wx = vec4(1.0 - fa.x, fa.x, 1.0 - fb.x, fb.x), wy = vec4(1.0 - fa.y, fa.y, 1.0 - fb.y, fb.y);
    uvec4 c[4][4]; // c[row y][column x]
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) c[j][i] = tableCorner(table, ivec2(xs[i], ys[j]), layer);
    vec4 sum = vec4(0.0);
    for (int y0 = 0; y0 < 2; ++y0)
        for (int y1 = 2; y1 < 4; ++y1)
            for (int x0 = 0; x0 < 2; ++x0)
                for (int x1 = 2; x1 < 4; ++x1)
                    sum += wy[y0] * wy[y1] * wx[x0] * wx[x1] *
                           boxFromCorners(c[y0][x0], c[y0][x1], c[y1][x0], c[y1][x1]);
    return sum;
}

// The mean moments over [lo, hi] of a table of `kind` (MOMENTS_*) quantised with `scale`.
vec4 tableBoxMean(usampler2DArray table, uint kind, float scale, vec2 lo, vec2 hi, int size,
                  float layer) {
    float area = max((hi.x - lo.x) * (hi.y - lo.y), 1e-6);
    return tableMean(kind, tableBoxSum(table, lo, hi, size, layer) / area, scale);
}

// The box of half-width `reach` texels around the receiver, cut to the map.
void satBox(Receiver r, float reach, float size, out vec2 lo, out vec2 hi) {
    vec2 p = r.uv * size;
    lo = clamp(p - reach, vec2(0.0), vec2(size));
    hi = clamp(p + reach, vec2(0.0), vec2(size));
}

// x visibility, y z the box's mean offset moments, w the receiver's offset moment depth. The box
// is savsm.size texels wide (of a sun's first cascade, scaled in the others), centred on the
// receiver, cut to the map (averaged over the part inside).
vec4 shadowSavsmDetail(usampler2DArray table, Receiver r, uint mapSize, ShadowViewData view) {
    vec2 lo, hi;
    satBox(r, 0.5 * max(savsm.size * r.kernelScale, 1.0), float(mapSize), lo, hi);
    vec2 moments = tableBoxMean(table, MOMENTS_VSM, savsm.tableScale, lo, hi, int(mapSize),
                                r.layer).xy;
    float t = momentDepth(view, r.depth) - 0.5;
    float v = chebyshevUpperBound(moments, t, savsm.minVariance);
    return vec4(snapToExtremes(reduceLightBleeding(v, savsm.bleedReduction)), moments, t);
}

// The receiver's depth at texel position c as `kind`'s table holds depths (MOMENTS_VSM: offset
// moment depth; MOMENTS_MSM: in [-1, 1]), on its plane (bias.receiver), so that a sub-kernel off
// the receiver's centre compares with the surface there, not with a tilted receiver's centre
// (which would shadow the half of a slope nearer the light). bias.receiverSides applies, not
// bias.receiverClamp: sub-kernels lie tens of texels out, where a slope seen at a grazing angle
// runs far past the clamp, and a clamped plane would read as a blocker.
float planeTableDepth(uint kind, Receiver r, ShadowViewData view, vec2 c, float size) {
    vec2 sides = vec2(-1e30, frame.biasParams.y > 0.0 ? 1e30 : 0.0);
    float z = momentDepth(view, receiverDepthAt(r.depth, r.gradient, c / size - r.uv, sides));
    return kind == MOMENTS_MSM ? 2.0 * z - 1.0 : z - 0.5;
}

// The receiver's plane over the cell [from, to] (texels) as `kind`'s table holds depths: x its
// mean, y its mean square, by Gauss-Legendre quadrature (2 x 2 points, exact for a cubic; 3 x 3
// moved no corpus figure). Under a spot's perspective a plane in the map's depth is not one in
// the moments' linear depth (1 / (a + b v) across a grazing floor), so it is sampled, not
// taken from the gradient alone.
vec2 planeCellMoments(uint kind, Receiver r, ShadowViewData view, vec2 from, vec2 to, float size) {
    vec2 c = 0.5 * (from + to), h = (0.5 / sqrt(3.0)) * (to - from), sum = vec2(0.0);
    for (int j = -1; j <= 1; j += 2)
        for (int i = -1; i <= 1; i += 2) {
            float z = planeTableDepth(kind, r, view, c + h * vec2(i, j), size);
            sum += 0.25 * vec2(z, z * z);
        }
    return sum;
}

// The summed-area soft members' settings: vssm (MOMENTS_VSM) or msm-soft (MOMENTS_MSM).
struct SoftSettings {
    uint kind;
    float cap, scale;
    int subdivision;
    bool refine;
};

SoftSettings softSettings(uint kind, ShadowViewData view) {
    return kind == MOMENTS_MSM
               ? SoftSettings(kind, kernelCap(view, msmSoft.maxRadius, msmSoft.cubeRadius),
                              msmSoft.tableScale, int(msmSoft.subdivision), msmSoft.refine != 0u)
               : SoftSettings(kind, kernelCap(view, vssm.maxRadius, vssm.cubeRadius),
                              vssm.tableScale, int(vssm.subdivision), vssm.refine != 0u);
}

// The box [lo, hi] cut into up to subdivision^2 sub-kernels (none under VSSM_MIN_CELL texels
// wide: Yang et al.'s answer to non-planar receivers), each compared with the receiver's plane at
// its centre and weighted by its area. search: x the blocking weight (chebyshevBlockers or
// momentBlockers), y the blocking weight times the blockers' depth, z the area; else x the
// visibility times the area, z the area.
vec3 softKernel(usampler2DArray table, SoftSettings s, Receiver r, ShadowViewData view, vec2 lo,
                vec2 hi, float size, bool search) {
    ivec2 cells = clamp(ivec2((hi - lo) / VSSM_MIN_CELL), ivec2(1), ivec2(s.subdivision));
    vec2 cell = (hi - lo) / vec2(cells);
    vec3 total = vec3(0.0);
    for (int j = 0; j < cells.y; ++j)
        for (int i = 0; i < cells.x; ++i) {
            vec2 from = lo + vec2(i, j) * cell;
            vec2 to = vec2(i + 1 == cells.x ? hi.x : from.x + cell.x,
                           j + 1 == cells.y ? hi.y : from.y + cell.y);
            vec4 moments = tableBoxMean(table, s.kind, s.scale, from, to, int(size), r.layer);
            float t = planeTableDepth(s.kind, r, view, 0.5 * (from + to), size);
            vec2 result;
            if (s.kind == MOMENTS_MSM) {
                float bias = msmSoft.momentBias;
                result = search ? momentBlockers(moments, t, bias)
                                : vec2(clamp(1.0 - momentOcclusion(moments, t, bias), 0.0, 1.0), 0.0);
            } else {
                float minVariance = vssm.minVariance;
                // The receiver's own spread is no evidence of a blocker (withoutReceiverSpread).
                vec2 m = withoutReceiverSpread(moments.xy,
                                               planeCellMoments(s.kind, r, view, from, to, size));
                result = search ? chebyshevBlockers(m, t, minVariance)
                                : vec2(reduceLightBleeding(chebyshevUpperBound(m, t,
                                                                               minVariance),
                                                           vssm.bleedReduction),
                                       0.0);
            }
            total += vec3(result, 1.0) * (cell.x * cell.y);
        }
    return total;
}

// The light view distance of a search's average blocker (not nearer than the near plane).
float softBlockerDistance(uint kind, vec3 found, ShadowViewData view) {
    float z = found.y / found.x;
    return max(momentDepthDistance(view, kind == MOMENTS_MSM ? 0.5 * z + 0.5 : z + 0.5),
               view.frustum.x);
}

// x visibility, y the average blocker's depth as the table holds depths (1: none found), z the
// blocking fraction of the last search, w the filter's radius (texels). PCSS's three steps
// [Fernando 2005] on a summed-area table, each at a constant cost whatever the light's size:
// a blocker search over the light's extent (PCSS's search radius, as a box), the average blocker
// depth from the moments, the penumbra from similar triangles, then the filter over a box of
// that width. Where the light's box finds no blocker, a box of VSSM_NARROW_SEARCH texels
// searches again: a blocker seen edge-on (a ramp under a low spot) spreads its depths over a wide
// box so far that Chebyshev's bound reads it as light, while the texels next to the receiver
// still say it is hidden. `refine` searches again over the penumbra's box (VSSM_REFINE_STEPS
// times): blockers at the estimated depth hide part of the light only from within it (at a
// blocker's depth, the search region is its penumbra's), so far-off blockers do not widen the
// estimate; the narrowest penumbra is kept (an estimate nearer the light comes from fewer
// blockers, and Chebyshev's bias towards the light is then what widens it). vssm [Yang et al. 2010] bounds
// with Chebyshev; msm-soft [Peters et al. 2016] with the Hamburger reconstruction.
vec4 shadowSoftDetail(usampler2DArray table, uint kind, Receiver r, uint mapSize,
                      ShadowViewData view) {
    SoftSettings s = softSettings(kind, view);
    float size = float(mapSize);
    float zReceiver = viewDistance(view, r.depth);
    vec2 lo, hi;
    satBox(r, clamp(momentSearchRadius(view, zReceiver, mapSize), 0.5, s.cap), size, lo, hi);
    vec3 found = softKernel(table, s, r, view, lo, hi, size, true);
    if (found.x <= VSSM_NO_BLOCKERS * found.z) {
        satBox(r, VSSM_NARROW_SEARCH, size, lo, hi);
        found = softKernel(table, s, r, view, lo, hi, size, true);
    }
    if (found.x <= VSSM_NO_BLOCKERS * found.z) return vec4(1.0, 1.0, 0.0, 0.0);
    float radius = penumbraRadius(view, zReceiver, softBlockerDistance(kind, found, view), mapSize);
    for (int step = 0; step < (s.refine ? VSSM_REFINE_STEPS : 0); ++step) {
        satBox(r, VSSM_BOX_PER_RADIUS * clamp(radius, 0.5, s.cap), size, lo, hi);
        found = softKernel(table, s, r, view, lo, hi, size, true);
        if (found.x <= VSSM_NO_BLOCKERS * found.z) return vec4(1.0, 1.0, 0.0, 0.0);
        radius = min(radius, penumbraRadius(view, zReceiver, softBlockerDistance(kind, found, view),
                                            mapSize));
    }
    radius = clamp(radius, 0.5, s.cap);
    satBox(r, VSSM_BOX_PER_RADIUS * radius, size, lo, hi);
    vec3 lit = softKernel(table, s, r, view, lo, hi, size, false);
    return vec4(snapToExtremes(lit.x / max(lit.z, 1e-6)), found.y / found.x, found.x / found.z,
                radius);
}

vec4 evaluateSavsm(TechniqueInput at) {
    return shadowSavsmDetail(shadowTable, at.r, at.mapSize, at.view);
}
vec4 evaluateVssm(TechniqueInput at) {
    return shadowSoftDetail(shadowTable, MOMENTS_VSM, at.r, at.mapSize, at.view);
}
vec4 evaluateMsmSoft(TechniqueInput at) {
    return shadowSoftDetail(shadowTable, MOMENTS_MSM, at.r, at.mapSize, at.view);
}

#endif
