#version 460
// Visibility pass: per pixel, reconstruct the world position from the G-buffer and evaluate the
// technique chosen by TECHNIQUE for one light, into that light's layer of the visibility image.
#include "gpu_types.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_TECHNIQUE) const uint TECHNIQUE = TECHNIQUE_HARD;
layout(constant_id = SPEC_FILTER) const uint FILTER = FILTER_BOX;
layout(constant_id = SPEC_RECEIVER) const uint RECEIVER = RECEIVER_OFF;
layout(constant_id = SPEC_HORIZON) const uint HORIZON = 0u;
layout(constant_id = SPEC_INTERMEDIATES) const bool WRITE_INTERMEDIATES = false;
#include "gbuffer.glsl"
#include "filter_math.h"
#include "shadow_common.glsl"
#include "techniques.glsl"
#include "shadow_sdf.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

layout(set = 0, binding = VIS_LIGHTS, std430) readonly buffer Lights { LightData lights[]; };
layout(set = 0, binding = VIS_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = VIS_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = VIS_SHADOW_MAP) uniform sampler2DArray shadowMap;
layout(set = 0, binding = VIS_SHADOW_COMPARE) uniform sampler2DArrayShadow shadowMapCmp;
layout(set = 0, binding = VIS_SHADOW_TABLE) uniform usampler2DArray shadowTable;
layout(set = 0, binding = VIS_OUT, r32f) uniform writeonly image2DArray visibility;
layout(set = 0, binding = VIS_VIEWS, std430) readonly buffer Views { ShadowViewData views[]; };
layout(set = 0, binding = VIS_FIELD) uniform sampler3D distanceField;
layout(set = 0, binding = VIS_INTERMEDIATES, rgba32f) uniform writeonly image2DArray intermediates;

// The technique's intermediate results at the last view it was evaluated in (the viewer's
// blocker-depth and penumbra views): evaluateTechnique's vector.
vec4 detail = vec4(0.0);
layout(push_constant) uniform Push { VisibilityPush push; };

// Light-space (u, v, depth) offset to the neighbour at p + step along one axis, taking the side
// whose depth is closer (the neighbour most likely on the same surface); zero if none exists.
vec3 neighbourOffset(mat4 S, ivec2 p, ivec2 step, vec3 centre, float depth) {
    uvec2 size = frame.imageSize.xy;
    vec3 best = vec3(0.0);
    float bestGap = 1e30;
    for (int side = -1; side <= 1; side += 2) {
        ivec2 q = p + side * step;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), size))) continue;
        float d = texelFetch(gDepth, q, 0).r;
        if (isBackground(d) || abs(d - depth) >= bestGap) continue;
        bestGap = abs(d - depth);
        vec4 s = S * vec4(worldPosition(frame.invViewProj, q, size, d), 1.0);
        best = float(side) * (s.xyz / s.w - centre);
    }
    return best;
}

// The pixel's footprint on its receiver, in world space: where the rays through the next pixel
// along x and along y meet the plane of the pixel's triangle, less the pixel's own position.
// Zero unless the technique reads a mip chain (vsm.filter=mip).
vec3 footprintDx = vec3(0.0), footprintDy = vec3(0.0);

// The ray through pixel q (from its point on the near plane, reverse-Z depth 1, through its
// point at `depth`) meeting the plane through `world` with normal `face`; the point at `depth`
// when the plane is seen edge-on.
vec3 onReceiverPlane(ivec2 q, float depth, vec3 world, vec3 face) {
    uvec2 size = frame.imageSize.xy;
    vec3 near = worldPosition(frame.invViewProj, q, size, 1.0);
    vec3 along = worldPosition(frame.invViewProj, q, size, depth) - near;
    float facing = dot(along, face);
    if (abs(facing) <= 1e-6 * length(along)) return near + along;
    return near + along * (dot(world - near, face) / facing);
}

