// Screen-space contact shadows (the `contact` layer, src/shadows/contact.cpp; shaders/contact.comp):
// the parameter block and the march's maths, compiled as GLSL and as C++ (the CPU reference).
// From a receiver, samples step towards the light; each is projected into the G-buffer, whose
// surface there is taken as the plane of its own triangle (position and face normal), so that a
// plane never hides a point above it whatever the angle it is seen at: the test is exact for the
// receiver's own surface, which a plain depth comparison is not (it compares with the depth at
// the texel's centre).
// clang-format off
#ifndef PENUMBRA_CONTACT_MARCH_H
#define PENUMBRA_CONTACT_MARCH_H
#include "technique_block.h"

PENUMBRA_GPU_BEGIN

struct ContactParams {   // std140, the layer's block (LAYER_PARAMS)
    float marchLength;   // contact.length: how far the march goes towards the light (world units)
    uint steps;          // contact.steps: samples along it
    float thickness;     // how deep a surface in the depth buffer is taken to be (world units)
    uint pad;
};

// The world point at normalised device coordinates `ndc` (reverse-Z: the near plane is 1).
SHARED vec3 unprojectNdc(IN(mat4) invViewProj, vec3 ndc) {
    vec4 world = invViewProj * vec4(ndc, 1.0f);
    return vec3(world.x, world.y, world.z) / world.w;
}

// The world size of a pixel at ndc: the distance to its neighbour along the image's x axis at
// the same depth.
SHARED float pixelFootprint(IN(mat4) invViewProj, vec3 ndc, float width) {
    return length(unprojectNdc(invViewProj, ndc + vec3(2.0f / width, 0.0f, 0.0f)) -
                  unprojectNdc(invViewProj, ndc));
}

// Where world point q falls in an image of `size` pixels seen through viewProj: its ndc, and
// whether it lies in front of the camera and on the image (`pixel`, continuous: texel
// (floor(pixel)) holds it).
SHARED bool contactProject(IN(mat4) viewProj, vec3 q, vec2 size, OUT(vec3) ndc, OUT(vec2) pixel) {
    vec4 clip = viewProj * vec4(q, 1.0f);
    ndc = vec3(clip.x, clip.y, clip.z) / clip.w;
    pixel = (vec2(ndc.x, ndc.y) * 0.5f + 0.5f) * size;
    return clip.w > 0.0f && pixel.x >= 0.0f && pixel.y >= 0.0f && pixel.x < size.x &&
           pixel.y < size.y;
}

// How far in front of a sample a surface must lie to hide it: half a pixel's footprint (the depth
// buffer's rounding; a texel's plane read a fraction of a pixel off its centre), and a step of
// the march: a sample just past a convex edge or a curved silhouette lies behind the
// neighbouring face's plane by less than the step that brought it there, while one that entered
// a body falls further behind its surface with every step.
SHARED float contactTolerance(IN(mat4) invViewProj, vec3 ndc, float width, float step) {
    return max(0.5f * pixelFootprint(invViewProj, ndc, width), 0.5f * step);
}

// The first of the 2x2 pixels whose centres surround continuous pixel position `pixel` in an
// image of `size` (clamped so that all four lie in it).
SHARED ivec2 contactTexels(vec2 pixel, uvec2 size) {
    vec2 first = floor(pixel - 0.5f);
    return ivec2(clamp(first, vec2(0.0f), vec2(float(size.x) - 2.0f, float(size.y) - 2.0f)));
}

// The bilinear weight of texel k (x = k & 1, y = k >> 1) of the four from `base` at `pixel`.
SHARED float contactTexelWeight(vec2 pixel, ivec2 base, int k) {
    vec2 f = clamp(pixel - 0.5f - vec2(base), vec2(0.0f), vec2(1.0f));
    float wx = (k & 1) != 0 ? f.x : 1.0f - f.x;
    float wy = (k >> 1) != 0 ? f.y : 1.0f - f.y;
    return wx * wy;
}

// How far along the ray sample i of `steps` lies: evenly spaced, the first offset by
// `jitter` (in [0, 1), per pixel) of a step, so that the steps' banding becomes noise.
SHARED float contactSampleDistance(uint i, uint steps, float marchLength, float jitter) {
    return marchLength * (float(i) + jitter) / float(steps);
}

// Whether the surface through `surface` with normal `normal` (the G-buffer's plane where sample
// q falls) hides q from the light: along the camera's ray to q (from `near`, the ray's point on
// the near plane), the plane lies in front of q by more than `tolerance` (what a texel's plane
// and the depth buffer's rounding can be off by) and by less than `thickness` (a surface has that
// much behind it: farther behind, the ray passes behind the object). A plane seen edge-on is
// placed at its own point's distance along the ray.
SHARED bool contactOccludes(vec3 q, vec3 near, vec3 surface, vec3 normal, float tolerance,
                            float thickness) {
    vec3 ray = q - near;
    float along = length(ray);
    float facing = dot(ray, normal);
    float u = abs(facing) > 1e-4f * along ? dot(surface - near, normal) / facing
                                           : dot(surface - near, ray) / (along * along);
    float gap = (1.0f - u) * along; // how far in front of q the surface lies
    // Seen at an angle, a body of `thickness` extends less far behind its surface along the
    // view: a sphere's or a cylinder's chord is its diameter times cos(angle), nothing at its
    // silhouette, where a sample beside it would otherwise read as inside it.
    float depth = thickness * abs(facing) / along;
    return gap > tolerance && gap < depth;
}

PENUMBRA_GPU_END

PENUMBRA_LAYER_BLOCK(ContactBlock, ContactParams, contact)

#endif
// clang-format on
