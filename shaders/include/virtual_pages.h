// Virtual shadow maps [Unreal Engine 5's virtual shadow maps; EEVEE-Next]: the maths of a page
// lookup, compiled as GLSL (the page marking and the visibility pass) and as C++ (the host's page
// cache, src/render/virtual_pages.cpp, and the tests' CPU reference).
//
// A light's virtual map is a stack of levels, each a shadow view (ShadowViewData) of
// `pagesPerSide` x `pagesPerSide` pages of `pageSize`^2 texels: a sun's clipmap levels (each twice
// the extent of the one below, centred on the camera), or a spot's frustum or a cube face and its
// coarser mips. A level's pages are entries of one page table, row by row from its first entry;
// an entry is VIRTUAL_NOT_RESIDENT or 1 + the index of the physical page that holds it in the
// pool, an atlas of `poolPagesPerSide`^2 pages, row by row.
// clang-format off
#ifndef PENUMBRA_VIRTUAL_PAGES_H
#define PENUMBRA_VIRTUAL_PAGES_H
#include "shared_prelude.h"

#define VIRTUAL_NOT_RESIDENT 0u
#define VIRTUAL_MAX_LEVELS 16u  // virtual.levels' largest value (a sun's clipmap)

PENUMBRA_GPU_BEGIN

// The page-table entry of page `page` of a level whose table starts at `tableOffset`.
SHARED uint virtualEntryIndex(uint tableOffset, uint pagesPerSide, ivec2 page) {
    return tableOffset + uint(page.y) * pagesPerSide + uint(page.x);
}

// The page that holds texel `texel` of a level (texels inside it: 0 <= texel < its size).
SHARED ivec2 virtualPageOf(ivec2 texel, uint pageSize) {
    return ivec2(texel.x / int(pageSize), texel.y / int(pageSize));
}

// Where texel `texel` of a level lies in the pool, its page resident at table entry `entry`.
SHARED ivec2 virtualAtlasTexel(uint entry, ivec2 texel, uint pageSize, uint poolPagesPerSide) {
    uint physical = entry - 1u;
    ivec2 page = virtualPageOf(texel, pageSize);
    ivec2 origin = ivec2(int(physical % poolPagesPerSide), int(physical / poolPagesPerSide)) *
                   int(pageSize);
    return origin + texel - page * int(pageSize);
}

// The finest level whose texel is still at least as large as about one pixel: level l's texel is
// 2^l times level 0's, so the pixel's world size `pixelWorld` over level 0's texel `texelWorld0`
// (both at the receiver) is 2^l; `lodBias` levels coarser (positive) or finer. Clamped to the
// levels there are.
SHARED uint virtualLevelFor(float pixelWorld, float texelWorld0, float lodBias, uint levels) {
    float ratio = max(pixelWorld / max(texelWorld0, 1e-30f), 1e-30f);
    float level = floor(log2(ratio) + lodBias);
    return uint(clamp(level, 0.0f, float(levels) - 1.0f));
}

// Whether uv (a level's [0, 1]^2) lies `margin` texels inside a level of `size` texels a side.
SHARED bool virtualHolds(vec2 uv, float size, float margin) {
    float m = margin / size;
    return uv.x >= m && uv.y >= m && uv.x <= 1.0f - m && uv.y <= 1.0f - m;
}

PENUMBRA_GPU_END

#endif
// clang-format on