// The pixel's footprint in a view's uv: xy across footprintDx, zw across footprintDy.
vec4 uvFootprint(ShadowViewData view, vec3 world) {
    vec4 a = view.shadowMatrix * vec4(world, 1.0);
    vec4 x = view.shadowMatrix * vec4(world + footprintDx, 1.0);
    vec4 y = view.shadowMatrix * vec4(world + footprintDy, 1.0);
    vec2 centre = a.xy / a.w;
    return vec4(x.xy / x.w - centre, y.xy / y.w - centre);
}

Receiver makeReceiver(LightData light, ShadowViewData view, ivec2 p, vec3 world, vec3 normal,
                      float depth, out bool inside) {
    ShadowCoord c = projectToShadowMap(view, offsetReceiver(light, view, world, normal));
    inside = c.inside;
    Receiver r;
    r.uv = c.uv;
    r.depth = c.depth;
    r.gradient = vec2(0.0);
    r.layer = view.texel.z;
    r.kernelScale = view.cascade.z;
    vec4 footprint = TECHNIQUE == TECHNIQUE_VSM ? uvFootprint(view, world) : vec4(0.0);
    r.uvDx = footprint.xy;
    r.uvDy = footprint.zw;
    if (RECEIVER == RECEIVER_LIGHT) {
        r.gradient = receiverGradientFromNormal(view.shadowMatrix, world, normal);
    } else if (RECEIVER == RECEIVER_SCREEN) {
        vec4 s = view.shadowMatrix * vec4(world, 1.0);
        vec3 centre = s.xyz / s.w;
        r.gradient = receiverGradientFromOffsets(
            neighbourOffset(view.shadowMatrix, p, ivec2(1, 0), centre, depth),
            neighbourOffset(view.shadowMatrix, p, ivec2(0, 1), centre, depth));
    }
    return r;
}

// The technique's visibility of one pixel through one shadow view.
float visibilityThrough(uint viewIndex, LightData light, ivec2 p, vec3 world, vec3 normal,
                        float depth) {
    ShadowViewData view = views[viewIndex];
    bool inside;
    Receiver r = makeReceiver(light, view, p, world, normal, depth, inside);
    detail = inside ? evaluateTechnique(TECHNIQUE, shadowMap, shadowMapCmp, shadowTable, r,
                                        push.light.z, view, uvec2(p))
                    : vec4(1.0, 1.0, 0.0, 0.0);
    return detail.x;
}

// Whether a kernel of `radius` texels around the receiver stays inside its view's map.
bool holds(Receiver r, bool inside, float radius) {
    float margin = radius / float(push.light.z);
    return inside && all(greaterThanEqual(r.uv, vec2(margin))) &&
           all(lessThanEqual(r.uv, vec2(1.0 - margin)));
}

// PCSS for a pixel of a sun's cascade `i` (of `count` from view `first`). Its kernels follow the
// light's size, and pcss.maxRadius caps them in texels of the map sampled: the blocker search
// runs in the finest cascade from i whose texels hold it under the cap (else the coarsest that
// holds the pixel), and the penumbra is filtered in the finest cascade from i that holds it, so
// contact shadows keep the fine texels and wide penumbrae are not clipped. The cascades share
// one orientation and depth range (src/core/cascades.cpp): light view distances carry over.
float pcssThroughCascades(uint first, uint i, uint count, LightData light, ivec2 p, vec3 world,
                          vec3 normal, float depth) {
    uint mapSize = push.light.z;
    float cap = frame.pcssParams.x;
    int searchIn = -1;
    // Each cascade's receiver, made once: the filter below looks again at those before searchIn.
    Receiver receivers[MAX_CASCADES];
    bool insides[MAX_CASCADES];
    for (uint j = i; j < count; ++j) {
        ShadowViewData view = views[first + j];
        receivers[j] = makeReceiver(light, view, p, world, normal, depth, insides[j]);
        float search = blockerSearchRadius(view, viewDistance(view, receivers[j].depth), mapSize);
        if (!holds(receivers[j], insides[j], min(search, cap))) continue;
        searchIn = int(j);
        if (search <= cap) break;
    }
    if (searchIn < 0) return visibilityThrough(first + i, light, p, world, normal, depth);
    float turns = rotationTurns(frame.pcssMode.z, uvec2(p));
    Receiver rs = receivers[searchIn];
    vec2 blockers = pcssSearch(shadowMap, rs, mapSize, views[first + uint(searchIn)], turns);
    if (blockers.x == 0.0) {
        detail = vec4(1.0, blockers.y, 0.0, 0.0);
        return 1.0;
    }
    float zBlocker = viewDistance(views[first + uint(searchIn)], blockers.y);
    for (uint k = i; k < uint(searchIn); ++k) {
        ShadowViewData view = views[first + k];
        Receiver r = receivers[k];
        float radius = penumbraRadius(view, viewDistance(view, r.depth), zBlocker, mapSize);
        if (radius <= cap && holds(r, insides[k], radius)) {
            detail = pcssFilter(shadowMap, r, mapSize, view, zBlocker, blockers, turns);
            return detail.x;
        }
    }
    detail = pcssFilter(shadowMap, rs, mapSize, views[first + uint(searchIn)], zBlocker, blockers,
                        turns);
    return detail.x;
}

