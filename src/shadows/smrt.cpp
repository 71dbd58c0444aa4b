// Technique `smrt`, shadow-map ray tracing [after Unreal Engine 5's virtual shadow maps, Epic
// Games 2022]: smrt.rays rays from the receiver towards points spread over the light, each marched
// through the light's depth map at smrt.samples points; a ray is blocked where it crosses the
// map's surface, and extrapolated on when it ends behind it. No blocker estimate: overlapping
// occluders and contact hardening come from the rays. Shader: shaders/include/shadow_smrt.glsl;
// the march's maths, shared with this reference: shaders/include/smrt_march.h; derivations in
// docs/techniques.md ("Shadow-map ray tracing").
#include "kernels.h"
#include "penumbra/renderer.h"
#include "shadows/smrt_screen.h"
#include "shadows/technique.h"
#include "smrt_march.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {
namespace {

// smrtStored, transcribed: the light view distance at the nearest texel of uv (clamped).
float stored(const FilterInput& in, glm::vec2 uv) {
    const auto size = static_cast<float>(in.map.size);
    const glm::vec2 at = uv * size;
    // How near uv came to a texel's border: the GPU may round it to the other texel.
    const glm::vec2 f = glm::fract(at);
    in.margins.see(std::min(std::min(f.x, 1.0f - f.x), std::min(f.y, 1.0f - f.y)), 0.0f);
    const glm::ivec2 texel = glm::floor(at);
    return gpu::viewDistance(in.view, in.map.texel(texel.x, texel.y));
}

// smrtPoint, transcribed.
gpu::SmrtPoint pointAt(const FilterInput& in, const gpu::SmrtParams& s, glm::vec3 p, glm::vec3 d,
                       float distance) {
    const gpu::SmrtScale scale = gpu::smrtScaleOf(in.view, in.map.size);
    gpu::SmrtPoint x = gpu::smrtPointAt(in.view, scale, p, d, distance);
    gpu::smrtSetStored(x, in.view, scale, stored(in, x.uv), s.slope);
    in.margins.see(x.behind / std::max(x.z, 1.0f), x.slack / std::max(x.z, 1.0f));
    return x;
}

// The nearest depth over the texels of `tile` at `level` of the bounds (levelSize tiles a side),
// straight from the map.
float tileNearest(const ShadowMapView& map, glm::ivec2 tile, int level, int levelSize) {
    const int side = 2 << level;
    const int endY = gpu::smrtTileEnd(tile.y, level, levelSize, map.size);
    const int endX = gpu::smrtTileEnd(tile.x, level, levelSize, map.size);
    float nearest = 1.0f;
    for (int y = tile.y * side; y < endY; ++y)
        for (int x = tile.x * side; x < endX; ++x)
            nearest = std::min(nearest, map.texel(x, y));
    return std::max(nearest, 0.0f);
}

// The bounds' size (half the map's, at least 1) and its levels down to one tile.
struct BoundsShape {
    uint32_t size = 1;
    int levels = 1;
};

BoundsShape boundsShape(uint32_t mapSize) {
    BoundsShape b{.size = std::max(mapSize >> 1, 1u)};
    while ((b.size >> b.levels) > 0)
        ++b.levels;
    return b;
}

// smrtChildrenHold, transcribed.
bool childrenHold(const FilterInput& in, const gpu::SmrtCeiling& c, glm::vec2 at, glm::ivec4 block,
                  int level, int boundsSize, float inner, glm::ivec4 covered) {
    if (level == 0)
        return false;
    const int child = level - 1;
    const int levelSize = std::max(boundsSize >> level, 1);
    const int childSize = std::max(boundsSize >> child, 1);
    const int lastX = gpu::smrtLastChild(block.z, levelSize, childSize);
    const int lastY = gpu::smrtLastChild(block.w, levelSize, childSize);
    for (int y = 2 * block.y; y <= lastY; ++y)
        for (int x = 2 * block.x; x <= lastX; ++x) {
            if (gpu::smrtInBlock({x, y}, covered))
                continue;
            const float d = gpu::smrtTileDistance(at, {x, y}, child, childSize, in.map.size);
            const float ceiling =
                gpu::smrtDepthOf(in.view, gpu::smrtLitCeiling(c, std::max(inner, d)));
            const float stored = tileNearest(in.map, {x, y}, child, childSize);
            in.margins.see(stored, ceiling);
            if (stored < ceiling)
                return false;
        }
    return true;
}

// smrtProvenLit, transcribed: each ring's nearest depth read straight from the texels its block's
// tiles cover (the bounds' level 0 takes 2x2 texels, each level above 2x2 tiles, and a level's
// last tile the odd-sized leftovers: smrt_bounds.comp, smrt_bounds_mip.comp).
bool provenLit(const FilterInput& in, const gpu::SmrtParams& s, glm::vec3 p) {
    const uint32_t size = in.map.size;
    const auto sizeF = static_cast<float>(size);
    const glm::vec2 at = in.probe.uv * sizeF;
    if (at.x < 0.0f || at.y < 0.0f || at.x >= sizeF || at.y >= sizeF)
        return false;
    auto below = [&](float stored, float ceiling) {
        in.margins.see(stored, ceiling);
        return stored < ceiling;
    };
    const gpu::SmrtCeiling c = gpu::smrtCeilingOf(in.view, p, size, s.slope);
    const float ceiling = gpu::smrtDepthOf(in.view, gpu::smrtLitCeiling(c, 0.0f));
    const glm::ivec2 home = glm::floor(at);
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
            if (below(in.map.texel(home.x + i, home.y + j), ceiling))
                return false;
    const auto [boundsSize, levels] = boundsShape(size);
    const uint32_t rings = gpu::smrtBoundsRings(s.maxRadius);
    for (uint32_t k = rings; k >= 1; --k) {
        const int level = std::min(static_cast<int>(k), levels - 1);
        const int levelSize = static_cast<int>(std::max(boundsSize >> level, 1u));
        const glm::ivec4 block = gpu::smrtBoundsBlock(at, static_cast<uint32_t>(level), levelSize);
        const float nearest =
            std::min(std::min(tileNearest(in.map, {block.x, block.y}, level, levelSize),
                              tileNearest(in.map, {block.z, block.y}, level, levelSize)),
                     std::min(tileNearest(in.map, {block.x, block.w}, level, levelSize),
                              tileNearest(in.map, {block.z, block.w}, level, levelSize)));
        const auto inner = static_cast<float>(1u << (k - 1));
        const float ring = gpu::smrtDepthOf(in.view, gpu::smrtLitCeiling(c, inner));
        if (below(nearest, ring) &&
            !childrenHold(in, c, at, block, level, static_cast<int>(boundsSize), inner,
                          gpu::smrtInnerBlock(at, k, level, static_cast<int>(boundsSize))))
            return false;
    }
    return true;
}

// The march's test for a step to check (smrtStepTexels against smrtLongStep).
bool isLongStep(const FilterInput& in, const gpu::SmrtPoint& a, const gpu::SmrtPoint& b) {
    const float texels = gpu::smrtStepTexels(a, b, in.map.size);
    in.margins.see(texels / gpu::smrtLongStep(), 1.0f);
    return texels > gpu::smrtLongStep();
}

// smrtStepClear, transcribed: each tile's nearest depth straight from the map.
bool stepClear(const FilterInput& in, const gpu::SmrtPoint& a, const gpu::SmrtPoint& b) {
    const auto [boundsSize, levels] = boundsShape(in.map.size);
    const glm::ivec4 box = gpu::smrtStepTexelBox(a, b, in.map.size);
    // The box's corners are the ends' own texels, whose margins `stored` has seen.
    const int level = gpu::smrtStepLevel(box, levels);
    const int levelSize = static_cast<int>(std::max(boundsSize >> level, 1u));
    const glm::ivec4 tiles = gpu::smrtStepTiles(box, level, levelSize);
    const float ceiling = gpu::smrtStepCeiling(in.view, a, b);
    for (int y = tiles.y; y <= tiles.w; ++y)
        for (int x = tiles.x; x <= tiles.z; ++x) {
            const float nearest = tileNearest(in.map, {x, y}, level, levelSize);
            in.margins.see(nearest, ceiling);
            if (nearest < ceiling)
                return false;
        }
    return true;
}

// shadowSmrtDetail: x visibility, y rays blocked, z of those blocked only by extrapolation, w the
// mean march length in texels (over the rays traced).
glm::vec4 smrtReference(const FilterInput& in) {
    // evaluateSmrt: a light without size is answered by the hard test.
    if (in.view.texel.w <= 0.0f)
        return moduleOf(Technique::Hard).reference(in);
    const gpu::SmrtParams s = in.params.get<gpu::SmrtParams>();
    const gpu::ShadowViewData& view = in.view;
    const uint32_t mapSize = in.map.size;
    const float turns = gpu::rotationTurns(s.rotation, in.probe.pixel);
    const glm::uvec2 budget = gpu::smrtBudget(view, s);
    const uint32_t rays = budget.x, samples = budget.y;
    const uint32_t adaptive = gpu::smrtAdaptive(view, s);
    const uint32_t gapSamples = gpu::smrtGapSamples(view, s);
    const glm::vec3 p =
        gpu::smrtViewPoint(view, in.probe.uv, gpu::viewDistance(view, in.probe.depth));
    const gpu::SmrtScale scale = gpu::smrtScaleOf(view, mapSize);
    if (s.skipLit != 0 && provenLit(in, s, p))
        return {1.0f, 0.0f, 0.0f, 0.0f};
    const gpu::SmrtPoint receiver = pointAt(in, s, p, glm::vec3(0.0f), 0.0f);
    float blocked = 0.0f, extrapolated = 0.0f, marched = 0.0f, traced = 0.0f;
    bool grazed = gpu::smrtIsBehind(receiver);
    const bool hiddenOn = gpu::smrtHiddenOn(view, s) != 0;
    for (uint32_t ray = 0; ray < rays; ++ray) {
        const uint32_t k = rays - 1 - ray;
        if (ray > 0 && ray == adaptive && (blocked == traced || (blocked == 0.0f && !grazed)))
            break;
        const glm::vec3 d = gpu::smrtRayDirection(view, p, k, rays, turns);
        const gpu::SmrtMarch march = gpu::smrtMarch(view, p, d, s.maxRadius, mapSize, samples);
        const float jitter = glm::fract(turns * 2.618034f + static_cast<float>(k) * 0.7548777f);
        gpu::SmrtPoint last = receiver;
        bool crossed = false;
        gpu::SmrtHidden hidden = gpu::smrtHiddenFrom(gpu::smrtIsBehind(receiver));
        gpu::SmrtHiddenCandidate candidate = gpu::smrtNoHiddenCandidate();
        // Where the crossing test sees a silhouette: the candidate (smrtNoteHiddenHere).
        auto note = [&](const gpu::SmrtPoint& front) {
            if (hiddenOn)
                gpu::smrtNoteHidden(candidate, hidden, front.s, gpu::smrtIsBehind(front));
        };
        auto track = [&](const gpu::SmrtPoint& x) {
            gpu::smrtTrackHidden(hidden, x.s, gpu::smrtIsBehind(x));
        };
        // smrtHiddenCrossed, transcribed, after the march (a candidate is only noted where
        // smrt.hidden is on).
        auto crossedHidden = [&]() {
            if (!candidate.found)
                return false;
            // The points again from their distances along the ray, as the shader makes them.
            const gpu::SmrtPoint first = gpu::smrtMarkPoint(
                view, scale, p, d, gpu::SmrtMark{.s = candidate.first, .behind = 0.0f}, s.slope);
            const gpu::SmrtPoint front = gpu::smrtMarkPoint(
                view, scale, p, d, gpu::SmrtMark{.s = candidate.front, .behind = 0.0f}, s.slope);
            const gpu::SmrtHiddenTexels t = gpu::smrtHiddenTexels(first, front, mapSize);
            const glm::vec4 depths{in.map.texel(t.near.x, t.near.y),
                                   in.map.texel(t.near.z, t.near.w), in.map.texel(t.far.x, t.far.y),
                                   in.map.texel(t.far.z, t.far.w)};
            float margin = 0.0f;
            const bool result =
                gpu::smrtCrossedHidden(view, first, front, t, depths, mapSize, margin);
            in.margins.see(margin, 0.0f);
            return result;
        };
        // The halvings and smrtCrosses, transcribed (the shader reads the halvings as
        // iterations of its march's loop: SmrtRefine).
        auto crosses = [&](gpu::SmrtPoint a, gpu::SmrtPoint b) {
            for (uint32_t j = 0; j < s.refine; ++j) {
                const gpu::SmrtPoint m = pointAt(in, s, p, d, 0.5f * (a.s + b.s));
                (gpu::smrtIsBehind(m) == gpu::smrtIsBehind(a) ? a : b) = m;
            }
            float margin = 0.0f;
            const bool result = gpu::smrtCrosses(view, a, b, s.slope, margin);
            in.margins.see(margin, 0.0f);
            return result;
        };
        for (uint32_t i = 0; i < samples && !crossed; ++i) {
            const gpu::SmrtPoint next =
                pointAt(in, s, p, d, gpu::smrtSampleDistance(march, p, d, i, jitter));
            grazed = grazed || gpu::smrtIsBehind(next);
            gpu::SmrtPoint from = last;
            if (gapSamples > 0 && !gpu::smrtIsBehind(last) && !gpu::smrtIsBehind(next) &&
                isLongStep(in, last, next) && !stepClear(in, last, next)) {
                for (uint32_t j = 1; j <= gapSamples && !crossed; ++j) {
                    const gpu::SmrtPoint inside =
                        pointAt(in, s, p, d, gpu::smrtGapDistance(last.s, next.s, j, gapSamples));
                    grazed = grazed || gpu::smrtIsBehind(inside);
                    if (gpu::smrtIsBehind(inside) != gpu::smrtIsBehind(from)) {
                        crossed = crosses(from, inside);
                        if (!crossed)
                            note(inside);
                    }
                    track(inside);
                    from = inside;
                }
            }
            if (!crossed && gpu::smrtIsBehind(next) != gpu::smrtIsBehind(from)) {
                crossed = crosses(from, next);
                if (!crossed)
                    note(next);
            }
            track(next);
            last = next;
        }
        crossed = crossed || crossedHidden();
        const bool hit = crossed || gpu::smrtIsBehind(last);
        blocked += hit ? 1.0f : 0.0f;
        extrapolated += hit && !crossed ? 1.0f : 0.0f;
        marched += glm::length((gpu::smrtProject(view, scale, p + march.extent * d) - in.probe.uv) *
                               static_cast<float>(mapSize));
        traced += 1.0f;
    }
    return {std::max(1.0f - blocked / traced, 0.0f), blocked, extrapolated, marched / traced};
}

} // namespace

