// Shadow-map ray tracing [after Unreal Engine 5's virtual shadow maps, Epic Games 2022]: rays from
// the receiver towards points spread over the light, each marched through the light's depth map;
// the visibility is the fraction of rays no occluder blocks. The march's maths (smrt_march.h) is
// shared with the CPU reference, src/shadows/smrt.cpp, which mirrors these loops. It reads the map
// texel by texel (fetchDepth), so it runs on virtual maps, cascades and cube faces alike.
#ifndef PENUMBRA_SHADOW_SMRT_GLSL
#define PENUMBRA_SHADOW_SMRT_GLSL
#include "kernels.h"
#include "smrt_march.h"
#include "technique_input.glsl"

// The light view distance the map holds at map position uv (the nearest texel, clamped).
float smrtStored(sampler2DArray map, ShadowViewData view, vec2 uv, uint mapSize, float layer) {
    ivec2 texel = clamp(ivec2(floor(uv * float(mapSize))), ivec2(0), ivec2(int(mapSize) - 1));
    return viewDistance(view, fetchDepth(map, texel, float(mapSize), layer));
}

// The march's point at s along d from p, read against the map.
SmrtPoint smrtPoint(sampler2DArray map, ShadowViewData view, vec3 p, vec3 d, float s,
                    uint mapSize, float layer) {
    SmrtPoint x = smrtPointAt(view, p, d, s);
    smrtSetStored(x, view, smrtStored(map, view, x.uv, mapSize, layer), mapSize, smrt.slope);
    return x;
}

// x visibility, y rays blocked, z of those, the rays blocked only by extrapolation, w the mean
// march length in texels of the map (over the rays traced).
vec4 shadowSmrtDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view,
                      uvec2 pixel) {
    float turns = rotationTurns(smrt.rotation, pixel);
    uvec2 budget = smrtBudget(view, smrt);
    uint rays = budget.x, samples = budget.y;
    vec3 p = smrtViewPoint(view, r.uv, viewDistance(view, r.depth));
    SmrtPoint receiver = smrtPoint(map, view, p, vec3(0.0), 0.0, mapSize, r.layer);
    float blocked = 0.0, extrapolated = 0.0, marched = 0.0, traced = 0.0;
    bool grazed = smrtIsBehind(receiver);
    // From the light's rim inwards: the first rays reach round its rim.
    for (uint ray = 0u; ray < rays; ++ray) {
        uint k = rays - 1u - ray;
        // The first smrt.adaptive rays all blocked, or all lit without one passing behind the
        // surface: fully in shadow or fully lit, no more rays.
        if (ray > 0u && ray == smrt.adaptive && (blocked == traced || (blocked == 0.0 && !grazed))) break;
        vec3 d = smrtRayDirection(view, p, k, rays, turns);
        SmrtMarch march = smrtMarch(view, p, d, smrt.maxRadius, mapSize);
        float jitter = fract(turns * 2.618034 + float(k) * 0.7548777);
        SmrtPoint last = receiver;
        bool crossed = false;
        for (uint i = 0u; i < samples && !crossed; ++i) {
            float s = smrtSampleDistance(march, p, d, i, samples, jitter);
            SmrtPoint next = smrtPoint(map, view, p, d, s, mapSize, r.layer);
            grazed = grazed || smrtIsBehind(next);
            if (smrtIsBehind(next) != smrtIsBehind(last)) {
                SmrtPoint a = last, b = next;
                for (uint j = 0u; j < smrt.refine; ++j) {
                    SmrtPoint m = smrtPoint(map, view, p, d, 0.5 * (a.s + b.s), mapSize, r.layer);
                    if (smrtIsBehind(m) == smrtIsBehind(a)) a = m;
                    else b = m;
                }
                float margin;
                crossed = smrtCrosses(view, a, b, smrt.slope, margin);
            }
            last = next;
        }
        // A ray that ends behind the surface is extrapolated on towards the light: it meets the
        // occluder it is behind (nothing lies nearer the light than the near plane).
        bool hit = crossed || smrtIsBehind(last);
        blocked += hit ? 1.0 : 0.0;
        extrapolated += hit && !crossed ? 1.0 : 0.0;
        marched += length((smrtProject(view, p + march.extent * d) - r.uv) * float(mapSize));
        traced += 1.0;
    }
    return vec4(1.0 - blocked / traced, blocked, extrapolated, marched / traced);
}

vec4 evaluateSmrt(TechniqueInput at) {
    return shadowSmrtDetail(shadowMap, at.r, at.mapSize, at.view, at.pixel);
}

#endif
