#version 460
// Checkerboard tracing's fill (checkerboard.h; src/shadows/checkerboard_fill.cpp mirrors it), one
// light's layer a dispatch, between the visibility pass's even pixels and its trace list: each
// odd pixel takes the mean of its four traced neighbours on its own surface where they lie within
// SPEC_FILL_RANGE of one another, else it goes on the trace list. A dispatch half the image high.
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
#include "checkerboard.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_FILL_RANGE) const float RANGE = 0.3;
#include "gbuffer.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = LAYER_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = LAYER_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = LAYER_VISIBILITY, r32f) uniform image2DArray visibility;
layout(set = 0, binding = LAYER_TRACE_LIST, std430) buffer TraceList {
    TraceListHead head;
    uint pixels[];
} traceList;
layout(push_constant) uniform Push { VisibilityPush push; };

void main() {
    ivec2 p = checkerboardPixel(gl_GlobalInvocationID.xy, 1u);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    int layer = int(push.light.y);
    float depth = texelFetch(gDepth, p, 0).r;
    if (isBackground(depth)) {
        imageStore(visibility, ivec3(p, layer), vec4(nanValue()));
        return;
    }
    vec3 world = worldPosition(frame.invViewProj, p, size, depth);
    vec3 normal = shadingNormal(texelFetch(gNormal, p, 0));
    // Left, right, the row before, the row after: the mirror sums in the same order.
    const ivec2 steps[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
    uint count = 0u;
    float lowest = 2.0, highest = -1.0, sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 q = p + steps[k];
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), size))) continue;
        float qDepth = texelFetch(gDepth, q, 0).r;
        if (isBackground(qDepth)) continue;
        // Every neighbour counts towards the span (a shadow's edge along an object's), only those
        // on the pixel's surface towards the mean.
        float v = imageLoad(visibility, ivec3(q, layer)).r;
        lowest = min(lowest, v);
        highest = max(highest, v);
        if (!checkerboardSameSurface(world, normal, worldPosition(frame.invViewProj, q, size, qDepth),
                                     shadingNormal(texelFetch(gNormal, q, 0))))
            continue;
        sum += v;
        ++count;
    }
    if (checkerboardFills(count, lowest, highest, RANGE)) {
        imageStore(visibility, ivec3(p, layer), vec4(sum / float(count)));
        return;
    }
    uint entry = atomicAdd(traceList.head.count, 1u);
    traceList.pixels[entry] = packPixel(p);
    // The entry that opens a column of groups (one a row) adds it.
    if (entry % (CHECKERBOARD_LIST_GROUP * traceList.head.groupsY) == 0u)
        atomicAdd(traceList.head.groupsX, 1u);
}
