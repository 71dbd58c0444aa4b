// Summed-area tables of fixed-point moments [Lauritzen 2007, GPU Gems 3 ch. 8], one axis a pass,
// one invocation per line (rows, then columns; lines run in parallel, each scanned in order):
// AXIS 0 sums tableMoments (moments.h) of each texel's momentDepth along its row, AXIS 1 sums
// those row sums down each column. Texel (i, j) of the table then holds the sum over every texel
// (a <= i, b <= j), modulo 2^32: the sums wrap, and a box's sum, a difference of corners, is
// still exact (docs/techniques.md, "savsm"). MOMENTS: MOMENTS_VSM (offset moments, FORMAT rg32ui)
// or MOMENTS_MSM (four moments, rgba32ui); SCALE: the technique's table scale (params_tables.h).
#include "post_pass.glsl"
#include "light_geometry.h"
#include "moments.h"
#include "bindings.h"
#include "params_tables.h"
layout(local_size_x = LINE_GROUP_SIZE) in;
#if AXIS == 0
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D source;
#else
layout(set = 0, binding = POST_INPUT_BINDING) uniform usampler2D source;
#endif
layout(set = 0, binding = POST_OUTPUT_BINDING, FORMAT) uniform writeonly uimage2D sums;

void main() {
    int line = int(gl_GlobalInvocationID.x);
    int size = int(push.size.x);
    if (line >= int(push.size.y)) return;
    ShadowViewData view = views[push.size.z];
    uvec4 sum = uvec4(0u);
    for (int k = 0; k < size; ++k) {
#if AXIS == 0
        ivec2 q = ivec2(k, line);
        sum += tableMoments(MOMENTS, momentDepth(view, texelFetch(source, q, 0).r), SCALE);
#else
        ivec2 q = ivec2(line, k);
        sum += texelFetch(source, q, 0);
#endif
        imageStore(sums, q, sum);
    }
}
