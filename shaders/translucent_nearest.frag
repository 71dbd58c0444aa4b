#version 460
// The translucent layer's coloured map: the nearest translucent surface's depth (the depth test
// keeps it) and what it lets through (written with it, so the nearest drawn stays).
#include "translucent_caster.glsl"

layout(location = 0) out vec4 outFront;

void main() {
    float depth;
    outFront = vec4(translucentFragment(depth), 1.0);
    gl_FragDepth = depth;
}
