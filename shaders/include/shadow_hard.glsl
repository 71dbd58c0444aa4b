// Technique `hard` [Williams 1978]: one nearest-texel sample; lit when d(p) <= s(p), the depth
// taken at the texel's centre when receiver-plane bias is on.
#ifndef PENUMBRA_SHADOW_HARD_GLSL
#define PENUMBRA_SHADOW_HARD_GLSL
#include "shadow_pcf.glsl"

float shadowHard(sampler2DArray shadowMap, Receiver r, uint mapSize, vec2 dzRange) {
    ivec2 texel = clamp(ivec2(floor(r.uv * float(mapSize))), ivec2(0), ivec2(int(mapSize) - 1));
    vec2 centre = (vec2(texel) + 0.5) / float(mapSize);
    return texelTest(r, texelFetch(shadowMap, ivec3(texel, int(r.layer)), 0).r, centre, dzRange);
}

#endif
