#version 460
// The viewer's display pass: what the window shows, one invocation per pixel, from the frame's
// targets (apps/viewer/display.cpp). Modes DISPLAY_* in viewer_types.h.
#include "frame_block.h"
#include "bindings.h"
#include "viewer_types.h"
#include "gbuffer.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

layout(set = 0, binding = DISPLAY_COLOR, rgba8) uniform readonly image2D colorA;
layout(set = 0, binding = DISPLAY_COLOR_B, rgba8) uniform readonly image2D colorB;
layout(set = 0, binding = DISPLAY_VISIBILITY_MAP) uniform sampler2DArray visibility;
layout(set = 0, binding = DISPLAY_DEPTH_MAP) uniform sampler2DArray depthMap;
layout(set = 0, binding = DISPLAY_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = DISPLAY_OVERLAY_IMAGE, rgba8) uniform readonly image2D overlay;
layout(set = 0, binding = DISPLAY_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(set = 0, binding = DISPLAY_OUT, rgba8) uniform writeonly image2D outColor;
layout(set = 0, binding = DISPLAY_INTERMEDIATES) uniform sampler2DArray intermediates;
layout(set = 0, binding = DISPLAY_LAYER_RESULTS) uniform sampler2DArray layerResults;
layout(push_constant) uniform Push { DisplayPush display; };

const vec3 kBackground = vec3(0.55, 0.65, 0.8);
const vec3 kNoBlocker = vec3(0.1, 0.12, 0.3); // the blocker search found nothing

// Dark blue through green to yellow as t goes from 0 to 1 (a penumbra's width).
vec3 ramp(float t) {
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(-0.5 + 2.0 * t, 0.2 + 0.8 * sin(3.14159 * min(t * 1.2, 1.0)) + 0.3 * t,
                      0.6 - 0.6 * t), 0.0, 1.0);
}

// Distinct tints for cascades 0..7, repeating.
vec3 cascadeTint(uint i) {
    const vec3 tints[4] = vec3[](vec3(1.0, 0.35, 0.35), vec3(0.35, 1.0, 0.35),
                                 vec3(0.4, 0.5, 1.0), vec3(1.0, 1.0, 0.3));
    return tints[i % 4u] * (i < 4u ? 1.0 : 0.7);
}

float split(uint i) { return display.splits[i / 4u][i % 4u]; }

vec4 shadowMapTexel(ivec2 p, ivec2 size) {
    // The square map, fitted into the window and centred.
    int side = min(size.x, size.y);
    ivec2 corner = (size - ivec2(side)) / 2;
    ivec2 q = p - corner;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(side))))
        return vec4(0.1, 0.1, 0.1, 1.0);
    vec2 uv = (vec2(q) + 0.5) / float(side);
    float d = textureLod(depthMap, vec3(uv, float(display.mode.y)), 0.0).r;
    float n = display.depthRange.x, f = display.depthRange.y;
    // Perspective maps hold 1/z-like depth: show the distance, near black, far white.
    float t = display.depthRange.z > 0.5 ? (n * f / (f - d * (f - n)) - n) / (f - n) : d;
    return vec4(vec3(clamp(t, 0.0, 1.0)), 1.0);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(outColor);
    if (any(greaterThanEqual(p, size))) return;
    vec4 color = uint(p.x) < display.mode.z ? imageLoad(colorA, p) : imageLoad(colorB, p);
    uint mode = display.mode.x;
    if (mode == DISPLAY_VISIBILITY) {
        float v = texelFetch(visibility, ivec3(p, int(display.mode.y)), 0).r;
        color = isnan(v) ? vec4(kBackground, 1.0) : vec4(vec3(clamp(v, 0.0, 1.0)), 1.0);
    } else if (mode == DISPLAY_LAYER) {
        float v = isBackground(texelFetch(gDepth, p, 0).r)
                      ? 1.0
                      : texelFetch(layerResults, ivec3(p, int(display.mode.y)), 0).r;
        color = vec4(vec3(v), 1.0);
    } else if (mode == DISPLAY_SHADOW_MAP) {
        color = shadowMapTexel(p, size);
    } else if (mode == DISPLAY_CASCADES) {
        float depth = texelFetch(gDepth, p, 0).r;
        if (!isBackground(depth) && display.mode.w > 0u) {
            vec3 world = worldPosition(frame.invViewProj, p, uvec2(size), depth);
            float along = dot(world - frame.position.xyz, display.forward.xyz);
            uint i = 0u;
            while (i + 1u < display.mode.w && along > split(i)) ++i;
            color.rgb = mix(color.rgb, cascadeTint(i), 0.45);
        }
    } else if (mode == DISPLAY_BLOCKER_DEPTH || mode == DISPLAY_PENUMBRA) {
        vec4 d = texelFetch(intermediates, ivec3(p, int(display.mode.y)), 0);
        if (isnan(d.x))
            color = vec4(kBackground, 1.0);
        else if (d.z <= 0.0) // no blocker: fully lit
            color = vec4(kNoBlocker, 1.0);
        else if (mode == DISPLAY_BLOCKER_DEPTH)
            color = vec4(vec3(clamp(d.y, 0.0, 1.0)), 1.0);
        else
            color = vec4(ramp(d.w / max(display.depthRange.w, 1e-6)), 1.0);
    } else if (mode == DISPLAY_OVERLAY) {
        color = imageLoad(overlay, p);
    }
    if (uint(p.x) == display.mode.z) color = vec4(1.0, 1.0, 0.2, 1.0); // the A/B split line
    imageStore(outColor, p, vec4(color.rgb, 1.0));
}
