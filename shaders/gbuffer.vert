#version 460
#include "frame_block.h"
#include "bindings.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
// Where each vertex was in the last frame, three floats a vertex in the vertex buffer's order
// (indexed as it is): read only when FrameData::motion.x says the vertices moved.
layout(set = 0, binding = GBUFFER_PREVIOUS_POSITIONS, std430) readonly buffer PreviousPositions {
    float previousPositions[];
};
layout(constant_id = SPEC_GBUFFER_MOTION) const bool MOTION = false;

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outWorld;
layout(location = 2) out vec2 outUv;
layout(location = 3) out vec4 outColor;
layout(location = 4) out vec3 outPreviousWorld;

void main() {
    gl_Position = frame.viewProj * vec4(inPosition, 1.0);
    outNormal = inNormal;
    outWorld = inPosition;
    outUv = inUv;
    outColor = inColor;
    outPreviousWorld = inPosition;
    if (MOTION && frame.motion.x != 0u) {
        uint i = 3u * uint(gl_VertexIndex);
        outPreviousWorld =
            vec3(previousPositions[i], previousPositions[i + 1u], previousPositions[i + 2u]);
    }
}
