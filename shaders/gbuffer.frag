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
layout(location = 4) in vec3 inPreviousWorld;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = GBUFFER_TEXTURE) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Push { MaterialPush material; };
// The material's flags as the pipeline was built for them (MaterialPush's own, one G-buffer
// pipeline per combination): lavapipe would sample the texture under a false branch.
layout(constant_id = SPEC_MATERIAL_TEXTURE) const bool HAS_TEXTURE = true;
layout(constant_id = SPEC_MATERIAL_ALPHA_TEST) const bool ALPHA_TEST = true;
// Whether the batch's vertices carry colours: without, one interpolated input fewer.
layout(constant_id = SPEC_MATERIAL_VERTEX_COLOR) const bool VERTEX_COLOR = true;
// Motion vectors (a third target, declared when something reads them).
layout(constant_id = SPEC_GBUFFER_MOTION) const bool MOTION = false;

layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outAlbedo;
layout(location = 2) out vec4 outMotion;

// Where a world position lands on the image under `viewProj`, in pixels (x right, y down) and
// its depth (NDC z, reverse-Z).
vec3 pixelOf(mat4 viewProj, vec3 world) {
    vec4 clip = viewProj * vec4(world, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    return vec3((ndc.xy * 0.5 + 0.5) * vec2(frame.imageSize.xy), ndc.z);
}

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
    // The point's motion since the last frame: where it is minus where it was, in pixels, and
    // its depth then; both ends projected alike, so a point that did not move has none.
    if (MOTION) {
        vec3 before = pixelOf(frame.previousViewProj, inPreviousWorld);
        outMotion = vec4(pixelOf(frame.viewProj, inWorld).xy - before.xy, before.z, 1.0);
    }
}
