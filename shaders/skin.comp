#version 460
// The `skin` pass: every skinned vertex placed by the weighted sum of its joints' matrices over
// the weights' sum (linear blend skinning), its normal by that matrix's inverse transpose (as cofactors: the determinant
// cancels when the normal is made unit, so no division), into the vertex buffer the shadow and
// G-buffer passes draw and the positions buffer the opaque casters' shadow pass draws.
#include "bindings.h"
#include "skinning.h"
layout(local_size_x = SKIN_BLOCK) in;

layout(set = 0, binding = SKIN_BIND_VERTICES, std430) readonly buffer Skinned {
    SkinVertex skinned[];
};
layout(set = 0, binding = SKIN_INFLUENCES, std430) readonly buffer Influences {
    SkinInfluence influences[];
};
layout(set = 0, binding = SKIN_JOINTS, std430) readonly buffer Joints { mat4 joints[]; };
layout(set = 0, binding = SKIN_VERTICES, std430) writeonly buffer Vertices {
    float vertexFloats[];
};
layout(set = 0, binding = SKIN_POSITIONS, std430) writeonly buffer Positions {
    float positions[];
};
layout(push_constant) uniform Push { SkinPush push; };

// The direction of inverse(transpose(m)) * n, unit; (0, 1, 0) where m or the result has none.
vec3 skinnedNormal(mat3 m, vec3 n) {
    vec3 c0 = cross(m[1], m[2]), c1 = cross(m[2], m[0]), c2 = cross(m[0], m[1]);
    float det = dot(m[0], c0);
    vec3 v = (c0 * n.x + c1 * n.y + c2 * n.z) * sign(det);
    return det != 0.0 && dot(v, v) > 0.0 ? normalize(v) : vec3(0.0, 1.0, 0.0);
}

void main() {
    uint i = push.first + gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    SkinVertex s = skinned[i];
    mat4 m = mat4(0.0);
    float total = 0.0;
    for (uint k = s.firstInfluence; k < s.firstInfluence + s.influenceCount; ++k) {
        m += influences[k].weight * joints[influences[k].joint];
        total += influences[k].weight;
    }
    m *= 1.0 / total; // weights over their sum, as the host takes them
    vec3 p = (m * vec4(s.position, 1.0)).xyz;
    vec3 n = skinnedNormal(mat3(m), s.normal);
    uint at = s.vertex * VERTEX_FLOATS;
    for (uint c = 0u; c < 3u; ++c) {
        vertexFloats[at + VERTEX_POSITION_FLOAT + c] = p[c];
        vertexFloats[at + VERTEX_NORMAL_FLOAT + c] = n[c];
        positions[3u * s.vertex + c] = p[c];
    }
}
