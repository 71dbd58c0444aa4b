#version 460
// smrt.skipLit's bounds, level 0: each texel the nearest depth of the 2x2 depth-map texels under
// it, as float bits (depths are not negative, so their bits order as they do). A level is
// floor(size / 2) a side, as Vulkan's mip levels; its last row and column also take the
// odd-sized map's leftover texels, so that every texel lies under a tile (shadow_smrt.glsl,
// smrtProvenLit).
#include "post_pass.glsl"
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D depth;
layout(set = 0, binding = POST_OUTPUT_BINDING, r32ui) uniform writeonly uimage2D bounds;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), push.size.xy))) return;
    ivec2 size = textureSize(depth, 0);
    ivec2 last = size - 1;
    // Two texels a side (one gather, its footprint the 2x2 texels round their shared corner),
    // three where this is the level's last tile and the map is odd-sized.
    vec4 four = textureGather(depth, vec2(2 * p + 1) / vec2(size));
    float nearest = min(min(four.x, four.y), min(four.z, four.w));
    ivec2 end = mix(min(2 * p + 1, last), last, equal(p, ivec2(push.size.xy) - 1));
    if (any(greaterThan(end, 2 * p + 1)))
        for (int y = 2 * p.y; y <= end.y; ++y)
            for (int x = 2 * p.x; x <= end.x; ++x)
                nearest = min(nearest, texelFetch(depth, ivec2(x, y), 0).r);
    imageStore(bounds, p, uvec4(floatBitsToUint(max(nearest, 0.0))));
}
