// One level of smrt.skipLit's bounds (shaders/include/shadow_smrt.glsl, smrtProvenLit): each
// texel the nearest of the 2x2 texels under it in the level above, the depth map for level 0, as
// float bits (depths are not negative, so their bits order as they do). A level is floor(size / 2)
// a side, as Vulkan's mip levels; its last row and column also take the odd-sized level above's
// leftovers (smrtLastChild), so that every texel lies under a tile. The including shader defines
// BOUNDS_ABOVE, the level above's sampler type, and BOUNDS_BITS(v), what it reads as uint bits.
#ifndef PENUMBRA_SMRT_BOUNDS_GLSL
#define PENUMBRA_SMRT_BOUNDS_GLSL
#include "post_pass.glsl"
#include "smrt_march.h"
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform BOUNDS_ABOVE above;
layout(set = 0, binding = POST_OUTPUT_BINDING, r32ui) uniform writeonly uimage2D level;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 tiles = ivec2(push.size.xy);
    if (any(greaterThanEqual(p, tiles))) return;
    ivec2 size = textureSize(above, 0);
    ivec2 last = ivec2(smrtLastChild(p.x, tiles.x, size.x), smrtLastChild(p.y, tiles.y, size.y));
    // The 2x2 in one gather (its footprint: the texels round their shared corner), the leftovers
    // texel by texel.
    uvec4 four = BOUNDS_BITS(textureGather(above, vec2(2 * p + 1) / vec2(size)));
    uint nearest = min(min(four.x, four.y), min(four.z, four.w));
    if (any(greaterThan(last, 2 * p + 1)))
        for (int y = 2 * p.y; y <= last.y; ++y)
            for (int x = 2 * p.x; x <= last.x; ++x)
                nearest = min(nearest, BOUNDS_BITS(texelFetch(above, ivec2(x, y), 0)).r);
    imageStore(level, p, uvec4(nearest));
}

#endif