// The visibility of a pixel through cascade i of a sun's `count` cascades from view `first`.
float throughCascade(uint first, uint i, uint count, LightData light, ivec2 p, vec3 world,
                     vec3 normal, float depth) {
    return TECHNIQUE == TECHNIQUE_PCSS
               ? pcssThroughCascades(first, i, count, light, p, world, normal, depth)
               : visibilityThrough(first + i, light, p, world, normal, depth);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    float v = nanValue();
    if (!isBackground(depth)) {
        vec3 world = worldPosition(frame.invViewProj, p, size, depth);
        vec4 normals = texelFetch(gNormal, p, 0);
        vec3 normal = shadingNormal(normals);
        if (TECHNIQUE == TECHNIQUE_VSM && frame.vsmParams.w > 0.0) {
            vec3 face = faceNormal(normals);
            footprintDx = onReceiverPlane(p + ivec2(1, 0), depth, world, face) - world;
            footprintDy = onReceiverPlane(p + ivec2(0, 1), depth, world, face) - world;
        }
        LightData light = lights[push.light.x];
        uint viewIndex = shadowViewOf(light, world);
        if (TECHNIQUE == TECHNIQUE_SDF) {
            // No shadow map: the field holds the whole scene, the tracer its own horizon.
            v = shadowSdf(distanceField, light, world, faceNormal(normals),
                          lightSine(light, views[viewIndex], world), HORIZON != 0u);
            imageStore(visibility, ivec3(p, int(push.light.y)), vec4(v));
            if (WRITE_INTERMEDIATES)
                imageStore(intermediates, ivec3(p, int(push.light.y)), vec4(v, 0.0, 0.0, 0.0));
            return;
        }
        uint cascades = light.positionType.w == float(LIGHT_DIRECTIONAL) ? light.views.y : 1u;
        if (cascades > 1u) {
            // A sun's cascade: the first whose slice reaches the pixel's view distance.
            float z = dot(world - frame.position.xyz, frame.cameraForward.xyz);
            uint i = 0u;
            while (i + 1u < cascades && z > views[viewIndex + i].cascade.x) ++i;
            v = throughCascade(viewIndex, i, cascades, light, p, world, normal, depth);
            vec4 c = views[viewIndex + i].cascade;
            if (i + 1u < cascades && z > c.y) // the blend band: mix into the next cascade
                v = mix(v, throughCascade(viewIndex, i + 1u, cascades, light, p, world, normal, depth),
                        cascadeBlendWeight(z, c.y, c.x));
        } else {
            v = visibilityThrough(viewIndex, light, p, world, normal, depth);
        }
        if (HORIZON != 0u)
            v *= horizonVisibility(dot(faceNormal(normals), directionToLight(light, world)),
                                   lightSine(light, views[viewIndex], world));
    }
    imageStore(visibility, ivec3(p, int(push.light.y)), vec4(v));
    if (WRITE_INTERMEDIATES)
        imageStore(intermediates, ivec3(p, int(push.light.y)), vec4(v, detail.yzw));
}
