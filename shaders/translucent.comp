#version 460
// The `translucent` layer (src/shadows/translucent.cpp): light through translucent casters, for
// one light. Each pixel reads its light's translucent maps at its shadow view (a point light's
// cube face, a sun's cascade by view distance), in the 2x2 texels around it: what the coloured
// map keeps at the pixel's depth (nothing, the nearest surface's transmittance or the product),
// or the transmittance the moments reconstruct there (translucent.h), weighed bilinearly. The
// light's visibility times the result is the light per channel (TRANSLUCENT_LAYER_COLOUR), and
// the visibility becomes its luminance (Rec. 709: the one channel the composite and the metrics
// read). Outside the views nothing is tinted; the background stays NaN.
#include "frame_block.h"
#include "light_geometry.h"
#include "bindings.h"
#include "pass_types.h"
#include "translucent.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_LIGHT_TYPE) const uint LIGHT_TYPE = LIGHT_DIRECTIONAL;
layout(constant_id = SPEC_LIGHT_VIEWS) const uint LIGHT_VIEWS = 1u;
layout(constant_id = SPEC_TRANSLUCENT_METHOD) const uint METHOD = TRANSLUCENT_COLOURED;
#define LIGHT_TYPE_OF(light) LIGHT_TYPE
#include "gbuffer.glsl"
#include "shadow_common.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = LAYER_LIGHTS, std140) uniform Lights { LightData lights[MAX_UNIFORM_LIGHTS]; };
layout(set = 0, binding = LAYER_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = LAYER_VISIBILITY, r32f) uniform image2DArray visibility;
layout(set = 0, binding = LAYER_PARAMS, std140) uniform Params { TranslucentParams params; };
layout(set = 0, binding = TRANSLUCENT_LAYER_VIEWS, std140) uniform Views { ShadowViewData views[MAX_UNIFORM_VIEWS]; };
// The coloured map's nearest and second nearest depths, the nearest's transmittance and the
// product; or the four moment maps (absorbance, then the red, green and blue moments); every
// view a layer.
layout(set = 0, binding = TRANSLUCENT_LAYER_NEAREST) uniform sampler2DArray nearestDepth;
layout(set = 0, binding = TRANSLUCENT_LAYER_SECOND) uniform sampler2DArray secondDepth;
layout(set = 0, binding = TRANSLUCENT_LAYER_MAPS) uniform sampler2DArray maps[TRANSLUCENT_MAPS];
layout(set = 0, binding = TRANSLUCENT_LAYER_COLOUR, rgba32f) uniform writeonly image2DArray colour;
layout(push_constant) uniform Push { VisibilityPush push; };
#include "light_views.glsl"

// The transmittance of one texel at the receiver's depth (`depth`, and its moment depth `z`).
vec3 texelTransmittance(ivec3 at, float depth, float z) {
    if (METHOD == TRANSLUCENT_COLOURED)
        return colouredMapTransmittance(texelFetch(maps[0], at, 0).rgb,
                                        texelFetch(maps[1], at, 0).rgb,
                                        texelFetch(nearestDepth, at, 0).r,
                                        texelFetch(secondDepth, at, 0).r, depth);
    vec4 a = texelFetch(maps[0], at, 0);
    float bias = params.moments.x, over = params.moments.y;
    return vec3(momentTransmittance(a.r, texelFetch(maps[1], at, 0), z, bias, over),
                momentTransmittance(a.g, texelFetch(maps[2], at, 0), z, bias, over),
                momentTransmittance(a.b, texelFetch(maps[3], at, 0), z, bias, over));
}

// Each of the 2x2 texels read at the receiver's depth, then mixed (as pcf mixes its tests): the
// coloured map's depths are tests, and a moment reconstruction of mixed texels would spread each
// texel's surfaces over its neighbours'.
vec3 transmittanceAt(ShadowViewData view, vec2 uv, float depth) {
    float size = float(textureSize(maps[0], 0).x);
    vec2 p = uv * size - 0.5;
    vec2 base = floor(p);
    vec2 f = p - base;
    int layer = int(view.texel.z);
    float z = momentDepth(view, depth);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 offset = ivec2(k & 1, k >> 1);
        ivec2 texel = clamp(ivec2(base) + offset, ivec2(0), ivec2(int(size) - 1));
        float w = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
        sum += w * texelTransmittance(ivec3(texel, layer), depth, z);
    }
    return sum;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    ivec3 at = ivec3(p, int(push.light.y));
    float v = imageLoad(visibility, at).r; // NaN on the background, which stays
    vec3 t = vec3(1.0);
    float depth = texelFetch(gDepth, p, 0).r;
    if (!isBackground(depth)) {
        vec3 world = worldPosition(frame.invViewProj, p, size, depth);
        LightData light = lights[push.light.x];
        // A point light's cube face, a sun's cascade (no blend band), else the light's one view.
        uint k = LIGHT_TYPE == LIGHT_DIRECTIONAL && LIGHT_VIEWS > 1u
                     ? sunCascadeOf(cameraViewDistance(world))
                     : lightViewOf(light, world);
        ShadowViewData view = viewOf(k);
        // No normal offset: the maps push each surface back by its slope (casterDepth), and a
        // receiver moved off its surface would read the texels beside its own.
        ShadowCoord c = projectToShadowMap(view, world);
        if (c.inside) t = transmittanceAt(view, c.uv, c.depth);
    }
    // The light per channel, and its luminance in the one channel the frame keeps.
    imageStore(colour, at, vec4(v * t, 0.0));
    imageStore(visibility, at, vec4(v * dot(t, TRANSLUCENT_LUMINANCE)));
}
