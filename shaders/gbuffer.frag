#version 460
#include "gbuffer_encoding.h"
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
#include "alpha_test.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inWorld;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = GBUFFER_TEXTURE) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Push { MaterialPush material; };
// The material's flags as the pipeline was built for them (MaterialPush's own, one G-buffer
// pipeline per combination): lavapipe would sample the texture under a false branch.
layout(constant_id = SPEC_MATERIAL_TEXTURE) const bool HAS_TEXTURE = true;
layout(constant_id = SPEC_MATERIAL_ALPHA_TEST) const bool ALPHA_TEST = true;
// Whether the batch's vertices carry colours: without, one interpolated input fewer.
layout(constant_id = SPEC_MATERIAL_VERTEX_COLOR) const bool VERTEX_COLOR = true;

layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outAlbedo;

void main() {
    vec4 vertexColor = VERTEX_COLOR ? inColor : vec4(1.0);
    if (coverageHole(material, baseColorTexture, inUv, vertexColor.a, ALPHA_TEST, HAS_TEXTURE))
        discard;
    vec3 n = normalize(inNormal);
    // The triangle's own plane, turned to face us: what hides part of a light's disc from the
    // pixel (bias.horizon), where the smooth normal may already point at the light.
    vec3 face = cross(dFdx(inWorld), dFdy(inWorld));
    float faceLength = length(face);
    face = faceLength > 0.0 ? face / faceLength : n;
    if (dot(face, frame.position.xyz - inWorld) < 0.0) face = -face;
    // Open surfaces are seen from both sides: when we look at a triangle's back, its normal is
    // flipped to face us. The side is the geometric one, so smooth normals near a silhouette,
    // which may point slightly away, are left alone.
    if (dot(face, n) < 0.0) n = -n;
    outNormal = vec4(octahedralEncode(n), octahedralEncode(face));
    // The sRGB image view decodes the texture to linear; mipmapped for the camera's view.
    vec4 albedo = material.baseColor * vertexColor;
    if (HAS_TEXTURE) albedo *= texture(baseColorTexture, inUv);
    outAlbedo = vec4(albedo.rgb, 1.0);
}
