#version 460
// Second-depth shadow maps: the midpoint of the nearest and second-nearest depths, the surface
// the visibility pass tests against. A texel with one layer (an open surface with nothing
// behind it) gets a midpoint halfway to the far plane (depth 1, the clear value): a receiver
// behind that surface but nearer than the midpoint is wrongly lit. Hence the method's demand
// for watertight geometry, whose every front face has a back face behind it.
#include "bindings.h"
#include "pass_types.h"
layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = POST_INPUT_BINDING) uniform sampler2D firstDepth;
layout(set = 0, binding = POST_INPUT_BINDING + 1) uniform sampler2D secondDepth;
layout(set = 0, binding = POST_OUTPUT_BINDING, r32f) uniform writeonly image2D midpoint;
layout(push_constant) uniform Push { PostPassPush push; };

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), push.size.xy))) return;
    float first = texelFetch(firstDepth, p, 0).r, second = texelFetch(secondDepth, p, 0).r;
    imageStore(midpoint, p, vec4(0.5 * (first + second)));
}
