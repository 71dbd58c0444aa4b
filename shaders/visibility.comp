#version 460
// Visibility pass: per pixel, reconstruct the world position from the G-buffer and evaluate the
// technique chosen by TECHNIQUE for one light, into that light's layer of the visibility image.
#include "gpu_types.h"
#include "gbuffer.glsl"
#include "shadow_common.glsl"
#include "shadow_hard.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(constant_id = 0) const uint TECHNIQUE = TECHNIQUE_HARD;

layout(set = 0, binding = 0, std140) uniform CameraBlock { CameraData camera; };
layout(set = 0, binding = 1, std430) readonly buffer Lights { LightData lights[]; };
layout(set = 0, binding = 2) uniform sampler2D gDepth;
layout(set = 0, binding = 3) uniform sampler2D gNormal;
layout(set = 0, binding = 4) uniform sampler2D shadowMap;           // nearest, raw depths
layout(set = 0, binding = 5) uniform sampler2DShadow shadowMapCmp;  // linear, hardware compare
layout(set = 0, binding = 6, r32f) uniform writeonly image2DArray visibility;
layout(push_constant) uniform Push { VisibilityPush push; };

float evaluate(LightData light, vec3 world, vec3 normal) {
    ShadowCoord c = projectToShadowMap(light, offsetReceiver(light, world, normal));
    if (!c.inside) return 1.0;
    switch (TECHNIQUE) {
    case TECHNIQUE_HARD:
    default: return shadowHard(shadowMap, c, push.light.z);
    }
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = camera.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    float v = nanValue();
    if (!isBackground(depth)) {
        vec3 world = worldPosition(camera.invViewProj, p, size, depth);
        vec3 normal = normalize(texelFetch(gNormal, p, 0).xyz);
        v = evaluate(lights[push.light.x], world, normal);
    }
    imageStore(visibility, ivec3(p, int(push.light.y)), vec4(v));
}
