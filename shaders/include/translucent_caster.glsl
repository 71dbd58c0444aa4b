// A translucent caster's fragment from the light (src/shadows/translucent.cpp): what it lets
// through per channel, Scene::transmittance's rule (docs/translucency.md). Included by the three
// draws of the translucent layer's maps: translucent_nearest.frag (the nearest surface's depth),
// translucent_product.frag (its transmittance multiplied into the product) and
// translucent_moments.frag (its absorbance and moments added). A fragment behind the opaque
// casters' depth map, or one that lets everything through (a leaf card's clear border), writes
// nothing: translucentFragment discards it.
#ifndef PENUMBRA_TRANSLUCENT_CASTER_GLSL
#define PENUMBRA_TRANSLUCENT_CASTER_GLSL
#include "translucent.h"
#include "light_geometry.h"
#include "bindings.h"
#include "pass_types.h"

layout(location = 0) in vec2 inUv;
layout(location = 1) in vec4 inColor;

layout(set = 0, binding = TRANSLUCENT_TEXTURE_BINDING) uniform sampler2D baseColorTexture;
layout(set = 0, binding = TRANSLUCENT_TRANSMISSION_TEXTURE) uniform sampler2D transmissionTexture;
layout(set = 0, binding = TRANSLUCENT_OPAQUE_DEPTH) uniform sampler2DArray opaqueDepth;
layout(set = 0, binding = TRANSLUCENT_VIEWS, std140) uniform Views { ShadowViewData views[MAX_UNIFORM_VIEWS]; };
layout(push_constant) uniform Push { TranslucentCasterPush push; };

// Scene::transmittance (src/scene/material_coverage.cpp), the base colour texture read at full
// resolution as the alpha test reads it, through an sRGB view (its colour arrives linear); the
// transmission texture's red channel likewise, through a UNORM view (stored linear).
vec3 transmittance() {
    uint flags = push.flags.x;
    vec4 texel = vec4(1.0);
    if ((flags & TRANSLUCENT_TEXTURE) != 0u) texel = textureLod(baseColorTexture, inUv, 0.0);
    float alpha = push.baseColor.a * inColor.a * texel.a;
    if ((flags & TRANSLUCENT_MASK) != 0u && alpha < push.bias.y) return vec3(1.0);
    float covered = (flags & TRANSLUCENT_BLEND) != 0u ? clamp(alpha, 0.0, 1.0) : 1.0;
    float fraction = push.bias.z * textureLod(transmissionTexture, inUv, 0.0).r;
    vec3 through = clamp(fraction * push.baseColor.rgb * inColor.rgb * texel.rgb, 0.0, 1.0);
    if ((flags & TRANSLUCENT_VOLUME) != 0u) through = sqrt(through) * push.attenuation.rgb;
    return (1.0 - covered) + covered * through;
}

// The surface's depth as its maps keep it: pushed away from the light by its slope over
// TRANSLUCENT_SLOPE_TEXELS texels and at least TRANSLUCENT_DEPTH_BIAS, so that a receiver on the
// surface itself (whose depth the layer's pass takes from the G-buffer) stays in front of it
// wherever the texels it reads cover it, as the depth map's slope bias keeps a receiver off its
// own opaque surface (the constant depth bias alone may be 0: bias.mode=adaptive).
// `precise`: the nearest depth's draw and the second's peel compute it in separate shaders, and
// the peel drops the nearest surface's own fragment by equality.
float casterDepth() {
    precise float slope = max(abs(dFdx(gl_FragCoord.z)), abs(dFdy(gl_FragCoord.z)));
    precise float depth = gl_FragCoord.z + TRANSLUCENT_SLOPE_TEXELS * slope + TRANSLUCENT_DEPTH_BIAS;
    return clamp(depth, 0.0, 1.0);
}

// The fragment's transmittance and its depth (casterDepth, taken before any fragment of the quad
// is discarded); discarded behind the opaque casters or where it keeps nothing.
vec3 translucentFragment(out float depth) {
    depth = casterDepth();
    float opaque = texelFetch(opaqueDepth, ivec3(ivec2(gl_FragCoord.xy), int(push.flags.y)), 0).r;
    if (gl_FragCoord.z > opaque) discard; // behind the opaque casters: no receiver sees it
    vec3 t = transmittance();
    if (all(greaterThanEqual(t, vec3(1.0)))) discard;
    return t;
}

#endif
