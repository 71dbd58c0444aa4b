// Technique `second-depth` [Wang and Molnar 1994]: its map holds the midpoint of the nearest and
// second-nearest depths (shadow_peel.frag, second_depth_mid.comp), so one sample against it
// never shadows the surface that drew the nearest depth, with no bias.
#ifndef PENUMBRA_SHADOW_SECOND_DEPTH_GLSL
#define PENUMBRA_SHADOW_SECOND_DEPTH_GLSL
#include "shadow_hard.glsl"

// No receiver-plane correction: the midpoint lies between two surfaces, on neither's plane.
vec4 evaluateSecondDepth(TechniqueInput at) {
    return vec4(shadowHard(shadowMap, at.r, at.mapSize, vec2(0.0)), vec3(0.0));
}

#endif
