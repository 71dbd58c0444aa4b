#version 460
// A map averaged over frames: the worked example of a post pass that reads last frame's version
// of a map kept with history (docs/architecture.md, "Adding a technique"). Input 0 is this
// frame's value, input 1 last frame's average (`<map> (previous)`); bit 1 of PostPassPush.size.w
// says whether it holds last frame's contents. Where it holds zeros (the first frame, a cut, a
// new size, views that moved), the average starts again from this frame's value.
#include "bindings.h"
#include "pass_types.h"
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D current;
layout(set = 0, binding = POST_INPUT_BINDING + 1) uniform sampler2D lastAverage;
layout(set = 0, binding = POST_OUTPUT_BINDING, r32f) uniform writeonly image2D average;
layout(push_constant) uniform Push { PostPassPush push; };

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), push.size.xy))) return;
    float now = texelFetch(current, p, 0).r;
    bool held = (push.size.w & 2u) != 0u;
    imageStore(average, p, vec4(held ? 0.5 * (now + texelFetch(lastAverage, p, 0).r) : now));
}
