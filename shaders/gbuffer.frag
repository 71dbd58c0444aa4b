#version 460
#include "gpu_types.h"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inWorld;
layout(location = 2) flat in uint inMaterial;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = 1, std430) readonly buffer Materials { vec4 baseColor[]; };

layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outAlbedo;

void main() {
    vec3 n = normalize(inNormal);
    // Open surfaces are seen from both sides: when we look at a triangle's back, its normal is
    // flipped to face us. The side is the geometric one (from derivatives), so smooth normals
    // near a silhouette, which may point slightly away, are left alone.
    vec3 faceNormal = cross(dFdx(inWorld), dFdy(inWorld));
    vec3 toCamera = frame.position.xyz - inWorld;
    if (dot(faceNormal, toCamera) * dot(faceNormal, n) < 0.0) n = -n;
    outNormal = vec4(n, 1.0);
    outAlbedo = baseColor[inMaterial];
}
