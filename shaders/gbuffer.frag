#version 460
#include "gpu_types.h"
#include "alpha_test.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inWorld;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = GBUFFER_TEXTURE) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Push { MaterialPush material; };

layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outAlbedo;

void main() {
    if (coverageHole(material, baseColorTexture, inUv, inColor.a)) discard;
    vec3 n = normalize(inNormal);
    // Open surfaces are seen from both sides: when we look at a triangle's back, its normal is
    // flipped to face us. The side is the geometric one (from derivatives), so smooth normals
    // near a silhouette, which may point slightly away, are left alone.
    vec3 faceNormal = cross(dFdx(inWorld), dFdy(inWorld));
    vec3 toCamera = frame.position.xyz - inWorld;
    if (dot(faceNormal, toCamera) * dot(faceNormal, n) < 0.0) n = -n;
    outNormal = vec4(n, 1.0);
    // The sRGB image view decodes the texture to linear; mipmapped for the camera's view.
    vec4 albedo = material.baseColor * inColor;
    if (material.hasTexture != 0u) albedo *= texture(baseColorTexture, inUv);
    outAlbedo = vec4(albedo.rgb, 1.0);
}
