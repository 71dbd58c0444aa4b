#version 460
// Composite: ambient + sum over lights of Lambert x attenuation x shadow factor, where the
// shadow factor mixes light and shadow as the seeds do: 1 - intensity x (1 - visibility).
#include "gpu_types.h"
#include "gbuffer.glsl"
#include "shadow_common.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = COMPOSITE_LIGHTS, std430) readonly buffer Lights { LightData lights[]; };
layout(set = 0, binding = COMPOSITE_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = COMPOSITE_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = COMPOSITE_GBUFFER_ALBEDO) uniform sampler2D gAlbedo;
layout(set = 0, binding = COMPOSITE_VISIBILITY) uniform sampler2DArray visibility;
layout(set = 0, binding = COMPOSITE_OUT, rgba8) uniform writeonly image2D outColor;

// glTF KHR_lights_punctual: inverse square with the recommended smooth range window.
float distanceAttenuation(LightData light, float d) {
    float range = light.directionRange.w;
    float window = range > 0.0 ? clamp(1.0 - pow(d / range, 4.0), 0.0, 1.0) : 1.0;
    return window * window / max(d * d, 1e-8);
}

vec3 directLight(LightData light, vec3 world, vec3 normal) {
    vec3 toLight = directionToLight(light, world);
    float lambert = max(dot(normal, toLight), 0.0);
    float attenuation = 1.0;
    if (light.positionType.w != float(LIGHT_DIRECTIONAL))
        attenuation = distanceAttenuation(light, distance(light.positionType.xyz, world));
    if (light.positionType.w == float(LIGHT_SPOT))
        attenuation *= smoothstep(light.cone.x, light.cone.y,
                                  dot(-toLight, light.directionRange.xyz));
    return light.colorIntensity.rgb * light.colorIntensity.a * lambert * attenuation;
}

vec3 srgbEncode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    vec3 color = frame.background.rgb;
    if (!isBackground(depth)) {
        vec3 world = worldPosition(frame.invViewProj, p, size, depth);
        vec3 normal = shadingNormal(texelFetch(gNormal, p, 0));
        vec3 albedo = texelFetch(gAlbedo, p, 0).rgb;
        vec3 light = vec3(frame.composite.x);
        for (uint i = 0u; i < frame.imageSize.z; ++i) {
            float layer = lights[i].cone.w;
            float v = layer >= 0.0 ? texelFetch(visibility, ivec3(p, int(layer)), 0).r : 1.0;
            light += frame.composite.z * directLight(lights[i], world, normal) *
                     (1.0 - frame.composite.y * (1.0 - v));
        }
        color = 1.0 - exp(-albedo * light); // exponential tone curve: no hard clipping
    }
    imageStore(outColor, p, vec4(srgbEncode(color), 1.0));
}
