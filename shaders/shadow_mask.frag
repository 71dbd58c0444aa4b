#version 460
// Alpha-tested casters (glTF alphaMode MASK) in the shadow pass: holes let the light through.
#include "bindings.h"
#include "pass_types.h"
#include "alpha_test.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 1) in float inAlpha;

layout(set = 0, binding = MASK_TEXTURE) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Push { ShadowPush push; MaterialPush material; };

void main() {
    if (coverageHole(material, baseColorTexture, inUv, inAlpha, material.alphaTest != 0u,
                     material.hasTexture != 0u))
        discard;
}
