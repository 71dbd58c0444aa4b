#version 460
// Depth peel for second-depth shadow maps [Wang and Molnar 1994]: keeps, per texel, the nearest
// surface behind the one the first shadow pass stored. Alpha-tested casters keep their holes.
#include "bindings.h"
#include "pass_types.h"
#include "alpha_test.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 1) in float inAlpha;

layout(set = 0, binding = READ_MAP) uniform sampler2D firstDepth;
layout(set = 0, binding = READ_TEXTURE) uniform sampler2D baseColorTexture;
layout(push_constant) uniform Push { ShadowPush push; MaterialPush material; };

void main() {
    if (coverageHole(material, baseColorTexture, inUv, inAlpha, material.alphaTest != 0u,
                     material.hasTexture != 0u))
        discard;
    float first = texelFetch(firstDepth, ivec2(gl_FragCoord.xy), 0).r;
    // The first layer itself: the same depth, up to a few ulps should another pipeline round
    // differently.
    if (gl_FragCoord.z <= first + 4e-7 * max(first, 1e-3)) discard;
}
