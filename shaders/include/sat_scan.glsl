// Summed-area tables of variance shadow maps [Lauritzen 2007, GPU Gems 3 ch. 8], one axis a pass,
// one invocation per line (rows, then columns; lines run in parallel, each scanned in order):
// AXIS 0 sums the offset moments (z - 1/2, (z - 1/2)^2) of momentDepth along each row, AXIS 1
// sums those row sums down each column. Texel (i, j) of the table then holds the sum over every
// texel (a <= i, b <= j). Offsetting the depths to [-1/2, 1/2] keeps the sums small (the signs
// cancel), which is what 32-bit float sums over a whole map need (docs/techniques.md, "savsm").
#include "post_pass.glsl"
#include "filter_math.h"
layout(local_size_x = LINE_GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D source;
layout(set = 0, binding = POST_OUTPUT_BINDING, rg32f) uniform writeonly image2D sums;

void main() {
    int line = int(gl_GlobalInvocationID.x);
    int size = int(push.size.x);
    if (line >= int(push.size.y)) return;
    ShadowViewData view = views[push.size.z];
    vec2 sum = vec2(0.0);
    for (int k = 0; k < size; ++k) {
#if AXIS == 0
        ivec2 q = ivec2(k, line);
        sum += offsetMoments(momentDepth(view, texelFetch(source, q, 0).r));
#else
        ivec2 q = ivec2(line, k);
        sum += texelFetch(source, q, 0).rg;
#endif
        imageStore(sums, q, vec4(sum, 0.0, 0.0));
    }
}
