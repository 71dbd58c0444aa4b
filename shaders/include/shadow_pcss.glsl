// Percentage-closer soft shadows [Fernando 2005; seed 001]: blocker search, penumbra estimate,
// then PCF over a kernel of the estimated width. Distances are light view distances (world
// units along the light's axis); see docs/techniques.md for the derivations.
// Its geometry (the search and penumbra radii) is in filter_math.h, shared with the CPU
// reference; src/reference/filter_reference.cpp mirrors the loops.
#ifndef PENUMBRA_SHADOW_PCSS_GLSL
#define PENUMBRA_SHADOW_PCSS_GLSL
#include "shadow_pcf.glsl"

// Average depth of the texels that block the receiver over `n` gathers on the Poisson disk of
// `radius` texels; returns how many of the 4 n texels block.
float searchBlockers(sampler2DArray map, Receiver r, uint mapSize, uint n, float radius, float turns,
                     vec2 dzRange, out float averageDepth) {
    float size = float(mapSize);
    vec2 centre = r.uv * size;
    float sum = 0.0, count = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec2 p = centre + rotatedOffset(poissonPoint(i), turns, radius) - 0.5;
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
    float maxRadius = frame.pcssParams.x * r.kernelScale;
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