const TechniqueModule& smrtModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Smrt,
                 .name = "smrt",
                 .summary = "shadow-map ray tracing: rays towards points of the light marched "
                            "through the depth map (contact hardening, overlapping occluders)",
                 .reference = "after Unreal Engine 5's virtual shadow maps (Epic Games 2022), "
                              "shadow-map ray tracing",
                 .families = {"bias", "smrt", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "fast",
                               .sets = {{"smrt.rays", "16"},
                                        {"smrt.adaptive", "4"},
                                        {"smrt.filterTolerance", "0.7"},
                                        {"smrt.cubeSamples", "12"}}}}},
        .parameters =
            {{.key = "smrt.rays",
              .type = ParameterType::Int,
              .defaultValue = 32,
              .min = 1,
              .max = 64,
              .unit = "rays per pixel",
              .description = "rays towards points of the light (a rotated low-discrepancy set "
                             "per pixel); the visibility is the fraction no occluder blocks "
                             "(spots and suns; smrt.cubeRays on cube faces)"},
             {.key = "smrt.samples",
              .type = ParameterType::Int,
              .defaultValue = 8,
              .min = 2,
              .max = 64,
              .unit = "map samples per ray",
              .description = "depth-map samples along each ray, denser near the receiver "
                             "(spots and suns; smrt.cubeSamples on cube faces)"},
             {.key = "smrt.cubeRays",
              .type = ParameterType::Int,
              .defaultValue = 8,
              .min = 1,
              .max = 64,
              .unit = "rays per pixel",
              .description = "smrt.rays on a point light's cube faces, where the march's spacing "
                             "limits the error more than the rays' noise"},
             {.key = "smrt.cubeSamples",
              .type = ParameterType::Int,
              .defaultValue = 13,
              .min = 2,
              .max = 64,
              .unit = "map samples per ray",
              .description = "smrt.samples on a point light's cube faces, whose rays sweep far "
                             "across the face as they near the light"},
             {.key = "smrt.maxRadius",
              .type = ParameterType::Float,
              .defaultValue = 256.0,
              .min = 2.0,
              .max = 256.0,
              .unit = "texels",
              .description = "how far from the receiver's texel a ray is marched; a ray still "
                             "behind an occluder there is taken as blocked (extrapolated)"},
             {.key = "smrt.slope",
              .type = ParameterType::Float,
              .defaultValue = 8.0,
              .min = 0.0,
              .max = 64.0,
              .unit = "depth per lateral unit",
              .description = "the steepest surface a ray may cross between two samples; a "
                             "steeper change of the map's depth is an occluder's silhouette"},
             {.key = "smrt.refine",
              .type = ParameterType::Int,
              .defaultValue = 3,
              .min = 0,
              .max = 8,
              .unit = "halvings",
              .description = "halvings of the interval where a ray changes side of the map's "
                             "surface before the crossing test (a silhouette's jump stays, a "
                             "surface's gap shrinks)"},
             {.key = "smrt.adaptive",
              .type = ParameterType::Int,
              .defaultValue = 8,
              .min = 0,
              .max = 64,
              .unit = "rays",
              .description = "rays traced first, round the light's rim: where all are blocked, or "
                             "all lit without one passing behind an occluder, no more are (0: "
                             "every pixel traces smrt.rays; spots and suns, smrt.cubeAdaptive on "
                             "cube faces)"},
             {.key = "smrt.cubeAdaptive",
              .type = ParameterType::Int,
              .defaultValue = 5,
              .min = 0,
              .max = 64,
              .unit = "rays",
              .description = "smrt.adaptive on a point light's cube faces, which trace "
                             "smrt.cubeRays"},
             {.key = "smrt.skipLit",
              .type = ParameterType::Bool,
              .defaultValue = 1,
              .description = "prove pixels fully lit from bounds of the map (the nearest depth "
                             "over tiles of 2 to 1024 texels, built after the depth pass) and "
                             "trace no ray there; the same result, fewer rays (not on virtual "
                             "maps)"},
             {.key = "smrt.gapSamples",
              .type = ParameterType::Int,
              .defaultValue = 0,
              .min = 0,
              .max = 16,
              .unit = "samples",
              .description = "samples added, evenly spaced, inside a step of more than 4 texels "
                             "whose ends lie in front of the map's surface where the map's "
                             "bounds cannot prove that nothing lies between (thin occluders the "
                             "long far steps would pass; 0: off; on virtual maps, which have no "
                             "bounds, every such step)"},
             {.key = "smrt.cubeGapSamples",
              .type = ParameterType::Int,
              .defaultValue = 0,
              .min = 0,
              .max = 16,
              .unit = "samples",
              .description =
                  "smrt.gapSamples on a point light's cube faces, whose rays towards "
                  "a close light's rim take the longest steps (off: more plain samples a "
                  "ray read as well for less)"},
             {.key = "smrt.hidden",
              .type = ParameterType::Bool,
              .defaultValue = 1, // measured: docs/techniques.md, smrt step 11
              .description = "a ray that comes out from behind a caster in front of a surface "
                             "crossed that surface where it, continued as a plane, hid the ray: "
                             "casters stacked over one another (a table under a slatted roof) "
                             "no longer leak (spots and suns, smrt.cubeHidden on cube faces; "
                             "it costs their pass 7-14%)"},
             {.key = "smrt.cubeHidden",
              .type = ParameterType::Bool,
              .defaultValue = 1,
              .description = "smrt.hidden on a point light's cube faces: a bulb in a room "
                             "lights through furniture stacked under other furniture without "
                             "it"},
             {.key = "smrt.filter",
              .type = ParameterType::Int,
              .defaultValue = 1,
              .min = 0,
              .max = 8,
              .unit = "pixels",
              .description = "the edge-aware spatial filter of the rays' noise: pixels each "
                             "side, along rows and then columns, of neighbours on the same "
                             "surface (0: off)"},
             {.key = "smrt.cubeFilter",
              .type = ParameterType::Int,
              .defaultValue = 1,
              .min = 0,
              .max = 8,
              .unit = "pixels",
              .description = "smrt.filter under point lights, whose cube faces trace fewer rays "
                             "(smrt.cubeRays); smrt.cubeFilterWide widens it inside wide "
                             "penumbrae"},
             {.key = "smrt.filterWide",
              .type = ParameterType::Int,
              .defaultValue = 0,
              .min = 0,
              .max = 8,
              .unit = "pixels",
              .description = "the filter's radius inside a wide penumbra: a pixel whose "
                             "neighbours out to this radius each side are in the penumbra too "
                             "(neither 0 nor 1) reaches that far (at most as far as they stay "
                             "in it); smrt.filter elsewhere (spots and suns; 0 or below "
                             "smrt.filter: off)"},
             {.key = "smrt.cubeFilterWide",
              .type = ParameterType::Int,
              .defaultValue = 8,
              .min = 0,
              .max = 8,
              .unit = "pixels",
              .description = "smrt.filterWide under point lights, whose wide penumbrae from a "
                             "close bulb take few rays a pixel (smrt.cubeRays)"},
             {.key = "smrt.filterTolerance",
              .type = ParameterType::Float,
              .defaultValue = 0.15,
              .min = 0.05,
              .max = 1.0,
              .unit = "visibility",
              .description = "the filter's range: a neighbour whose visibility differs by this "
                             "much or more does not count, so hard edges and narrow penumbrae "
                             "stay sharp (spots and suns)"},
             {.key = "smrt.cubeFilterTolerance",
              .type = ParameterType::Float,
              .defaultValue = 0.7,
              .min = 0.05,
              .max = 1.0,
              .unit = "visibility",
              .description = "smrt.filterTolerance under point lights, whose fewer rays a "
                             "pixel (smrt.cubeRays) leave more noise to take"},
             {.key = "smrt.checkerboard",
              .type = ParameterType::Bool,
              .defaultValue = 1,
              .description = "trace half the pixels (a checkerboard), then fill each other "
                             "pixel from its four neighbours on its surface where they agree "
                             "within smrt.fillRange, and trace the rest (off: every pixel is "
                             "traced; the viewer's technique views trace every pixel)"},
             {.key = "smrt.fillRange",
              .type = ParameterType::Float,
              .defaultValue = 0.1,
              .min = 0.0,
              .max = 1.0,
              .unit = "visibility",
              .description = "smrt.checkerboard's agreement: a pixel whose neighbours' "
                             "visibilities span more than this is traced (0: only where they "
                             "are equal; spots and suns)"},
             {.key = "smrt.cubeFillRange",
              .type = ParameterType::Float,
              .defaultValue = 0.3,
              .min = 0.0,
              .max = 1.0,
              .unit = "visibility",
              .description = "smrt.fillRange under point lights, whose fewer rays a pixel "
                             "(smrt.cubeRays) differ by 1/8 from one pixel to the next in a "
                             "smooth penumbra"},
             {.key = "smrt.rotation",
              .type = ParameterType::Choice,
              .defaultValue = 2,
              .choices = {std::begin(gpu::kRotationChoices), std::end(gpu::kRotationChoices)},
              .description = "per-pixel rotation of the ray set and jitter of the samples"}},
        // smrt.skipLit's bounds: the nearest depth over 2x2 texels, then 2x2 tiles, level by level
        // (float bits; read at TECH_TABLE beside the depth map).
        .maps = {{.name = "bounds",
                  .format = MapFormat::R32UI,
                  .mipmappedFor = [](const ParameterValues&) { return true; },
                  .shrink = 1}},
        .postPasses = {{.shader = "smrt_bounds.comp", .inputs = {kDepthMap}, .outputs = {"bounds"}},
                       {.shader = "smrt_bounds_mip.comp",
                        .outputs = {"bounds"},
                        .dispatch = PostDispatch::MipChain}},
        .visibilityMaps = {"bounds"},
        .constants =
            [](const ParameterValues& p) {
                // Bit 0 spots and suns, bit 1 point lights (the shader picks by LIGHT_TYPE).
                return std::vector<SpecConstant>{
                    {SPEC_SMRT_HIDDEN, (p.number("smrt.hidden") != 0.0 ? 1u : 0u) |
                                           (p.number("smrt.cubeHidden") != 0.0 ? 2u : 0u)}};
            },
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                auto whole = [&](const char* key) { return static_cast<uint32_t>(p.number(key)); };
                auto real = [&](const char* key) { return static_cast<float>(p.number(key)); };
                block.set(gpu::SmrtParams{.rays = whole("smrt.rays"),
                                          .samples = whole("smrt.samples"),
                                          .rotation = whole("smrt.rotation"),
                                          .maxRadius = real("smrt.maxRadius"),
                                          .slope = real("smrt.slope"),
                                          .refine = whole("smrt.refine"),
                                          .adaptive = whole("smrt.adaptive"),
                                          .cubeRays = whole("smrt.cubeRays"),
                                          .cubeSamples = whole("smrt.cubeSamples"),
                                          .skipLit = whole("smrt.skipLit"),
                                          .cubeAdaptive = whole("smrt.cubeAdaptive"),
                                          .gapSamples = whole("smrt.gapSamples"),
                                          .cubeGapSamples = whole("smrt.cubeGapSamples"),
                                          .hidden = whole("smrt.hidden"),
                                          .cubeHidden = whole("smrt.cubeHidden")});
            },
        .reference = smrtReference,
        .modelsLightSize = true,
        .blurRadiusTexels =
            [](const ParameterValues& p) { return p.number("smrt.maxRadius") + 1.0; },
        // Its rays stay in the light's cone; a light without size is the hard test.
        .footprintFollowsLight = true,
        .readsVirtualMaps = true,
        .screenPasses = smrtScreenPasses};
    return module;
}

} // namespace penumbra::shadows
