#version 460
// A translucent caster drawn from the light (the translucent layer's maps, src/shadows/
// translucent.cpp): the shadow pass's position, and what the fragment needs of the material.
#include "translucent.h"
#include "pass_types.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec4 inColor;
layout(push_constant) uniform Push { TranslucentCasterPush push; };

layout(location = 0) out vec2 outUv;
layout(location = 1) out vec4 outColor;

void main() {
    // shadowClip's sum (shadow_clip.glsl) on this push: the depth map's constant bias.
    precise vec4 clip = push.viewProj * vec4(inPosition, 1.0);
    clip.z += push.bias.x * clip.w;
    gl_Position = clip;
    outUv = inUv;
    outColor = inColor;
}
