// The separable Gaussian blur of the prefiltered family's maps [Donnelly and Lauritzen 2006], one
// axis a pass: AXIS 0 runs along rows, reading the light's depth and storing what the technique
// keeps of it (warpedMoments of momentDepth: MOMENTS, one of MOMENTS_* in moments.h, in maps
// of image format FORMAT); AXIS 1 runs along columns over the row pass's result. PARAMS is the
// technique's parameter block (params_moments.h; its `size`: the blur's taps), EXPONENTS its
// warps' exponents (esm, evsm) and STORE16 whether the column pass quantises to 16 bits (msm). Texels past the
// map's edge repeat the edge (clamp-to-edge, as the CPU reference does). The kernel is the
// technique's size in taps, in texels of a sun's first cascade, scaled in the farther ones
// (scaledKernelSize).
#include "post_pass.glsl"
#include "kernels.h"
#include "light_geometry.h"
#include "moments.h"
#include "bindings.h"
#include "params_moments.h"
#ifndef EXPONENTS
#define EXPONENTS vec2(0.0)
#endif
#ifndef STORE16
#define STORE16 false
#endif
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D source;
#ifdef FORMAT
layout(set = 0, binding = POST_OUTPUT_BINDING, FORMAT) uniform writeonly image2D blurred;
#else // the map's format follows a parameter (msm.precision): written without a format
layout(set = 0, binding = POST_OUTPUT_BINDING) uniform writeonly image2D blurred;
#endif

vec4 momentsAt(ivec2 q, ShadowViewData view) {
#if AXIS == 0
        vec2 exponents = EXPONENTS;
    return warpedMoments(MOMENTS, momentDepth(view, texelFetch(source, q, 0).r), exponents);
#else
    return texelFetch(source, q, 0);
#endif
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(push.size.xy);
    if (any(greaterThanEqual(p, size))) return;
    ShadowViewData view = views[push.size.z];
    uint taps = PARAMS.size;
    int n = scaledKernelSize(taps, view.cascade.z);
    int reach = (n - 1) / 2;
    ivec2 axis = AXIS == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int k = -reach; k <= reach; ++k) {
        float w = gaussianTap(k, n);
        sum += w * momentsAt(clamp(p + k * axis, ivec2(0), size - 1), view);
        weights += w;
    }
    vec4 result = sum / weights;
    if (AXIS == 1 && STORE16) result = msmStore16(result); // what a 16-bit unorm map holds
    imageStore(blurred, p, result);
}
