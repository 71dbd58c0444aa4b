// Technique `hard` [Williams 1978]: one nearest-texel sample; lit when d(p) <= s(p).
#ifndef PENUMBRA_SHADOW_HARD_GLSL
#define PENUMBRA_SHADOW_HARD_GLSL

float shadowHard(sampler2D shadowMap, ShadowCoord c, uint mapSize) {
    ivec2 texel = clamp(ivec2(floor(c.uv * float(mapSize))), ivec2(0), ivec2(int(mapSize) - 1));
    float s = texelFetch(shadowMap, texel, 0).r;
    return c.depth <= s ? 1.0 : 0.0;
}

#endif
