// The composite's shading: ambient + sum over lights of Lambert x attenuation x shadow factor,
// where the shadow factor mixes light and shadow as the seeds do: 1 - intensity x (1 -
// visibility); then an exponential tone curve and sRGB. composite.comp runs it on its own;
// visibility.comp runs it in the last light's dispatch (SPEC_FUSED_COMPOSITE). The includer
// declares `lights` (LightData[], uniform) and defines LIGHT_VISIBILITY(i, light), light i's
// visibility at the pixel: a float, or a vec3 per channel (the translucent layer's tint).
#ifndef PENUMBRA_SHADING_GLSL
#define PENUMBRA_SHADING_GLSL
#include "light_geometry.h"
#include "bindings.h"

// The scene's lights as the pipeline was built for them: their count when at most
// MAX_SPECIALIZED_LIGHTS (0: more, counted at run time in frame.imageSize.z) and their LIGHT_*
// kinds, two bits each. Lavapipe runs both sides of every branch and loads a uniform record one
// lane at a time at a loop's index: known lights unroll the loop and drop the other kinds' code.
layout(constant_id = SPEC_SCENE_LIGHTS) const uint SCENE_LIGHTS = 0u;
layout(constant_id = SPEC_SCENE_LIGHT_TYPES) const uint SCENE_LIGHT_TYPES = 0u;

uint sceneLightType(uint i, LightData light) {
    return SCENE_LIGHTS > 0u ? (SCENE_LIGHT_TYPES >> (2u * i)) & 3u
                             : uint(light.positionType.w);
}

// glTF KHR_lights_punctual: inverse square with the recommended smooth range window.
float distanceAttenuation(LightData light, float d) {
    float range = light.directionRange.w;
    float window = range > 0.0 ? clamp(1.0 - pow(d / range, 4.0), 0.0, 1.0) : 1.0;
    return window * window / max(d * d, 1e-8);
}

vec3 directLight(LightData light, uint type, vec3 world, vec3 normal) {
    vec3 toLight = type == LIGHT_DIRECTIONAL ? -light.directionRange.xyz
                                             : normalize(light.positionType.xyz - world);
    float lambert = max(dot(normal, toLight), 0.0);
    float attenuation = 1.0;
    if (type != LIGHT_DIRECTIONAL)
        attenuation = distanceAttenuation(light, distance(light.positionType.xyz, world));
    if (type == LIGHT_SPOT)
        attenuation *= smoothstep(light.cone.x, light.cone.y,
                                  dot(-toLight, light.directionRange.xyz));
    return light.colorIntensity.rgb * light.colorIntensity.a * lambert * attenuation;
}

// sRGB's transfer curve; c^(1/2.4) as Taylor's fit in c^(1/2), c^(1/4) and c^(1/8) [Ian Taylor,
// "Fast sRGB conversion"], within 0.001 of 1.055 c^(1/2.4) - 0.055 over [0.0031308, 1] (a quarter
// of an 8-bit step): three square roots cost lavapipe far less than three pows.
vec3 srgbEncode(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
    vec3 curve = 0.662002687 * s1 + 0.684122060 * s2 - 0.323583601 * s3 - 0.0225411470 * c;
    return mix(c * 12.92, curve, step(0.0031308, c));
}

// The pixel's tone-mapped colour (linear; srgbEncode for display).
vec3 shadePixel(vec3 world, vec3 normal, vec3 albedo) {
    vec3 light = vec3(frame.composite.x);
    uint count = SCENE_LIGHTS > 0u ? SCENE_LIGHTS : frame.imageSize.z;
    for (uint i = 0u; i < count; ++i) {
        LightData l = lights[i];
        light += frame.composite.z * directLight(l, sceneLightType(i, l), world, normal) *
                 (1.0 - frame.composite.y * (1.0 - LIGHT_VISIBILITY(i, l)));
    }
    return 1.0 - exp(-albedo * light); // exponential tone curve: no hard clipping
}

#endif
