#version 460
// Visibility pass: per pixel, reconstruct the world position from the G-buffer and evaluate the
// technique chosen by TECHNIQUE for one light, into that light's layer of the visibility image.
// The pass knows no technique by name: what differs between them comes from capabilities their
// modules declare (src/shadows/technique.h), as specialization constants.
#include "kernels.h"
#include "bias.h"
#include "light_geometry.h"
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
#include "checkerboard.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_TECHNIQUE) const uint TECHNIQUE = 0u;
layout(constant_id = SPEC_RECEIVER) const uint RECEIVER = RECEIVER_OFF;
layout(constant_id = SPEC_HORIZON) const uint HORIZON = 0u;
layout(constant_id = SPEC_INTERMEDIATES) const bool WRITE_INTERMEDIATES = false;
// The dispatch's light: its LIGHT_* kind and how many shadow views it has (a sun's cascades, a
// point light's 6 faces). Lavapipe runs every branch and loads a uniform record one lane at a
// time unless its index is uniform: with these constants the other kinds' code goes, the loops
// over views unroll, and every view record is read at a uniform index (viewOf).
layout(constant_id = SPEC_LIGHT_TYPE) const uint LIGHT_TYPE = LIGHT_DIRECTIONAL;
layout(constant_id = SPEC_LIGHT_VIEWS) const uint LIGHT_VIEWS = 1u;
#define LIGHT_TYPE_OF(light) LIGHT_TYPE
// The last light's dispatch shades the pixel too (shading.glsl): one pass fewer over the
// G-buffer, and the pixel's position and normal are reconstructed once.
layout(constant_id = SPEC_FUSED_COMPOSITE) const bool FUSED_COMPOSITE = false;
layout(constant_id = SPEC_CASCADE_BLEND) const bool CASCADE_BLEND = true;
layout(constant_id = SPEC_ADAPTIVE_BIAS) const bool ADAPTIVE = false;
// Capabilities: the technique reads the pixel's footprint in the map; searches blockers (a sun's
// search and filter may then run in different cascades); traces the scene's distance field
// instead of reading a map (and clips the light at the receiver's horizon itself).
layout(constant_id = SPEC_FOOTPRINT) const bool FOOTPRINT = false;
layout(constant_id = SPEC_BLOCKER_SEARCH) const bool BLOCKER_SEARCH = false;
layout(constant_id = SPEC_TRACES_FIELD) const bool TRACES_FIELD = false;
// Which pixels this dispatch traces: all, the checkerboard's even ones, or the trace list's
// (checkerboard.h; visibility_fill.comp fills the others between the two).
layout(constant_id = SPEC_CHECKERBOARD) const uint CHECKERBOARD = 0u;
#include "gbuffer.glsl"
#include "shadow_common.glsl"
#include "techniques.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

layout(set = 0, binding = VIS_LIGHTS, std140) uniform Lights { LightData lights[MAX_UNIFORM_LIGHTS]; };
layout(set = 0, binding = VIS_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = VIS_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = VIS_OUT, r32f) uniform image2DArray visibility;
layout(set = 0, binding = VIS_VIEWS, std140) uniform Views { ShadowViewData views[MAX_UNIFORM_VIEWS]; };
layout(set = 0, binding = VIS_INTERMEDIATES, rgba32f) uniform writeonly image2DArray intermediates;
layout(set = 0, binding = VIS_GBUFFER_ALBEDO) uniform sampler2D gAlbedo;
layout(set = 0, binding = VIS_COLOR, rgba8) uniform writeonly image2D outColor;
layout(set = 0, binding = VIS_TRACE_LIST, std430) readonly buffer TraceList {
    TraceListHead head;
    uint pixels[];
} traceList;

// The technique's intermediate results at the last view it was evaluated in (the viewer's
// blocker-depth and penumbra views): evaluateTechnique's vector.
vec4 detail = vec4(0.0);
layout(push_constant) uniform Push { VisibilityPush push; };
#include "virtual_levels.glsl"
#include "light_views.glsl"

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
// Zero unless the technique reads its footprint (FOOTPRINT).
vec3 footprintDx = vec3(0.0), footprintDy = vec3(0.0);

