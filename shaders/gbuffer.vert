#version 460
#include "frame_block.h"
#include "bindings.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outWorld;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outColor;

void main() {
    gl_Position = frame.viewProj * vec4(inPosition, 1.0);
    outNormal = inNormal;
    outWorld = inPosition;
    outUv = inUv;
    outColor = inColor;
}
