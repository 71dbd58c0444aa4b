#version 460
// Composite on its own (a frame whose lights have no shadow map; otherwise the last visibility
// dispatch shades, SPEC_FUSED_COMPOSITE): shading.glsl for every pixel.
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

ivec2 p = ivec2(gl_GlobalInvocationID.xy);
float visibilityOf(LightData light) {
    float layer = light.cone.w;
    return layer >= 0.0 ? texelFetch(visibility, ivec3(p, int(layer)), 0).r : 1.0;
}
#define LIGHT_VISIBILITY(i, light) visibilityOf(light)
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
