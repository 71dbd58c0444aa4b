// Technique `hard` [Williams 1978]: one nearest-texel sample; lit when d(p) <= s(p), the depth
// taken at the texel's centre when receiver-plane bias is on.
#ifndef PENUMBRA_SHADOW_HARD_GLSL
#define PENUMBRA_SHADOW_HARD_GLSL
#include "technique_input.glsl"

float shadowHard(sampler2DArray map, Receiver r, uint mapSize, vec2 dzRange) {
    ivec2 texel = clamp(ivec2(floor(r.uv * float(mapSize))), ivec2(0), ivec2(int(mapSize) - 1));
    vec2 centre = (vec2(texel) + 0.5) / float(mapSize);
    return texelTest(r, fetchDepth(map, texel, float(mapSize), r.layer), centre, dzRange);
}

vec4 evaluateHard(TechniqueInput at) {
    return vec4(shadowHard(shadowMap, at.r, at.mapSize, frame.biasParams.xy), vec3(0.0));
}

#endif
