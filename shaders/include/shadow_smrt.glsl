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
#include "shadow_hard.glsl"

// smrt.hidden (bit 0: spots and suns) and smrt.cubeHidden (bit 1: point lights), a constant of
// the pipeline, as is its light's kind (LIGHT_TYPE): lavapipe runs the march loop's branches
// masked, and its checks would cost every pixel where it is off.
layout(constant_id = SPEC_SMRT_HIDDEN) const uint SMRT_HIDDEN_LIGHTS = 0u;
const bool SMRT_HIDDEN = (SMRT_HIDDEN_LIGHTS & (LIGHT_TYPE == LIGHT_POINT ? 2u : 1u)) != 0u;

// The light view distance the map holds at map position uv (the nearest texel, clamped).
float smrtStored(sampler2DArray map, ShadowViewData view, vec2 uv, uint mapSize, float layer) {
    ivec2 texel = clamp(ivec2(floor(uv * float(mapSize))), ivec2(0), ivec2(int(mapSize) - 1));
    return viewDistance(view, fetchDepth(map, texel, float(mapSize), layer));
}

// The march's point at s along d from p, read against the map.
SmrtPoint smrtPoint(sampler2DArray map, ShadowViewData view, SmrtScale scale, vec3 p, vec3 d,
                    float s, uint mapSize, float layer) {
    SmrtPoint x = smrtPointAt(view, scale, p, d, s);
    smrtSetStored(x, view, scale, smrtStored(map, view, x.uv, mapSize, layer), smrt.slope);
    return x;
}

// Ring k's block (at `level`) through its tiles' children, each against the ceiling at its own
// distance, never nearer than the ring's inner radius (smrtLastChild, smrtTileDistance).
bool smrtChildrenHold(usampler2DArray bounds, ShadowViewData view, SmrtCeiling c, vec2 at,
                      ivec4 block, int level, int boundsSize, uint mapSize, int layer,
                      float inner, ivec4 covered) {
    if (level == 0) return false;
    int child = level - 1;
    int levelSize = max(boundsSize >> level, 1), childSize = max(boundsSize >> child, 1);
    int lastX = smrtLastChild(block.z, levelSize, childSize);
    int lastY = smrtLastChild(block.w, levelSize, childSize);
    for (int y = 2 * block.y; y <= lastY; ++y)
        for (int x = 2 * block.x; x <= lastX; ++x) {
            if (smrtInBlock(ivec2(x, y), covered)) continue; // the inner ring's (smrtInnerBlock)
            float d = smrtTileDistance(at, ivec2(x, y), child, childSize, mapSize);
            float ceiling = smrtDepthOf(view, smrtLitCeiling(c, max(inner, d)));
            if (uintBitsToFloat(texelFetch(bounds, ivec3(x, y, layer), child).r) < ceiling)
                return false;
        }
    return true;
}

