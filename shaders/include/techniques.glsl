// The technique table of the visibility pass: TECHNIQUE (a specialization constant) picks one
// entry; the probe shader used by the parity tests calls the same function.
#ifndef PENUMBRA_TECHNIQUES_GLSL
#define PENUMBRA_TECHNIQUES_GLSL
#include "shadow_hard.glsl"
#include "shadow_pcf.glsl"
#include "shadow_pcss.glsl"
#include "shadow_moments.glsl"
#include "shadow_sat.glsl"

// x: visibility; yzw: intermediate results the parity tests check (PCSS: average blocker depth,
// blocking texels found, filter radius in texels; VSM: the two filtered moments and the
// receiver's moment depth; ESM, EVSM, MSM: see shadow_moments.glsl; SAVSM, VSSM, MSM-soft: see
// shadow_sat.glsl; zero for the others).
// `table`: the technique's map when it holds integers (the summed-area members').
vec4 evaluateTechnique(uint technique, sampler2DArray map, sampler2DArrayShadow mapCompare,
                       usampler2DArray table, Receiver r, uint mapSize, ShadowViewData view,
                       uvec2 pixel) {
    switch (technique) {
    case TECHNIQUE_PCSS: return shadowPcssDetail(map, r, mapSize, view, pixel);
    // Second-depth [Wang and Molnar 1994]: `map` holds the midpoint of the nearest and second
    // nearest depths, so a surface never shadows itself and needs no bias.
    case TECHNIQUE_SECOND_DEPTH: return vec4(shadowHard(map, r, mapSize, vec2(0.0)), vec3(0.0));
    case TECHNIQUE_VSM: return shadowVsmDetail(map, r, mapSize, view);
    case TECHNIQUE_ESM: return shadowEsmDetail(map, r, mapSize, view);
    case TECHNIQUE_EVSM: return shadowEvsmDetail(map, r, mapSize, view);
    case TECHNIQUE_SAVSM: return shadowSavsmDetail(table, r, mapSize, view);
    case TECHNIQUE_MSM: return shadowMsmDetail(map, r, mapSize, view);
    case TECHNIQUE_VSSM: return shadowSoftDetail(table, MOMENTS_VSM, r, mapSize, view);
    case TECHNIQUE_MSM_SOFT: return shadowSoftDetail(table, MOMENTS_MSM, r, mapSize, view);
    case TECHNIQUE_PCF: return vec4(shadowPcf(map, mapCompare, r, mapSize, pixel), vec3(0.0));
    case TECHNIQUE_HARD:
    default: return vec4(shadowHard(map, r, mapSize, frame.biasParams.xy), vec3(0.0));
    }
}

#endif
