// The page draws' vertex stage (page_position.vert, page_depth.vert; src/render/page_draw_passes.h):
// instance k draws the k-th page of its list into the page's square of the pool, the whole pool
// being the viewport; clip distances keep the triangles inside the square, as a viewport and
// scissor per page would. The constant bias as shadow_clip.glsl's.
#ifndef PENUMBRA_PAGE_DRAW_GLSL
#define PENUMBRA_PAGE_DRAW_GLSL
#include "page_passes.h"

layout(set = 0, binding = PAGE_DRAW_LIST, std430) readonly buffer List { PageDrawData list[]; };
layout(push_constant) uniform Push { PageDrawPush push; };

out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[4];
};

void placeInPage(vec3 position) {
    PageDrawData page = list[push.list.x * push.list.y + uint(gl_InstanceIndex)];
    precise vec4 clip = page.poolFromWorld * vec4(position, 1.0);
    clip.z += push.bias.x * clip.w;
    gl_Position = clip;
    gl_ClipDistance[0] = clip.x - page.square.x * clip.w;
    gl_ClipDistance[1] = page.square.z * clip.w - clip.x;
    gl_ClipDistance[2] = clip.y - page.square.y * clip.w;
    gl_ClipDistance[3] = page.square.w * clip.w - clip.y;
}

#endif
