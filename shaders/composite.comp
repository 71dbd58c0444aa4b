#version 460
// Composite on its own (a frame whose lights have no shadow map; otherwise the last visibility
// dispatch shades, SPEC_FUSED_COMPOSITE): shading.glsl for every pixel, each light's visibility
// in colour where the translucent layer ran (SPEC_COMPOSITE_COLOURED).
#include "light_geometry.h"
#include "frame_block.h"
#include "bindings.h"
#include "gbuffer.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = COMPOSITE_LIGHTS, std140) uniform Lights {
    LightData lights[MAX_UNIFORM_LIGHTS];
};
layout(set = 0, binding = COMPOSITE_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = COMPOSITE_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = COMPOSITE_GBUFFER_ALBEDO) uniform sampler2D gAlbedo;
layout(set = 0, binding = COMPOSITE_VISIBILITY) uniform sampler2DArray visibility;
layout(set = 0, binding = COMPOSITE_OUT, rgba8) uniform writeonly image2D outColor;
// The translucent layer's light per channel, a layer per light (SPEC_COMPOSITE_COLOURED).
layout(constant_id = SPEC_COMPOSITE_COLOURED) const bool COLOURED = false;
layout(set = 0, binding = COMPOSITE_TRANSMITTANCE) uniform sampler2DArray transmittance;

ivec2 p = ivec2(gl_GlobalInvocationID.xy);
// The light's visibility, in colour where the translucent layer tinted it: the layer runs after
// every other (src/shadows/layer.cpp), so what it wrote is the light's final light per channel.
vec3 lightThrough(LightData light) {
    float layer = light.cone.w;
    if (layer < 0.0) return vec3(1.0);
    ivec3 at = ivec3(p, int(layer));
    return COLOURED ? texelFetch(transmittance, at, 0).rgb : vec3(texelFetch(visibility, at, 0).r);
}
#define LIGHT_VISIBILITY(i, light) lightThrough(light)
#include "shading.glsl"

void main() {
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    vec3 color = frame.background.rgb;
    if (!isBackground(depth)) {
        vec3 world = worldPosition(frame.invViewProj, p, size, depth);
        vec3 normal = shadingNormal(texelFetch(gNormal, p, 0));
        color = shadePixel(world, normal, texelFetch(gAlbedo, p, 0).rgb);
    }
    imageStore(outColor, p, vec4(srgbEncode(color), 1.0));
}
