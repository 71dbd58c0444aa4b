// How a technique reads depths from its map: straight from the map's layer, or (SPEC_VIRTUAL,
// virtual.enabled) through the page table from the physical pool (shaders/include/virtual_pages.h).
// A virtual level is named by its first page-table entry where a map's layer would be, and a texel
// whose page is not resident reads as the far plane (lit): the visibility pass picks a level whose
// page at the receiver is resident, and the marking asked for the pages its filter reaches. The
// including pass declares the frame block as `frame`.
#ifndef PENUMBRA_MAP_READS_GLSL
#define PENUMBRA_MAP_READS_GLSL
#include "bindings.h"
#include "virtual_pages.h"

layout(constant_id = SPEC_VIRTUAL) const bool VIRTUAL_MAPS = false;
layout(set = 0, binding = TECH_PAGE_TABLE, std430) readonly buffer PageTable { uint pageTable[]; };

// The page-table entry of a virtual level's page holding `texel` (a level of `size` texels, its
// table from `tableOffset`).
uint virtualEntry(ivec2 texel, uint size, uint tableOffset) {
    uint pageSize = frame.virtualPages.x;
    return pageTable[virtualEntryIndex(tableOffset, size / pageSize, virtualPageOf(texel, pageSize))];
}

// The depth at texel `texel` of a level of `size` texels (clamped to its edge, as a sampler
// clamps).
float virtualDepth(sampler2DArray pool, ivec2 texel, uint size, uint tableOffset) {
    texel = clamp(texel, ivec2(0), ivec2(int(size) - 1));
    uint entry = virtualEntry(texel, size, tableOffset);
    if (entry == VIRTUAL_NOT_RESIDENT) return 1.0;
    ivec2 at = virtualAtlasTexel(entry, texel, frame.virtualPages.x, frame.virtualPages.y);
    return texelFetch(pool, ivec3(at, 0), 0).r;
}

// The depth of one texel of view `layer`.
float fetchDepth(sampler2DArray map, ivec2 texel, float size, float layer) {
    if (VIRTUAL_MAPS) return virtualDepth(map, texel, uint(size), uint(layer));
    return texelFetch(map, ivec3(texel, int(layer)), 0).r;
}

// The 2x2 texels whose first texel is `base`, in textureGather order: x (i, j+1), y (i+1, j+1),
// z (i+1, j), w (i, j).
vec4 gatherDepths(sampler2DArray map, ivec2 base, float size, float layer) {
    if (VIRTUAL_MAPS) {
        uint s = uint(size), t = uint(layer);
        return vec4(virtualDepth(map, base + ivec2(0, 1), s, t),
                    virtualDepth(map, base + ivec2(1, 1), s, t),
                    virtualDepth(map, base + ivec2(1, 0), s, t), virtualDepth(map, base, s, t));
    }
    return textureGather(map, vec3((vec2(base) + 1.0) / size, layer), 0);
}

#endif
