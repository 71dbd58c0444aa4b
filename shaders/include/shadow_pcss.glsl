// Percentage-closer soft shadows [Fernando 2005; seed 001]: blocker search, penumbra estimate,
// then PCF over a kernel of the estimated width. Distances are light view distances (world
// units along the light's axis); see docs/techniques.md for the derivations.
// Its geometry (the search and penumbra radii) is in light_geometry.h, shared with the CPU
// reference; src/shadows/pcss.cpp mirrors the loops. With SPEC_BLOCKER_SEARCH the visibility
// pass may run the search and the filter in different cascades of a sun (STAGE_SEARCH,
// STAGE_FILTER).
#ifndef PENUMBRA_SHADOW_PCSS_GLSL
#define PENUMBRA_SHADOW_PCSS_GLSL
#include "params_pcf.h"
#include "technique_input.glsl"

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
        vec4 depths = gatherDepths(map, base, size, r.layer);
        vec4 lit = gatherTests(map, base, size, r, dzRange);
        vec4 blocks = vec4(1.0) - lit;
        sum += dot(blocks, depths);
        count += blocks.x + blocks.y + blocks.z + blocks.w;
    }
    averageDepth = count > 0.0 ? sum / count : 1.0;
    return count;
}

// The blocker search over the light's extent seen from the receiver, capped at pcss.maxRadius
// texels of this view (pcss.cubeRadius on a cube face): x blocking texels found, y their average depth in this view (1: none).
vec2 pcssSearch(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view, float turns) {
    float search = min(blockerSearchRadius(view, viewDistance(view, r.depth), mapSize),
                       kernelCap(view, pcss.maxRadius, pcss.cubeRadius));
    float blockerDepth;
    float blockers = searchBlockers(map, r, mapSize, pcss.blockerSamples, max(search, 0.5), turns,
                                    frame.biasParams.xy, blockerDepth);
    return vec2(blockers, blockerDepth);
}

// The penumbra of blockers at light view distance zBlocker (found by `blockers`, a pcssSearch,
// in this view or a coarser cascade of it), filtered in this view. The result as
// shadowPcssDetail's.
vec4 pcssFilter(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view, float zBlocker,
                vec2 blockers, float turns) {
    float radius = clamp(penumbraRadius(view, viewDistance(view, r.depth), zBlocker, mapSize),
                         0.5, kernelCap(view, pcss.maxRadius, pcss.cubeRadius));
    // Only blockers and a penumbra under a texel: inside the umbra.
    if (blockers.x == 4.0 * float(pcss.blockerSamples) && radius <= 1.0)
        return vec4(0.0, blockers.y, blockers.x, radius);
    float v = poissonTaps(map, r, mapSize, pcss.filterSamples, radius, turns, frame.biasParams.xy);
    return vec4(snapToExtremes(v), blockers.y, blockers.x, radius);
}

// x visibility, y average blocker depth, z blocking texels found, w filter radius (texels).
// pcss.maxRadius is in texels of the view sampled; the visibility pass spreads a sun's PCSS over
// its cascades so that the cap does not clip what a coarser cascade can hold.
vec4 shadowPcssDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view, uvec2 pixel) {
    float turns = turnedByFrame(rotationTurns(pcss.rotation, pixel), frame.motion.y);
    vec2 blockers = pcssSearch(map, r, mapSize, view, turns);
    if (blockers.x == 0.0) return vec4(1.0, blockers.y, 0.0, 0.0); // nothing in the way: lit
    return pcssFilter(map, r, mapSize, view, viewDistance(view, blockers.y), blockers, turns);
}

vec4 evaluatePcss(TechniqueInput at) {
    float turns = turnedByFrame(rotationTurns(pcss.rotation, at.pixel), frame.motion.y);
    if (at.stage == STAGE_SEARCH)
        return vec4(pcssSearch(shadowMap, at.r, at.mapSize, at.view, turns), 0.0, 0.0);
    if (at.stage == STAGE_FILTER)
        return pcssFilter(shadowMap, at.r, at.mapSize, at.view, at.zBlocker, at.blockers, turns);
    return shadowPcssDetail(shadowMap, at.r, at.mapSize, at.view, at.pixel);
}

#endif