// smrt.skipLit: whether no ray of the pixel can pass behind the map's surface, so that it is fully
// lit without tracing one (smrtLitCeiling). Ring 0 reads the 3x3 texels round p's; ring k a 2x2
// block of the bounds' level k (`bounds`: the nearest depth over each tile, as float bits; built by
// smrt_bounds.comp and smrt_bounds_mip.comp), against the ceiling 2^(k-1) texels out. Not on
// virtual maps (no bounds) nor for a receiver outside the map (its clamped reads would lie nearer
// the map's edge than the points that make them).
bool smrtProvenLit(sampler2DArray map, usampler2DArray bounds, ShadowViewData view, vec3 p,
                   vec2 uv, uint mapSize, float layer) {
    vec2 at = uv * float(mapSize);
    if (VIRTUAL_MAPS || any(lessThan(at, vec2(0.0))) ||
        any(greaterThanEqual(at, vec2(float(mapSize)))))
        return false;
    SmrtCeiling c = smrtCeilingOf(view, p, mapSize, smrt.slope);
    float ceiling = smrtDepthOf(view, smrtLitCeiling(c, 0.0));
    ivec2 home = ivec2(floor(at));
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 texel = clamp(home + ivec2(i, j), ivec2(0), ivec2(int(mapSize) - 1));
            if (fetchDepth(map, texel, float(mapSize), layer) < ceiling) return false;
        }
    uint rings = smrtBoundsRings(smrt.maxRadius);
    int levels = textureQueryLevels(bounds);
    // A level's size by arithmetic: lavapipe 22.3 answers textureSize(bounds, level) with level 0's
    // size when the level changes from one iteration of the loop to the next.
    int boundsSize = textureSize(bounds, 0).x;
    int l = int(layer);
    // Outermost first: where a caster stands in the light's way, the wide rings fail first, before
    // the near ones spend reads on their children.
    for (uint k = rings; k >= 1u; --k) {
        int level = min(int(k), levels - 1);
        ivec4 block = smrtBoundsBlock(at, uint(level), max(boundsSize >> level, 1));
        uint nearest = min(min(texelFetch(bounds, ivec3(block.xy, l), level).r,
                               texelFetch(bounds, ivec3(block.zy, l), level).r),
                           min(texelFetch(bounds, ivec3(block.xw, l), level).r,
                               texelFetch(bounds, ivec3(block.zw, l), level).r));
        float inner = float(1u << (k - 1u));
        float ring = smrtDepthOf(view, smrtLitCeiling(c, inner));
        if (uintBitsToFloat(nearest) < ring &&
            !smrtChildrenHold(bounds, view, c, at, block, level, boundsSize, mapSize, l, inner,
                              smrtInnerBlock(at, k, level, boundsSize)))
            return false;
    }
    return true;
}

// smrt.gapSamples: whether the bounds prove that no point of the step from a to b lies behind the
// map (smrtLongStep). Virtual maps have no bounds: nothing is proven, and every long step in front
// of the surface is sampled again.
bool smrtStepClear(usampler2DArray bounds, ShadowViewData view, SmrtPoint a, SmrtPoint b,
                   uint mapSize, int layer, int levels, int boundsSize) {
    if (VIRTUAL_MAPS) return false;
    ivec4 box = smrtStepTexelBox(a, b, mapSize);
    int level = smrtStepLevel(box, levels);
    ivec4 tiles = smrtStepTiles(box, level, max(boundsSize >> level, 1));
    // The box's 2x2 tiles (or fewer, read twice): no loop, which lavapipe would run masked.
    uint nearest = min(min(texelFetch(bounds, ivec3(tiles.xy, layer), level).r,
                           texelFetch(bounds, ivec3(tiles.zy, layer), level).r),
                       min(texelFetch(bounds, ivec3(tiles.xw, layer), level).r,
                           texelFetch(bounds, ivec3(tiles.zw, layer), level).r));
    return uintBitsToFloat(nearest) >= smrtStepCeiling(view, a, b);
}

// A side change between two reads of the march: the interval (a, b) is halved smrt.refine times,
// then smrtCrosses decides whether the ray crossed the map's surface there (the mirror's
// `crosses`, src/shadows/smrt.cpp). The halvings' reads are iterations of the march's own loop:
// lavapipe runs a loop nested in the march for a whole group at every sample while one lane
// needs it, and a side change comes once or twice a ray. The ends are marks (SmrtMark).
struct SmrtRefine {
    bool on;       // halving (a, b)
    bool aBehind;  // the side a stays on (b, and end, lie on the other)
    uint done;     // halvings done
    SmrtMark a, b;
    SmrtMark end;  // the read that changed side, where the march goes on from
};

SmrtRefine smrtRefineOff() {
    SmrtMark none = SmrtMark(0.0, 0.0);
    return SmrtRefine(false, false, 0u, none, none, none);
}

SmrtRefine smrtRefineBetween(SmrtMark from, bool fromBehind, SmrtPoint to) {
    SmrtMark t = smrtMarkOf(to);
    return SmrtRefine(true, fromBehind, 0u, from, t, t);
}

