// How the G-buffer stores normals, compiled as GLSL (gbuffer.frag writes, the screen-space
// passes read) and as C++ (the tests check the round trip).
// clang-format off
#ifndef PENUMBRA_GBUFFER_ENCODING_H
#define PENUMBRA_GBUFFER_ENCODING_H
#include "shared_prelude.h"

PENUMBRA_GPU_BEGIN

// The G-buffer keeps two unit normals in one RGBA16F texel, each folded onto the octahedron
// |x| + |y| + |z| = 1 and its lower half unfolded over the corners [Cigolle et al. 2014].
// The lower half's fold, its own inverse: a point of the inner diamond to the corner beyond the
// edge facing it, and back.
SHARED vec2 octahedralFold(vec2 p) {
    return vec2((1.0f - abs(p.y)) * (p.x >= 0.0f ? 1.0f : -1.0f),
                (1.0f - abs(p.x)) * (p.y >= 0.0f ? 1.0f : -1.0f));
}

SHARED vec2 octahedralEncode(vec3 n) {
    vec2 p = vec2(n.x, n.y) / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z >= 0.0f ? p : octahedralFold(p);
}

SHARED vec3 octahedralDecode(vec2 e) {
    float z = 1.0f - abs(e.x) - abs(e.y);
    vec2 p = z >= 0.0f ? e : octahedralFold(e);
    vec3 n = vec3(p.x, p.y, z);
    return n / sqrt(dot(n, n));
}

PENUMBRA_GPU_END

#endif
// clang-format on
