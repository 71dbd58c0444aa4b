#version 460
// Shadow pass of the opaque casters: depth only, from the positions alone (GpuScene::positions,
// 12 bytes a vertex: lavapipe's vertex fetch, on one thread, reads a quarter of the full
// vertex's bytes).
#include "pass_types.h"
#include "shadow_clip.glsl"

layout(location = 0) in vec3 inPosition;
layout(push_constant) uniform Push { ShadowPush push; };

void main() { gl_Position = shadowClip(push, inPosition); }
