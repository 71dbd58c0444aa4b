// An edge-aware spatial filter of a light's visibility (a technique's noise: smrt's few rays per
// pixel, each pixel's ray set turned its own way), compiled as GLSL and as C++ (the CPU
// reference, src/shadows/visibility_filter.cpp). Separable: along the image's rows into a scratch
// layer, then along its columns back. A neighbour counts by a tent over its offset, times how
// well it continues the pixel's surface (its distance from the pixel's tangent plane against
// its distance, and its normal), times how near its visibility lies to the pixel's: a hard edge
// (a step of more than `tolerance`) stays sharp, the noise of a wide penumbra averages out.
// Every factor is continuous, so that the GPU and its mirror agree to rounding.
// clang-format off
#ifndef PENUMBRA_VISIBILITY_FILTER_WEIGHTS_H
#define PENUMBRA_VISIBILITY_FILTER_WEIGHTS_H
#include "shared_prelude.h"

PENUMBRA_GPU_BEGIN

// How far from the tangent plane (relative to its distance) a neighbour still continues the
// surface (a kink of about 6 degrees), and how far its normal may turn (cos 37 degrees).
#define FILTER_PLANE_SLOPE 0.1f
#define FILTER_NORMAL_COS 0.8f

// The weight of neighbour q (world position, unit normal m, visibility vq) `offset` pixels from
// pixel p (n, vp) along the pass's axis, for a filter of `radius` pixels.
SHARED float visibilityFilterWeight(vec3 p, vec3 n, float vp, vec3 q, vec3 m, float vq, int offset,
                                    int radius, float tolerance) {
    float tent = float(radius + 1 - abs(offset));
    vec3 d = q - p;
    float plane = max(1.0f - abs(dot(n, d)) / (FILTER_PLANE_SLOPE * length(d) + 1e-12f), 0.0f);
    float facing = clamp((dot(n, m) - FILTER_NORMAL_COS) / (1.0f - FILTER_NORMAL_COS), 0.0f, 1.0f);
    float range = max(1.0f - abs(vq - vp) / tolerance, 0.0f);
    return tent * plane * facing * range;
}

// A visibility inside a penumbra, not settled at 0 or 1: a wide penumbra's pixels widen the filter
// while every neighbour out to the radius is one too (smrt.filterWide). The margin keeps a
// settled pixel's filtered value, which a GPU's division may leave an ulp off 0 or 1, settled;
// a ray's fraction is 1/64 or more away.
SHARED bool visibilityFilterInPenumbra(float v) { return v > 1e-3f && v < 1.0f - 1e-3f; }

PENUMBRA_GPU_END

#endif
// clang-format on
