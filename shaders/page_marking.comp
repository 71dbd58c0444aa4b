#version 460
// Virtual maps' page marking (virtual.enabled; src/render/virtual_passes.cpp), after the
// G-buffer: the visible pixels ask, for one light, for the pages of the level they will read
// (virtual_levels.glsl) that the technique's filter reaches around them. The host reads the
// requests back after the frame, adds each page's chain of coarser pages (withCoarserPages: what
// a reader falls back on when the pool is full) and makes them resident
// (src/core/virtual_maps.h).
#include "bindings.h"
#include "frame_block.h"
#include "light_geometry.h"
#include "pass_types.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_LIGHT_TYPE) const uint LIGHT_TYPE = LIGHT_DIRECTIONAL;
#define LIGHT_TYPE_OF(light) LIGHT_TYPE
#include "gbuffer.glsl"
#include "shadow_common.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = MARK_LIGHTS, std140) uniform Lights { LightData lights[MAX_UNIFORM_LIGHTS]; };
layout(set = 0, binding = MARK_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = MARK_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = MARK_VIEWS, std140) uniform Views { ShadowViewData views[MAX_UNIFORM_VIEWS]; };
layout(set = 0, binding = MARK_REQUESTS, std430) writeonly buffer Requests { uint requests[]; };
layout(push_constant) uniform Push { VisibilityPush push; };
#include "virtual_levels.glsl"

// Every page within `reach` texels of uv of a level of `pages` pages a side, its table from
// `tableOffset`. `marked`: the entry this invocation marked last, not stored again.
void markAround(uint tableOffset, uint pages, vec2 uv, float reach, inout uint marked) {
    uint pageSize = frame.virtualPages.x;
    float size = float(pages * pageSize);
    ivec2 edge = ivec2(int(size) - 1);
    ivec2 lo = virtualPageOf(clamp(ivec2(floor(uv * size - reach)), ivec2(0), edge), pageSize);
    ivec2 hi = virtualPageOf(clamp(ivec2(floor(uv * size + reach)), ivec2(0), edge), pageSize);
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            uint entry = virtualEntryIndex(tableOffset, pages, ivec2(x, y));
            if (entry != marked) requests[entry] = 1u;
            marked = entry;
        }
}

// The ray through pixel q meeting the plane through `world` with normal `face` (the point at
// `depth` when the plane is seen edge-on).
vec3 onPlane(ivec2 q, float depth, vec3 world, vec3 face) {
    uvec2 size = frame.imageSize.xy;
    vec3 near = worldPosition(frame.invViewProj, q, size, 1.0);
    vec3 along = worldPosition(frame.invViewProj, q, size, depth) - near;
    float facing = dot(along, face);
    if (abs(facing) <= 1e-6 * length(along)) return near + along;
    return near + along * (dot(world - near, face) / facing);
}

// The pages of light's levels first .. first + count - 1 (finest first) that a receiver at
// `world` reads from `level` on (the first whose window holds it), within `reach` texels, widened
// by `spread` (the block's extent in the finest level's uv). False when no level holds it.
void markReceiver(uint first, uint count, uint level, vec3 world, float reach, vec2 spread,
                  inout uint marked) {
    // Every level's uv is an affine map of the finest's (fromFirst: a sun's levels share its
    // orientation and depth; a spot's or a face's mips, its projection): a record's three
    // fields are read per level, not the whole record.
    vec4 s = views[first].shadowMatrix * vec4(world, 1.0);
    if (s.w <= 0.0 || s.z / s.w > 1.0) return;
    vec2 uv0 = s.xy / s.w;
    for (uint l = level; l < count; ++l) {
        uint v = first + l;
        vec4 fromFirst = views[v].fromFirst;
        vec2 uv = fromFirst.xy * uv0 + fromFirst.zw;
        if (insideMap(uv, 0.0)) {
            float texels = float(uint(views[v].cascade.w) * frame.virtualPages.x);
            float block = min(max(spread.x * fromFirst.x, spread.y * fromFirst.y) * texels,
                              2.0 * float(frame.virtualPages.x));
            markAround(uint(views[v].texel.z), uint(views[v].cascade.w), uv, reach + block,
                       marked);
            return;
        }
        if (LIGHT_TYPE != LIGHT_DIRECTIONAL) return; // outside the frustum: nothing to read
    }
}

// One pixel of every MARK_BLOCK^2 (lavapipe pays for each pixel a pass reads about what four
// cascades' rasterization costs): the pages of the level it reads within the filter's reach,
// widened by how far its block's pixels lie from it in that level, on its triangle's plane
// (capped at two pages: a grazing plane's far pixels read the coarser pages the host adds).
// A block's corner in another cube face marks that face's pages around itself. A surface
// smaller than a block that no block's pixel lands on reads the coarser pages the host adds.
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy) * int(MARK_BLOCK) + int(MARK_BLOCK / 2u);
    uvec2 size = frame.imageSize.xy;
    p = min(p, ivec2(size) - 1);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy * MARK_BLOCK, size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    if (isBackground(depth)) return;
    vec3 world = worldPosition(frame.invViewProj, p, size, depth);
    vec3 face = faceNormal(texelFetch(gNormal, p, 0));
    LightData light = lights[push.light.x];
    VirtualChoice c = virtualChoice(light, world, pixelWorldSize(p, depth, world));
    // The block's corners on the plane, and their spread in the finest level's uv.
    ShadowViewData finest = views[c.first];
    vec4 s = finest.shadowMatrix * vec4(world, 1.0);
    vec2 uv0 = s.xy / s.w;
    int h = int(MARK_BLOCK / 2u);
    vec3 corners[4];
    vec2 spread = vec2(0.0);
    for (int k = 0; k < 4; ++k) {
        corners[k] = onPlane(p + ivec2((k & 1) != 0 ? h : -h, (k & 2) != 0 ? h : -h), depth,
                             world, face);
        vec4 t = finest.shadowMatrix * vec4(corners[k], 1.0);
        if (t.w > 0.0) spread = max(spread, abs(t.xy / t.w - uv0));
    }
    // The normal offset moves the receiver by up to bias.normal texels before the lookup.
    float reach = frame.virtualLod.y + light.bias.z + 1.0;
    uint marked = 0xffffffffu;
    markReceiver(c.first, c.count, c.level, world, reach, spread, marked);
    if (LIGHT_TYPE == LIGHT_POINT) {
        uint centreFace = cubeFace(world - light.positionType.xyz);
        for (int k = 0; k < 4; ++k) {
            uint f = cubeFace(corners[k] - light.positionType.xyz);
            if (f != centreFace)
                markReceiver(light.views.x + f * c.count, c.count, c.level, corners[k], reach,
                             vec2(0.0), marked);
        }
    }
}