// A read while halving replaces the end on its side (true); any other read counts towards the
// adaptive stop's `grazed` (false), and the march classifies it.
bool smrtHalving(inout SmrtRefine h, SmrtPoint m, inout bool grazed) {
    if (!h.on) {
        grazed = grazed || smrtIsBehind(m);
        return false;
    }
    if (smrtIsBehind(m) == h.aBehind) h.a = smrtMarkOf(m);
    else h.b = smrtMarkOf(m);
    ++h.done;
    return true;
}

// Whether the ray from p along d crossed a hidden surface at the march's candidate
// (smrtNoteHidden, smrtCrossedHidden; never without SMRT_HIDDEN, which the pipeline's constant
// folds away with this code).
bool smrtHiddenCrossed(sampler2DArray map, ShadowViewData view, SmrtScale scale,
                       SmrtHiddenCandidate c, vec3 p, vec3 d, uint mapSize, float layer) {
    if (!SMRT_HIDDEN || !c.found) return false;
    // The check reads neither point's `behind`.
    SmrtPoint first = smrtMarkPoint(view, scale, p, d, SmrtMark(c.first, 0.0), smrt.slope);
    SmrtPoint front = smrtMarkPoint(view, scale, p, d, SmrtMark(c.front, 0.0), smrt.slope);
    SmrtHiddenTexels t = smrtHiddenTexels(first, front, mapSize);
    float size = float(mapSize), margin;
    vec4 depths = vec4(fetchDepth(map, t.near.xy, size, layer), fetchDepth(map, t.near.zw, size, layer),
                       fetchDepth(map, t.far.xy, size, layer), fetchDepth(map, t.far.zw, size, layer));
    return smrtCrossedHidden(view, first, front, t, depths, mapSize, margin);
}

// smrtNoteHidden where SMRT_HIDDEN is on.
void smrtNoteHiddenHere(inout SmrtHiddenCandidate c, SmrtHidden h, float front, bool frontBehind) {
    if (SMRT_HIDDEN) smrtNoteHidden(c, h, front, frontBehind);
}

// smrtTrackHidden where SMRT_HIDDEN is on (its constant folds the tracking away elsewhere).
void smrtFollowHidden(inout SmrtHidden h, float s, bool behind) {
    if (SMRT_HIDDEN) smrtTrackHidden(h, s, behind);
}

// After smrt.refine halvings, smrtCrosses decides whether the ray from p along d crossed the
// surface (`crossed`); a side change it did not cross is smrt.hidden's candidate. The march then
// goes on from the read that changed side (h.end). False while halvings remain, or with none
// under way.
bool smrtSettled(ShadowViewData view, SmrtScale scale, vec3 p, vec3 d, inout SmrtRefine h,
                 inout SmrtHiddenCandidate candidate, SmrtHidden hidden, inout bool crossed) {
    if (!h.on || h.done != smrt.refine) return false;
    float margin;
    crossed = smrtCrosses(view, smrtMarkPoint(view, scale, p, d, h.a, smrt.slope),
                          smrtMarkPoint(view, scale, p, d, h.b, smrt.slope), smrt.slope, margin);
    if (!crossed) smrtNoteHiddenHere(candidate, hidden, h.end.s, !h.aBehind);
    h.on = false;
    return true;
}

