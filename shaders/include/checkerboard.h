// Checkerboard tracing of a technique's visibility (ScreenPassDecl::fillsCheckerboard; smrt),
// compiled as GLSL and as C++ (the CPU mirror, src/shadows/checkerboard_fill.cpp). The visibility
// pass traces the pixels whose x + y is even (CHECKERBOARD_EVEN: a dispatch half the image high,
// every lane a pixel); visibility_fill.comp gives each other pixel the mean of its four traced
// neighbours on its own surface where they lie within the range of one another, and appends the
// rest to the trace list; the visibility pass then traces the list (CHECKERBOARD_LIST, an
// indirect dispatch of as many groups as the list needs). A penumbra's smooth inside is filled,
// its edges and every lone pixel traced.
// clang-format off
#ifndef PENUMBRA_CHECKERBOARD_H
#define PENUMBRA_CHECKERBOARD_H
#include "shared_prelude.h"
#include "bindings.h"
#include "visibility_filter_weights.h"

// The visibility pass's modes (SPEC_CHECKERBOARD).
#define CHECKERBOARD_OFF 0u  // every pixel
#define CHECKERBOARD_EVEN 1u // the pixels with x + y even
#define CHECKERBOARD_LIST 2u // the trace list's pixels
// Invocations of a list dispatch's workgroup: GROUP_SIZE x GROUP_SIZE, one entry each.
#define CHECKERBOARD_LIST_GROUP (GROUP_SIZE * GROUP_SIZE)
// Groups a row of the list's dispatch at most: the least maxComputeWorkGroupCount[0] a device may
// have. A longer list (over 4 million pixels: an image of 8 million and more) takes more rows.
#define CHECKERBOARD_ROW_GROUPS 65535u

PENUMBRA_GPU_BEGIN

// The trace list's head: the indirect dispatch's group counts (x grows with the list, a group
// every groupsY x CHECKERBOARD_LIST_GROUP entries; y, the rows the host chose for the image, and
// z stay), then how many pixels the list holds. The pixels follow, packed by packPixel.
struct TraceListHead {
    uint groupsX, groupsY, groupsZ, count;
};

// The rows of groups a list of up to `entries` pixels takes: enough that no row passes
// CHECKERBOARD_ROW_GROUPS, and at least one.
SHARED uint checkerboardListRows(uint entries) {
    uint groups = (entries + CHECKERBOARD_LIST_GROUP - 1u) / CHECKERBOARD_LIST_GROUP;
    return max((groups + CHECKERBOARD_ROW_GROUPS - 1u) / CHECKERBOARD_ROW_GROUPS, 1u);
}

// The pixel of invocation g in a dispatch half the image high: the one of column g.x in the rows
// 2 g.y, 2 g.y + 1 whose x + y has the parity `odd` (0: the traced ones, 1: the filled ones). A
// row of invocations (a SIMD group's lanes) covers a block two rows high, not a row twice as long:
// neighbours in the image share more of their rays' work.
SHARED ivec2 checkerboardPixel(uvec2 g, uint odd) {
    return ivec2(int(g.x), int(2u * g.y + ((g.x + odd) & 1u)));
}

// The rows of invocations such a dispatch takes on an image `height` pixels high: one a pair of
// rows, the last pair of an odd height half on the image.
SHARED uint checkerboardRows(uint height) { return (height + 1u) / 2u; }

SHARED uint packPixel(ivec2 p) { return uint(p.x) | (uint(p.y) << 16u); }
SHARED ivec2 unpackPixel(uint packed) {
    return ivec2(int(packed & 0xffffu), int(packed >> 16u));
}

// Whether neighbour q (world position, unit normal m) lies on pixel p's surface (n): near its
// tangent plane for its distance and facing its way (the filter's own bounds).
SHARED bool checkerboardSameSurface(vec3 p, vec3 n, vec3 q, vec3 m) {
    vec3 d = q - p;
    return abs(dot(n, d)) <= FILTER_PLANE_SLOPE * length(d) && dot(n, m) >= FILTER_NORMAL_COS;
}

// Whether a pixel with `count` neighbours on its surface takes their mean (else it is traced):
// some neighbour, and all its neighbours, on its surface or not, within `range` of one another
// ([lowest, highest]): a shadow's edge that runs along an object's edge is traced.
SHARED bool checkerboardFills(uint count, float lowest, float highest, float range) {
    return count > 0u && highest - lowest <= range;
}

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(TraceListHead) == 16);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
