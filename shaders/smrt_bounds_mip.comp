#version 460
// smrt.skipLit's bounds, levels 1..: each texel the nearest of the 2x2 texels of the level above
// (and, in the level's last row and column, the odd-sized level's leftovers: smrt_bounds.comp).
#include "post_pass.glsl"
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform usampler2D above;
layout(set = 0, binding = POST_OUTPUT_BINDING, r32ui) uniform writeonly uimage2D level;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), push.size.xy))) return;
    ivec2 size = textureSize(above, 0);
    ivec2 last = size - 1;
    uvec4 four = textureGather(above, vec2(2 * p + 1) / vec2(size)); // as smrt_bounds.comp
    uint nearest = min(min(four.x, four.y), min(four.z, four.w));
    ivec2 end = mix(min(2 * p + 1, last), last, equal(p, ivec2(push.size.xy) - 1));
    if (any(greaterThan(end, 2 * p + 1)))
        for (int y = 2 * p.y; y <= end.y; ++y)
            for (int x = 2 * p.x; x <= end.x; ++x)
                nearest = min(nearest, texelFetch(above, ivec2(x, y), 0).r);
    imageStore(level, p, uvec4(nearest));
}
