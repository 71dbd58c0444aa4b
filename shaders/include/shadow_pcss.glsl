// Percentage-closer soft shadows [Fernando 2005; seed 001]: blocker search, penumbra estimate,
// then PCF over a kernel of the estimated width. Distances are light view distances (world
// units along the light's axis); see docs/techniques.md for the derivations.
// src/reference/filter_reference.cpp mirrors this file on the CPU.
#ifndef PENUMBRA_SHADOW_PCSS_GLSL
#define PENUMBRA_SHADOW_PCSS_GLSL
#include "shadow_pcf.glsl"

// Light view distance of a normalised light depth (inverse of the seeds' depth mappings).
float viewDistance(ShadowViewData view, float depth) {
    float n = view.frustum.x, f = view.frustum.y;
    return view.texel.y > 0.5 ? n * f / (f - depth * (f - n)) : n + depth * (f - n);
}

// Texels per world unit laterally at view distance z (u axis).
float texelsPerWorld(ShadowViewData view, float z, uint mapSize) {
    float worldPerUv = view.frustum.z * (view.texel.y > 0.5 ? z : 1.0);
    return float(mapSize) / worldPerUv;
}

// Search radius (texels): the light seen from the receiver, cut by the near plane, where the
// nearest possible blocker lies. Perspective: R (z_r - n) / z_r at the near plane;
// orthographic: (z_r - n) tan(half angle).
float blockerSearchRadius(ShadowViewData view, float zReceiver, uint mapSize) {
    float n = view.frustum.x, size = view.texel.w;
    float world = view.texel.y > 0.5 ? size * (zReceiver - n) / zReceiver
                                     : (zReceiver - n) * size;
    return world * texelsPerWorld(view, view.texel.y > 0.5 ? n : 1.0, mapSize);
}

// Penumbra radius (texels at the receiver): perspective, the seed's
// w = (d_receiver - d_blocker) w_light / d_blocker with distances along the light; orthographic,
// (z_r - z_b) tan(half angle).
float penumbraRadius(ShadowViewData view, float zReceiver, float zBlocker, uint mapSize) {
    float size = view.texel.w;
    float world = view.texel.y > 0.5 ? (zReceiver - zBlocker) * size / zBlocker
                                     : (zReceiver - zBlocker) * size;
    return world * texelsPerWorld(view, zReceiver, mapSize);
}

// Average depth of the texels that block the receiver over `n` gathers on the Poisson disk of
// `radius` texels; returns how many of the 4 n texels block.
float searchBlockers(sampler2DArray map, Receiver r, uint mapSize, uint n, float radius, float turns,
                     vec2 dzRange, out float averageDepth) {
    float angle = 6.28318530718 * turns;
    float c = cos(angle), s = sin(angle), size = float(mapSize);
    vec2 centre = r.uv * size;
    float sum = 0.0, count = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec2 d = poissonPoint(i);
        vec2 p = centre + radius * vec2(c * d.x - s * d.y, s * d.x + c * d.y) - 0.5;
        ivec2 base = ivec2(floor(p));
        vec4 depths = textureGather(map, vec3((vec2(base) + 1.0) / size, r.layer), 0);
        vec4 lit = gatherTests(map, base, size, r, dzRange);
        vec4 blocks = vec4(1.0) - lit;
        sum += dot(blocks, depths);
        count += blocks.x + blocks.y + blocks.z + blocks.w;
    }
    averageDepth = count > 0.0 ? sum / count : 1.0;
    return count;
}

// x visibility, y average blocker depth, z blocking texels found, w filter radius (texels).
vec4 shadowPcssDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view, uvec2 pixel) {
    vec2 dzRange = frame.biasParams.xy;
    float turns = rotationTurns(frame.pcssMode.z, pixel);
    float maxRadius = frame.pcssParams.x;
    float zReceiver = viewDistance(view, r.depth);
    float search = min(blockerSearchRadius(view, zReceiver, mapSize), maxRadius);
    float blockerDepth;
    uint searchTaps = frame.pcssMode.x;
    float blockers = searchBlockers(map, r, mapSize, searchTaps, max(search, 0.5), turns, dzRange,
                                    blockerDepth);
    if (blockers == 0.0) return vec4(1.0, blockerDepth, 0.0, 0.0); // nothing in the way: lit
    float zBlocker = viewDistance(view, blockerDepth);
    float radius = clamp(penumbraRadius(view, zReceiver, zBlocker, mapSize), 0.5, maxRadius);
    // Only blockers and a penumbra under a texel: inside the umbra.
    if (blockers == 4.0 * float(searchTaps) && radius <= 1.0)
        return vec4(0.0, blockerDepth, blockers, radius);
    float v = poissonTaps(map, r, mapSize, frame.pcssMode.y, radius, turns, dzRange);
    return vec4(snapToExtremes(v), blockerDepth, blockers, radius);
}

#endif
