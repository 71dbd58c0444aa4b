// G-buffer access shared by the screen-space compute passes.
#ifndef PENUMBRA_GBUFFER_GLSL
#define PENUMBRA_GBUFFER_GLSL

#include "gbuffer_encoding.h"

float nanValue() { return uintBitsToFloat(0x7fc00000u); }

// Reverse-Z: the depth buffer is cleared to 0, so 0 means no geometry.
bool isBackground(float depth) { return depth <= 0.0; }

// World position of pixel `p` (its centre) from reverse-Z depth.
vec3 worldPosition(mat4 invViewProj, ivec2 p, uvec2 size, float depth) {
    vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 world = invViewProj * vec4(ndc, depth, 1.0);
    return world.xyz / world.w;
}

// The G-buffer's normals (gbuffer.frag): the interpolated one that shades, and the triangle's.
vec3 shadingNormal(vec4 texel) { return octahedralDecode(texel.xy); }
vec3 faceNormal(vec4 texel) { return octahedralDecode(texel.zw); }

#endif
