// Receiver-plane depth bias [Tuft 2010; seed 000]: the receiver's light depth as a linear
// function of shadow-map (u, v) on its tangent plane, so each filter tap compares against the
// depth the receiver has *at that tap* instead of at its centre.
#ifndef PENUMBRA_RECEIVER_PLANE_GLSL
#define PENUMBRA_RECEIVER_PLANE_GLSL
#include "gpu_types.h"

// The three rows of d(u, v, depth)/d(world) at `world` for the projective map S.
void shadowJacobian(mat4 S, vec3 world, out vec3 du, out vec3 dv, out vec3 dz) {
    vec4 s = S * vec4(world, 1.0);
    vec3 rowW = vec3(S[0][3], S[1][3], S[2][3]);
    du = (vec3(S[0][0], S[1][0], S[2][0]) - (s.x / s.w) * rowW) / s.w;
    dv = (vec3(S[0][1], S[1][1], S[2][1]) - (s.y / s.w) * rowW) / s.w;
    dz = (vec3(S[0][2], S[1][2], S[2][2]) - (s.z / s.w) * rowW) / s.w;
}

// `light`: from the surface normal. The plane's normal in (u, v, depth) space is J^-T N, and
// J^-T is the cofactor matrix of J over det J, whose rows are du x dz... (see techniques.md).
vec2 receiverGradientFromNormal(mat4 S, vec3 world, vec3 normal) {
    vec3 du, dv, dz;
    shadowJacobian(S, world, du, dv, dz);
    float nu = dot(cross(dv, dz), normal);
    float nv = dot(cross(dz, du), normal);
    float nz = dot(cross(du, dv), normal);
    if (abs(nz) <= 1e-6 * (abs(nu) + abs(nv))) return vec2(0.0); // edge-on to the light
    return vec2(-nu, -nv) / nz;
}

// `screen`: from the light-space offsets to two neighbouring pixels (seed 000's 2x2 solve):
// [dz/du, dz/dv] = [dz/dx, dz/dy] [[du/dx, dv/dx], [du/dy, dv/dy]]^-1.
vec2 receiverGradientFromOffsets(vec3 alongX, vec3 alongY) {
    float det = alongX.x * alongY.y - alongX.y * alongY.x;
    if (abs(det) < 1e-20) return vec2(0.0);
    return vec2(alongX.z * alongY.y - alongY.z * alongX.y,
                alongX.x * alongY.z - alongY.x * alongX.z) / det;
}

#endif
