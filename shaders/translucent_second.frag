#version 460
// The translucent layer's coloured map: the second nearest translucent surface's depth, a peel
// past the nearest (whose map this reads at the fragment's texel; the same surface's fragment
// has the same depth there, and goes).
#include "translucent_caster.glsl"

layout(set = 0, binding = TRANSLUCENT_NEAREST_DEPTH) uniform sampler2DArray nearestDepth;

void main() {
    float depth;
    translucentFragment(depth);
    float nearest = texelFetch(nearestDepth, ivec3(ivec2(gl_FragCoord.xy), int(push.flags.y)), 0).r;
    if (depth <= nearest) discard;
    gl_FragDepth = depth;
}
