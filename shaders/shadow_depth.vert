#version 460
// Shadow pass: depth only, from the light. The constant bias moves casters away from the light
// by a fixed amount of the [0,1] depth range; the slope-scaled part is the rasterizer's.
#include "gpu_types.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec4 inColor;
// The depth peel of second-depth shadow maps redraws the scene and must reproduce the first
// pass's depths: `precise` forbids reassociation. (`invariant gl_Position` would say so too,
// but glslang decorates a block member with it, which the SPIR-V validator flags.)
layout(push_constant) uniform Push { ShadowPush push; };

// Read by the alpha-tested casters' fragment shaders only.
layout(location = 0) out vec2 outUv;
layout(location = 1) out float outAlpha;

void main() {
    precise vec4 clip = push.viewProj * vec4(inPosition, 1.0);
    clip.z += push.bias.x * clip.w;
    gl_Position = clip;
    outUv = inUv;
    outAlpha = inColor.a;
}
