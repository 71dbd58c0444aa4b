#version 460
// The translucent layer's moments: each surface's absorbance per channel and its moments of
// momentDepth (moments.h), added in by the blend (layerMoments, translucent.h).
#include "translucent_caster.glsl"

layout(location = 0) out vec4 outAbsorbance;
layout(location = 1) out vec4 outRed;
layout(location = 2) out vec4 outGreen;
layout(location = 3) out vec4 outBlue;

void main() {
    float depth;
    vec3 a = layerAbsorbance(translucentFragment(depth));
    float z = momentDepth(views[push.flags.y], depth);
    outAbsorbance = vec4(a, 0.0);
    outRed = layerMoments(a.r, z);
    outGreen = layerMoments(a.g, z);
    outBlue = layerMoments(a.b, z);
}
