#version 460
// Shadow pass of the casters that read their material (alpha-tested casters, depth peels): the
// vertex's texture coordinates and alpha go on to the fragment shader.
#include "pass_types.h"
#include "shadow_clip.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec4 inColor;
layout(push_constant) uniform Push { ShadowPush push; };

layout(location = 0) out vec2 outUv;
layout(location = 1) out float outAlpha;

void main() {
    gl_Position = shadowClip(push, inPosition);
    outUv = inUv;
    outAlpha = inColor.a;
}
