// The shadow passes' clip position: the light's view-projection, then the constant bias, which
// moves casters away from the light by a fixed amount of the [0,1] depth range (the slope-scaled
// part is the rasterizer's). The depth peel of second-depth shadow maps redraws the scene and
// must reproduce the first pass's depths: `precise` forbids reassociation. (`invariant
// gl_Position` would say so too, but glslang decorates a block member with it, which the SPIR-V
// validator flags.)
#ifndef PENUMBRA_SHADOW_CLIP_GLSL
#define PENUMBRA_SHADOW_CLIP_GLSL
#include "pass_types.h"

vec4 shadowClip(ShadowPush push, vec3 position) {
    precise vec4 clip = push.viewProj * vec4(position, 1.0);
    clip.z += push.bias.x * clip.w;
    return clip;
}

#endif
