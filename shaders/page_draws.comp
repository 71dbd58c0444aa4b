#version 460
// The page draws' setup (src/render/page_draw_passes.h), after the page decisions: for each page
// they render (by rank), the matrix that takes the world to its square of the pool, listed by
// the pipeline that draws it (a sun's levels clamp depth, a spot's and a face's do not).
#include "page_passes.h"

layout(local_size_x = PAGES_BLOCK) in;
layout(set = 0, binding = PAGE_DRAW_LEVELS, std430) readonly buffer Levels { PageLevelData levels[]; };
layout(set = 0, binding = PAGE_DRAW_VIEWS, std430) readonly buffer Views { PageViewData views[]; };
layout(set = 0, binding = PAGE_DRAW_RENDER, std430) readonly buffer Render { PageRenderData render[]; };
layout(set = 0, binding = PAGE_DRAW_COUNTS, std430) readonly buffer Counts { PageCounts counts; };
layout(set = 0, binding = PAGE_DRAW_LIST, std430) writeonly buffer List { PageDrawData list[]; };
layout(set = 0, binding = PAGE_DRAW_LIST_COUNTS, std430) buffer ListCounts { uint listCounts[2]; };
layout(push_constant) uniform Push { PageSetupPush push; };

// The level whose table holds `entry` (their tables follow one another).
uint levelHolding(uint entry) {
    uint lo = 0u, hi = push.levelCount;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (levels[mid].tableOffset <= entry) lo = mid;
        else hi = mid;
    }
    return lo;
}

void main() {
    uint rank = gl_GlobalInvocationID.x;
    if (rank >= counts.rendered) return;
    uint entry = render[rank].entry, physical = render[rank].physical;
    uint i = levelHolding(entry);
    uint n = levels[i].pagesPerSide, local = entry - levels[i].tableOffset;
    vec2 page = vec2(local % n, local / n);
    // The page's crop of its level: NDC [2p/n - 1, 2(p+1)/n - 1] -> [-1, 1] (pageViewProj).
    float fn = float(n);
    mat4 crop = mat4(1.0);
    crop[0][0] = fn;
    crop[1][1] = fn;
    crop[3].xy = -(2.0 * page + 1.0 - fn);
    // Then [-1, 1] -> its square of the pool, S squares a side: x' = x / S + (lo + 1 / S) w.
    float side = float(push.poolPagesPerSide);
    vec2 lo = -1.0 + 2.0 * vec2(physical % push.poolPagesPerSide, physical / push.poolPagesPerSide) / side;
    mat4 place = mat4(1.0);
    place[0][0] = 1.0 / side;
    place[1][1] = 1.0 / side;
    place[3].xy = lo + 1.0 / side;
    uint kind = views[i].kind.x;
    uint at = atomicAdd(listCounts[kind], 1u);
    list[kind * push.pages + at] = PageDrawData(place * crop * views[i].viewProj,
                                                vec4(lo, lo + 2.0 / side));
}
