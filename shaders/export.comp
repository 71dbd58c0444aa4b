#version 460
// Readback helper (not part of the timed frame): world position, unit normal and the triangle's
// unit normal per pixel, NaN where there is no geometry, for position.pfm / normal.pfm, the
// ground truth and the screen-space layers' CPU references.
#include "frame_block.h"
#include "bindings.h"
#include "gbuffer.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = EXPORT_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = EXPORT_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = EXPORT_POSITION, rgba32f) uniform writeonly image2D outPosition;
layout(set = 0, binding = EXPORT_NORMAL, rgba32f) uniform writeonly image2D outNormal;
layout(set = 0, binding = EXPORT_FACE_NORMAL, rgba32f) uniform writeonly image2D outFaceNormal;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    vec4 position = vec4(nanValue()), normal = vec4(nanValue()), face = vec4(nanValue());
    if (!isBackground(depth)) {
        position = vec4(worldPosition(frame.invViewProj, p, size, depth), 1.0);
        vec4 normals = texelFetch(gNormal, p, 0);
        normal = vec4(shadingNormal(normals), 0.0);
        face = vec4(faceNormal(normals), 0.0);
    }
    imageStore(outPosition, p, position);
    imageStore(outNormal, p, normal);
    imageStore(outFaceNormal, p, face);
}
