#version 460
// Clears the squares of the pages the decisions render (src/render/page_draw_passes.h): instance
// k covers the k-th page's square of the pool at the far plane (two triangles, depth test
// always), before the casters are drawn into it.
#include "page_passes.h"

layout(set = 0, binding = PAGE_DRAW_RENDER, std430) readonly buffer Render { PageRenderData render[]; };
layout(push_constant) uniform Push { PageDrawPush push; };

void main() {
    uint side = push.list.z, physical = render[gl_InstanceIndex].physical;
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(1, 0), vec2(1, 1), vec2(0, 1));
    vec2 lo = -1.0 + 2.0 * vec2(physical % side, physical / side) / float(side);
    gl_Position = vec4(lo + corners[gl_VertexIndex] * 2.0 / float(side), 1.0, 1.0);
}