// x visibility, y rays blocked, z of those, the rays blocked only by extrapolation, w the mean
// march length in texels of the map (over the rays traced).
vec4 shadowSmrtDetail(sampler2DArray map, Receiver r, uint mapSize, ShadowViewData view,
                      uvec2 pixel) {
    float turns = turnedByFrame(rotationTurns(smrt.rotation, pixel), frame.motion.y);
    uvec2 budget = smrtBudget(view, smrt);
    uint rays = budget.x, samples = budget.y, adaptive = smrtAdaptive(view, smrt);
    uint gapSamples = smrtGapSamples(view, smrt);
    vec3 p = smrtViewPoint(view, r.uv, viewDistance(view, r.depth));
    SmrtScale scale = smrtScaleOf(view, mapSize);
    if (smrt.skipLit != 0u && smrtProvenLit(map, shadowTable, view, p, r.uv, mapSize, r.layer))
        return vec4(1.0, 0.0, 0.0, 0.0);
    SmrtPoint receiver = smrtPoint(map, view, scale, p, vec3(0.0), 0.0, mapSize, r.layer);
    float blocked = 0.0, extrapolated = 0.0, marched = 0.0, traced = 0.0;
    bool grazed = smrtIsBehind(receiver);
    int l = int(r.layer);
    int levels = VIRTUAL_MAPS ? 1 : textureQueryLevels(shadowTable);
    int boundsSize = VIRTUAL_MAPS ? 1 : textureSize(shadowTable, 0).x;
    // The bounds' last level: one tile, the layer's nearest depth (virtual maps: none, no stop).
    float nearest = VIRTUAL_MAPS
                        ? -1e30
                        : smrtNearestBehind(view, uintBitsToFloat(texelFetch(
                                                      shadowTable, ivec3(0, 0, l), levels - 1).r));
    // From the light's rim inwards: the first rays reach round its rim.
    for (uint ray = 0u; ray < rays; ++ray) {
        uint k = rays - 1u - ray;
        // The first smrt.adaptive rays all blocked, or all lit without one passing behind the
        // surface: fully in shadow or fully lit, no more rays.
        if (ray > 0u && ray == adaptive && (blocked == traced || (blocked == 0.0 && !grazed))) break;
        vec3 d = smrtRayDirection(view, p, k, rays, turns);
        SmrtMarch march = smrtMarch(view, p, d, smrt.maxRadius, mapSize, samples);
        float jitter = fract(turns * 2.618034 + float(k) * 0.7548777);
        // The stop short of the light, on a ray that nears it (smrtNearestBehind).
        float stopAt = d.z < 0.0 ? nearest : -1e30;
        // The receiver's mark: s = 0 on any ray is p itself. Its side travels with it: each read
        // knows its own, and the end of a halving lies opposite its start (SmrtRefine).
        SmrtMark last = smrtMarkOf(receiver);
        bool lastBehind = smrtIsBehind(receiver);
        bool crossed = false;
        SmrtHidden hidden = smrtHiddenFrom(smrtIsBehind(receiver));
        SmrtHiddenCandidate candidate = smrtNoHiddenCandidate();
        // A side change's halvings (SmrtRefine) run as the loop's own iterations; the march goes
        // on from the read that changed side once smrtCrosses has decided. `advanced`: the read
        // the march moved to this iteration, if it moved.
        SmrtRefine h = smrtRefineOff();
        uint i = 0u;
        // Two loops, not one with a test of gapSamples in it: lavapipe runs a branch inside
        // the march masked, taken or not, and the gaps' reads would cost every pixel.
        if (gapSamples == 0u) {
            while (!crossed && (h.on || i < samples)) {
                float s = h.on ? 0.5 * (h.a.s + h.b.s)
                               : smrtSampleDistance(march, p, d, i, jitter);
                // The rest of the ray lies nearer the light than any texel (smrtNearestBehind).
                if (!h.on && !lastBehind && p.z + s * d.z < stopAt) break;
                SmrtPoint x = smrtPoint(map, view, scale, p, d, s, mapSize, r.layer);
                bool moved = false;
                SmrtMark advanced = smrtMarkOf(x);
                bool advancedBehind = smrtIsBehind(x);
                if (!smrtHalving(h, x, grazed)) {
                    if (advancedBehind != lastBehind) h = smrtRefineBetween(last, lastBehind, x);
                    else moved = true;
                }
                if (smrtSettled(view, scale, p, d, h, candidate, hidden, crossed)) {
                    advanced = h.end;
                    advancedBehind = !h.aBehind;
                    moved = true;
                }
                if (moved) {
                    smrtFollowHidden(hidden, advanced.s, advancedBehind);
                    last = advanced;
                    lastBehind = advancedBehind;
                    ++i;
                }
            }
        } else {
            // One loop, one read an iteration, for the main samples, the gaps' and the halvings'
            // alike: lavapipe runs a loop nested in the march for every lane while one lane needs
            // it, and lanes open long steps at different samples. The order of the points, and so
            // every decision, is that of smrt.cpp's nested loops: a step that opens is sampled
            // inside (j = 1 .. gapSamples), then its far end is read again (j = gapSamples + 1).
            SmrtMark from = last, next = last;
            uint j = 0u;
            bool gapping = false;
            while (!crossed && (h.on || gapping || i < samples)) {
                float s = h.on         ? 0.5 * (h.a.s + h.b.s)
                          : !gapping   ? smrtSampleDistance(march, p, d, i, jitter)
                          : j <= gapSamples ? smrtGapDistance(last.s, next.s, j, gapSamples)
                                            : next.s;
                SmrtPoint fromPoint = smrtMarkPoint(view, scale, p, d, from, smrt.slope);
                bool fromBehind = smrtIsBehind(fromPoint);
                // The last read already lies nearer the light than any texel, and so does the
                // rest (a gap opened before it would hold points farther out): lit.
                if (!h.on && !gapping && !fromBehind && fromPoint.z < stopAt) break;
                SmrtPoint x = smrtPoint(map, view, scale, p, d, s, mapSize, r.layer);
                bool moved = false;
                SmrtMark advanced = smrtMarkOf(x);
                bool advancedBehind = smrtIsBehind(x);
                if (!smrtHalving(h, x, grazed)) {
                    // A long step in front of the surface that the bounds cannot prove clear:
                    // sampled again inside.
                    if (!gapping && !fromBehind && !advancedBehind &&
                        smrtStepTexels(fromPoint, x, mapSize) > smrtLongStep() &&
                        !smrtStepClear(shadowTable, view, fromPoint, x, mapSize, l, levels,
                                       boundsSize)) {
                        gapping = true;
                        j = 1u;
                        next = advanced;
                    } else if (advancedBehind != fromBehind) {
                        h = smrtRefineBetween(from, fromBehind, x);
                    } else {
                        moved = true;
                    }
                }
                if (smrtSettled(view, scale, p, d, h, candidate, hidden, crossed)) {
                    advanced = h.end;
                    advancedBehind = !h.aBehind;
                    moved = true;
                }
                if (moved) {
                    smrtFollowHidden(hidden, advanced.s, advancedBehind);
                    from = advanced;
                    if (gapping && j <= gapSamples) {
                        ++j;
                    } else {
                        gapping = false;
                        last = advanced;
                        lastBehind = advancedBehind;
                        ++i;
                    }
                }
            }
        }
        if (!crossed) crossed = smrtHiddenCrossed(map, view, scale, candidate, p, d, mapSize, r.layer);
        // A ray that ends behind the surface is extrapolated on towards the light: it meets the
        // occluder it is behind (nothing lies nearer the light than the near plane).
        bool hit = crossed || lastBehind;
        blocked += hit ? 1.0 : 0.0;
        extrapolated += hit && !crossed ? 1.0 : 0.0;
        marched += length((smrtProject(view, scale, p + march.extent * d) - r.uv) * float(mapSize));
        traced += 1.0;
    }
    // A division may round either way by 2.5 ulp (a GPU takes a reciprocal): with every ray
    // blocked, 1 - 5/5 would read -1e-7 on an H100 without the max.
    return vec4(max(1.0 - blocked / traced, 0.0), blocked, extrapolated, marched / traced);
}

// A light without size (texel.w 0) sends every ray along the one line the hard test answers:
// smrt answers it as hard does (its texel, its bias), so that the two agree exactly there instead
// of by the march's own slack.
vec4 evaluateSmrt(TechniqueInput at) {
    if (at.view.texel.w <= 0.0) return evaluateHard(at);
    return shadowSmrtDetail(shadowMap, at.r, at.mapSize, at.view, at.pixel);
}

#endif