// bias.mode=adaptive: the pixel's own triangle's normal and how fast its surface's shading
// normal turns (radians per world unit), set by main.
vec3 receiverFace = vec3(0.0);
float receiverCurvature = 0.0;

// The shading normal's turn per world unit towards the neighbour along each axis on the side
// nearer in depth (the one likely on the same surface), the larger of the two axes.
float surfaceCurvature(ivec2 p, float depth, vec3 world, vec3 normal) {
    uvec2 size = frame.imageSize.xy;
    float curvature = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
        float bestGap = 1e30, turn = 0.0;
        for (int side = -1; side <= 1; side += 2) {
            ivec2 q = p + side * step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), size))) continue;
            float d = texelFetch(gDepth, q, 0).r;
            if (isBackground(d) || abs(d - depth) >= bestGap) continue;
            bestGap = abs(d - depth);
            vec3 along = worldPosition(frame.invViewProj, q, size, d) - world;
            vec3 bend = shadingNormal(texelFetch(gNormal, q, 0)) - normal;
            turn = length(bend) / max(length(along), 1e-20);
        }
        curvature = max(curvature, turn);
    }
    return curvature;
}

// bias.mode=adaptive's terms at a receiver of `view` (bias.h, adaptiveBiasTerms): the
// lift comes off its depth; the curvature terms go with it to every tap.
void applyAdaptiveBias(inout Receiver r, float texelWorld, float depthPerWorld, float cosine,
                       float sinRadius) {
    vec4 t = adaptiveBiasTerms(texelWorld, float(push.light.z), depthPerWorld, cosine,
                               receiverCurvature, frame.biasParams.z, frame.biasParams.w,
                               length(r.gradient));
    r.depth -= t.x;
    r.curve = t.yz;
    r.planeRange = vec2(-1e30, t.w);
    r.creaseLimit = creaseLimit(t.z, sinRadius, frame.filterLimits.y);
}

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
    vec4 footprint = FOOTPRINT ? uvFootprint(view, world) : vec4(0.0);
    r.uvDx = footprint.xy;
    r.uvDy = footprint.zw;
    noAdaptiveTerms(r);
    if (ADAPTIVE) {
        // [Dou et al. 2014]: the tangent plane of the pixel's own triangle, the one the map
        // rasterized; the smooth normal would tilt it off the stored depths.
        r.gradient = receiverGradientFromNormal(view.shadowMatrix, world, receiverFace);
        vec3 toLight = directionToLight(light, world);
        float texelWorld = view.texel.x;
        if (view.texel.y > 0.5) texelWorld *= max((view.shadowMatrix * vec4(world, 1.0)).w, 0.0);
        applyAdaptiveBias(r, texelWorld,
                          abs(dot(lightDepthGradient(view.shadowMatrix, world), toLight)),
                          dot(receiverFace, toLight), lightSine(light, view, world));
    } else if (RECEIVER == RECEIVER_LIGHT) {
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

// A sun's cascades share most of what makeReceiver computes: the normal offset's direction and
// size in texels, the depth (one depth range and orientation: every cascade has the first's
// depth row), and the receiver plane and footprint, which map from the first cascade's (u, v)
// to each one's by ShadowViewData::fromFirst. A cascade then costs its (u, v) rows (orthographic
// views: w is 1).
struct CascadeBase {
    vec3 world, normal;
    float offsetScale; // the normal offset in world units per world unit of a cascade's texel
    float depth;       // the receiver's light depth before the normal offset ...
    float depthAlong;  // ... and its change per world unit of offset
    vec2 gradient;     // the receiver plane's d depth / d uv in the first cascade
    vec4 footprint;    // the pixel's uv footprint in the first cascade (FOOTPRINT)
    float depthPerWorld, cosine, sinRadius; // bias.mode=adaptive: shared by every cascade
};

CascadeBase cascadeBase(LightData light, ivec2 p, vec3 world, vec3 normal, float depth) {
    ShadowViewData first = views[push.light.w];
    CascadeBase b;
    b.world = world;
    b.normal = normal;
    b.offsetScale = light.bias.z * (1.0 - max(dot(normal, directionToLight(light, world)), 0.0));
    b.depth = (first.shadowMatrix * vec4(world, 1.0)).z;
    b.depthAlong = (mat3(first.shadowMatrix) * normal).z;
    bool inside;
    Receiver r = makeReceiver(light, first, p, world, normal, depth, inside);
    b.gradient = r.gradient;
    b.footprint = vec4(r.uvDx, r.uvDy);
    vec3 toLight = directionToLight(light, world);
    b.depthPerWorld = ADAPTIVE ? abs(dot(lightDepthGradient(first.shadowMatrix, world), toLight))
                               : 0.0;
    b.cosine = dot(receiverFace, toLight);
    b.sinRadius = lightSine(light, first, world); // a sun's: every cascade's the same
    return b;
}

Receiver cascadeReceiver(CascadeBase b, ShadowViewData view, out bool inside) {
    float offset = b.offsetScale * view.texel.x;
    Receiver r;
    r.uv = (view.shadowMatrix * vec4(b.world + b.normal * offset, 1.0)).xy;
    r.depth = b.depth + offset * b.depthAlong;
    inside = insideMap(r.uv, r.depth);
    r.gradient = b.gradient / view.fromFirst.xy;
    r.layer = view.texel.z;
    r.kernelScale = view.cascade.z;
    r.uvDx = b.footprint.xy * view.fromFirst.xy;
    r.uvDy = b.footprint.zw * view.fromFirst.xy;
    noAdaptiveTerms(r);
    if (ADAPTIVE) applyAdaptiveBias(r, view.texel.x, b.depthPerWorld, b.cosine, b.sinRadius);
    return r;
}

// What the technique is handed at a receiver of `view`.
TechniqueInput techniqueInput(Receiver r, ShadowViewData view, ivec2 p, uint stage) {
    TechniqueInput at;
    at.r = r;
    at.view = view;
    at.mapSize = VIRTUAL_MAPS ? virtualSize(view) : push.light.z;
    at.pixel = uvec2(p);
    at.stage = stage;
    at.blockers = vec2(0.0);
    at.zBlocker = 0.0;
    at.world = vec3(0.0);
    at.face = vec3(0.0);
    at.sinRadius = 0.0;
    at.horizon = false;
    return at;
}

// The technique at a receiver of `view` (lit outside the view's frustum, which nothing in its map
// can shadow).
float evaluate(Receiver r, bool inside, ShadowViewData view, ivec2 p) {
    detail = inside ? evaluateTechnique(TECHNIQUE, techniqueInput(r, view, p, STAGE_WHOLE))
                    : vec4(1.0, 1.0, 0.0, 0.0);
    return detail.x;
}

// The technique's visibility of one pixel through the light's shadow view k.
float visibilityThrough(uint k, LightData light, ivec2 p, vec3 world, vec3 normal, float depth) {
    ShadowViewData view = viewOf(k);
    bool inside;
    Receiver r = makeReceiver(light, view, p, world, normal, depth, inside);
    return evaluate(r, inside, view, p);
}

// The technique's visibility of one pixel through the sun's cascade i.
float visibilityThroughCascade(CascadeBase b, uint i, ivec2 p) {
    ShadowViewData view = viewOf(i);
    bool inside;
    Receiver r = cascadeReceiver(b, view, inside);
    return evaluate(r, inside, view, p);
}

// Virtual maps: the technique through the level the pixel wants (virtualChoice), or the first
// coarser one whose page at the receiver is resident (a page not yet rendered, or one a full pool
// could not hold); lit outside a spot's or a face's frustum, or when no level holds it.
float visibilityThroughVirtual(LightData light, ivec2 p, vec3 world, vec3 normal, float depth) {
    VirtualChoice c = virtualChoice(light, world, pixelWorldSize(p, depth, world));
    for (uint l = c.level; l < c.count; ++l) {
        ShadowViewData view = views[c.first + l];
        bool inside;
        Receiver r = makeReceiver(light, view, p, world, normal, depth, inside);
        if (!inside) {
            if (LIGHT_TYPE != LIGHT_DIRECTIONAL) break;
            continue; // a finer clipmap level's window ends before the receiver
        }
        uint size = virtualSize(view);
        ivec2 texel = clamp(ivec2(floor(r.uv * float(size))), ivec2(0), ivec2(int(size) - 1));
        if (virtualEntry(texel, size, uint(view.texel.z)) != VIRTUAL_NOT_RESIDENT)
            return evaluate(r, true, view, p);
    }
    detail = vec4(1.0, 1.0, 0.0, 0.0);
    return 1.0;
}

// Whether a kernel of `radius` texels around the receiver stays inside its view's map.
bool holds(Receiver r, bool inside, float radius) {
    float margin = radius / float(push.light.z);
    return inside && all(greaterThanEqual(r.uv, vec2(margin))) &&
           all(lessThanEqual(r.uv, vec2(1.0 - margin)));
}

// A technique that searches blockers (BLOCKER_SEARCH) for a pixel of a sun's cascade `i`. Its
// kernels follow the light's size, and frame.filterLimits.x caps them in texels of the map sampled: the
// blocker search runs in the finest cascade from i whose texels hold it under the cap (else the
// coarsest that holds the pixel, else i), and the penumbra is filtered in the finest cascade from
// i that holds it (else where the search ran), so contact shadows keep the fine texels and wide
// penumbrae are not clipped. The cascades share one orientation and depth range
// (src/core/cascades.cpp): light view distances carry over. One search and one filter run, in the
// cascades chosen first: the loops over cascades unroll and only pick.
float searchThroughCascades(CascadeBase b, uint i, ivec2 p) {
    uint mapSize = push.light.z;
    float cap = frame.filterLimits.x;
    uint searchIn = i;
    bool found = false, settled = false;
    for (uint j = 0u; j < LIGHT_VIEWS; ++j) {
        ShadowViewData view = views[push.light.w + j];
        bool inside;
        Receiver r = cascadeReceiver(b, view, inside);
        float search = blockerSearchRadius(view, viewDistance(view, r.depth), mapSize);
        if (j >= i && !settled && holds(r, inside, min(search, cap))) {
            searchIn = j;
            found = true;
            settled = search <= cap;
        }
    }
    ShadowViewData searchView = viewOf(searchIn);
    bool inside;
    Receiver rs = cascadeReceiver(b, searchView, inside);
    if (!found && !inside) { // outside the light's frustum: lit, as evaluate says
        detail = vec4(1.0, 1.0, 0.0, 0.0);
        return 1.0;
    }
    vec2 blockers = evaluateTechnique(TECHNIQUE, techniqueInput(rs, searchView, p, STAGE_SEARCH)).xy;
    float zBlocker = viewDistance(searchView, blockers.y);
    uint filterIn = searchIn;
    bool chosen = false;
    for (uint k = 0u; k + 1u < LIGHT_VIEWS; ++k) {
        ShadowViewData view = views[push.light.w + k];
        bool insideK;
        Receiver r = cascadeReceiver(b, view, insideK);
        float radius = penumbraRadius(view, viewDistance(view, r.depth), zBlocker, mapSize);
        if (k >= i && k < searchIn && !chosen && radius <= cap && holds(r, insideK, radius)) {
            filterIn = k;
            chosen = true;
        }
    }
    ShadowViewData filterView = viewOf(filterIn);
    Receiver rf = cascadeReceiver(b, filterView, inside);
    if (blockers.x == 0.0) {
        detail = vec4(1.0, blockers.y, 0.0, 0.0);
    } else {
        TechniqueInput at = techniqueInput(rf, filterView, p, STAGE_FILTER);
        at.blockers = blockers;
        at.zBlocker = zBlocker;
        detail = evaluateTechnique(TECHNIQUE, at);
    }
    return detail.x;
}

// The visibility of a pixel through cascade i of the sun's.
float throughCascade(CascadeBase b, uint i, ivec2 p) {
    return BLOCKER_SEARCH ? searchThroughCascades(b, i, p) : visibilityThroughCascade(b, i, p);
}

// The pixel this invocation evaluates (off the image: none).
ivec2 invocationPixel() {
    if (CHECKERBOARD == CHECKERBOARD_EVEN) return checkerboardPixel(gl_GlobalInvocationID.xy, 0u);
    if (CHECKERBOARD == CHECKERBOARD_LIST) {
        uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        uint i = group * CHECKERBOARD_LIST_GROUP + gl_LocalInvocationIndex;
        return i < traceList.head.count ? unpackPixel(traceList.pixels[i]) : ivec2(-1);
    }
    return ivec2(gl_GlobalInvocationID.xy);
}

// Light i's visibility at the pixel, for the fused composite: this dispatch's own in `current`,
// the earlier dispatches' from their layers.
float current;
ivec2 pixel;
float visibilityOf(uint i, LightData light) {
    float layer = light.cone.w;
    float stored = imageLoad(visibility, ivec3(pixel, max(int(layer), 0))).r;
    return i == push.light.x ? current : layer >= 0.0 ? stored : 1.0;
}
#define LIGHT_VISIBILITY(i, light) visibilityOf(i, light)
#include "shading.glsl"

void main() {
    ivec2 p = invocationPixel();
    pixel = p;
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    // Lavapipe runs both sides of a branch anyway: the pixel's geometry is reconstructed once,
    // for the technique and the shading, background or not.
    vec3 world = worldPosition(frame.invViewProj, p, size, depth);
    vec4 normals = texelFetch(gNormal, p, 0);
    vec3 normal = shadingNormal(normals);
    float v = nanValue();
    if (!isBackground(depth)) {
        if (FOOTPRINT) {
            vec3 face = faceNormal(normals);
            footprintDx = onReceiverPlane(p + ivec2(1, 0), depth, world, face) - world;
            footprintDy = onReceiverPlane(p + ivec2(0, 1), depth, world, face) - world;
        }
        if (ADAPTIVE) {
            receiverFace = faceNormal(normals);
            receiverCurvature = surfaceCurvature(p, depth, world, normal);
        }
        LightData light = lights[push.light.x];
        uint k = lightViewOf(light, world);
        if (TRACES_FIELD) {
            // No shadow map: the field holds the whole scene, the tracer its own horizon.
            TechniqueInput at = techniqueInput(Receiver(vec2(0.0), 0.0, vec2(0.0), 0.0, 1.0,
                                                        vec2(0.0), vec2(0.0), vec2(0.0),
                                                        vec2(-1e30, 1e30), 0.0),
                                               viewOf(k), p, STAGE_WHOLE);
            at.light = light;
            at.world = world;
            at.face = faceNormal(normals);
            at.sinRadius = lightSine(light, viewOf(k), world);
            at.horizon = HORIZON != 0u;
            detail = evaluateTechnique(TECHNIQUE, at);
            v = detail.x;
        } else if (VIRTUAL_MAPS) {
            v = visibilityThroughVirtual(light, p, world, normal, depth);
        } else if (LIGHT_TYPE == LIGHT_DIRECTIONAL && LIGHT_VIEWS > 1u) {
            // A sun's cascade: the first whose slice reaches the pixel's view distance.
            float z = cameraViewDistance(world);
            uint i = sunCascadeOf(z);
            CascadeBase b = cascadeBase(light, p, world, normal, depth);
            v = throughCascade(b, i, p);
            vec4 c = viewOf(i).cascade;
            // The blend band: mix into the next cascade (without csm.blend, no band: lavapipe
            // would still pay for the second cascade's branch).
            if (CASCADE_BLEND && i + 1u < LIGHT_VIEWS && z > c.y)
                v = mix(v, throughCascade(b, i + 1u, p), cascadeBlendWeight(z, c.y, c.x));
        } else {
            v = visibilityThrough(k, light, p, world, normal, depth);
        }
        float nDotL = dot(faceNormal(normals), directionToLight(light, world));
        // (every view of a light has its size and kind: a virtual map's first, read directly)
        float sinRadius = VIRTUAL_MAPS ? lightSine(light, views[push.light.w], world)
                                       : lightSine(light, viewOf(k), world);
        if (HORIZON != 0u && !TRACES_FIELD) v *= horizonVisibility(nDotL, sinRadius);
        v = min(v, backFacingVisibility(nDotL, sinRadius));
    }
    imageStore(visibility, ivec3(p, int(push.light.y)), vec4(v));
    if (WRITE_INTERMEDIATES)
        imageStore(intermediates, ivec3(p, int(push.light.y)), vec4(v, detail.yzw));
    if (FUSED_COMPOSITE) {
        current = v;
        vec3 color = isBackground(depth) ? frame.background.rgb
                                         : shadePixel(world, normal, texelFetch(gAlbedo, p, 0).rgb);
        imageStore(outColor, p, vec4(srgbEncode(color), 1.0));
    }
}
