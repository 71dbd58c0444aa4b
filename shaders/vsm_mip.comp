#version 460
// vsm.filter=mip [Donnelly and Lauritzen 2006, section 4]: one level of the blurred moments' mip
// chain, each texel the mean of the 2x2 texels above it (levels are floor(size / 2^level) a side,
// as Vulkan's: an odd-sized level's last row and column are left out). Moments average linearly,
// so every level holds the moments of the depths under its texels.
#include "post_pass.glsl"
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D above;
layout(set = 0, binding = POST_OUTPUT_BINDING, rg32f) uniform writeonly image2D level;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), push.size.xy))) return;
    ivec2 last = textureSize(above, 0) - 1;
    vec4 sum = texelFetch(above, min(2 * p, last), 0) +
               texelFetch(above, min(2 * p + ivec2(1, 0), last), 0) +
               texelFetch(above, min(2 * p + ivec2(0, 1), last), 0) +
               texelFetch(above, min(2 * p + ivec2(1, 1), last), 0);
    imageStore(level, p, 0.25 * sum);
}
