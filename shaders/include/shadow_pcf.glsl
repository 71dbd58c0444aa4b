// Technique `pcf`: percentage-closer filtering [Reeves et al. 1987] and its variants, every
// kernel built from bilinear comparison taps (receiver.glsl); edge-only PCF [Isidoro 2006]. The
// kernel is pcf's own specialization constant FILTER (== pcf.kernel), so each compiles alone: a
// runtime switch over every kernel made even the simplest one 2x slower on lavapipe. The CPU
// mirror is src/shadows/pcf.cpp.
#ifndef PENUMBRA_SHADOW_PCF_GLSL
#define PENUMBRA_SHADOW_PCF_GLSL
#include "params_pcf.h"
#include "technique_input.glsl"
layout(constant_id = SPEC_FILTER) const uint FILTER = FILTER_BOX;

float pcfPoisson(sampler2DArray map, Receiver r, uint mapSize, uvec2 pixel, vec2 dzRange) {
    return poissonTaps(map, r, mapSize, pcf.samples, pcf.radius * r.kernelScale,
                       turnedByFrame(rotationTurns(pcf.rotation, pixel), frame.motion.y),
                       dzRange);
}

// [Isidoro 2006] edge-only PCF: four taps at the kernel's corners; when they agree fully
// (all lit or all shadowed) the pixel is taken to be away from any edge.
bool pcfProbeDecides(sampler2DArray map, Receiver r, uint mapSize, vec2 dzRange, out float result) {
    float reach = FILTER == FILTER_POISSON
                      ? pcf.radius * r.kernelScale * 0.70710678
                      : 0.5 * float(scaledKernelSize(pcf.size, r.kernelScale) - 1);
    vec2 centre = r.uv * float(mapSize);
    float sum = bilinearTap(map, centre + vec2(-reach, -reach), float(mapSize), r, dzRange) +
                bilinearTap(map, centre + vec2(reach, -reach), float(mapSize), r, dzRange) +
                bilinearTap(map, centre + vec2(-reach, reach), float(mapSize), r, dzRange) +
                bilinearTap(map, centre + vec2(reach, reach), float(mapSize), r, dzRange);
    result = sum * 0.25;
    return sum == 0.0 || sum == 4.0;
}

float shadowPcfUnsnapped(sampler2DArray map, sampler2DArrayShadow mapCompare, Receiver r, uint mapSize,
                         uvec2 pixel) {
    const uint filterKind = FILTER;
    vec2 dzRange = frame.biasParams.xy;
    if (filterKind == FILTER_HARDWARE) {
        // One comparison-sampler tap (SampleCmpLevelZero). Without linear depth filtering
        // (lavapipe) the same bilinear comparison is done by hand.
        // A comparison sampler compares every texel with one reference depth, so receiver-plane
        // bias cannot apply per texel here (nor the adaptive mode's per-tap lift: it lifts the
        // receiver by its plane's rise over the footprint instead); the by-hand version does the
        // same.
        float lift = frame.biasMode.w == BIAS_ADAPTIVE
                         ? footprintLift(r.gradient, float(mapSize), -dzRange.x)
                         : 0.0;
        if (frame.biasMode.y != 0u)
            return texture(mapCompare, vec4(r.uv, r.layer, r.depth - lift));
        Receiver noPlane = r;
        noPlane.depth -= lift;
        noPlane.gradient = vec2(0.0);
        noPlane.curve = vec2(0.0);
        noPlane.creaseLimit = 0.0; // one reference depth for all four texels: no plane of theirs
        return bilinearTap(map, r.uv * float(mapSize), float(mapSize), noPlane, dzRange);
    }
    float early;
    if (pcf.edgeOnly != 0u && filterKind != FILTER_BILINEAR &&
        pcfProbeDecides(map, r, mapSize, dzRange, early))
        return early;
    if (filterKind == FILTER_POISSON) return pcfPoisson(map, r, mapSize, pixel, dzRange);
    int n = filterKind == FILTER_BILINEAR ? 1 : scaledKernelSize(pcf.size, r.kernelScale);
    return pcfGrid(map, r, mapSize, filterKind, n, pcf.sigma * r.kernelScale, dzRange);
}

float shadowPcf(sampler2DArray map, sampler2DArrayShadow mapCompare, Receiver r, uint mapSize, uvec2 pixel) {
    return snapToExtremes(shadowPcfUnsnapped(map, mapCompare, r, mapSize, pixel));
}

vec4 evaluatePcf(TechniqueInput at) {
    return vec4(shadowPcf(shadowMap, shadowMapCmp, at.r, at.mapSize, at.pixel), vec3(0.0));
}

#endif
