#version 460
// Page draws of the alpha-tested casters (page_draw.glsl), with shadow_mask.frag: the vertex's
// texture coordinates and alpha go on, as shadow_depth.vert's.
#include "page_draw.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec4 inColor;

layout(location = 0) out vec2 outUv;
layout(location = 1) out float outAlpha;

void main() {
    placeInPage(inPosition);
    outUv = inUv;
    outAlpha = inColor.a;
}
