// Lights and their shadow views as the shaders see them (uniform records), and the geometry of
// a view compiled as GLSL and as C++: light view distances, texels per world unit, the light's
// extent seen from a receiver (PCSS's search and penumbra), a point light's cube face, a sun's
// cascade blend.
// clang-format off
#ifndef PENUMBRA_LIGHT_GEOMETRY_H
#define PENUMBRA_LIGHT_GEOMETRY_H
#include "shared_prelude.h"

#define LIGHT_DIRECTIONAL 0u
#define LIGHT_SPOT 1u
#define LIGHT_POINT 2u
#define MAX_CASCADES 8u          // csm.cascades' largest value (src/core/light_space.h)
// Lights and shadow views reach the screen-space passes as uniform buffers, not storage
// buffers: lavapipe loads a storage buffer one lane at a time even at a uniform index, a uniform
// buffer with one scalar load (uniform index) or a vector gather. The blocks are declared at
// these capacities (64 KiB each at most, NVIDIA's and lavapipe's maxUniformBufferRange) and bound
// at the size used; a device with a smaller range holds fewer (render checks, error: otherwise).
#define MAX_UNIFORM_LIGHTS 512u  // 96 bytes each
#define MAX_UNIFORM_VIEWS 448u   // 144 bytes each

PENUMBRA_GPU_BEGIN

struct LightData {       // std140 uniform record, one per scene light
    vec4 positionType;   // xyz position (spot, point), w: LIGHT_* type
    vec4 directionRange; // xyz direction the light travels, w range (0 = unlimited)
    vec4 colorIntensity; // rgb linear colour, a intensity
    vec4 cone;           // x cos(outer), y cos(inner), w visibility layer (-1: no shadow map)
    vec4 bias;           // x constant, y slope (both applied in the shadow pass), z normal offset
                         // (texels)
    uvec4 views;         // x first shadow view (ShadowViewData), y how many (0: no shadow map;
                         // 6 for a point light's cube faces, in cubeFace() order)
};
// One shadow view: a projection of a light into one layer of the technique's maps (a light may
// own several: cascades, cube faces).
struct ShadowViewData {  // std140 uniform record, one per shadow view
    mat4 shadowMatrix;   // world -> (u, v, depth) * w: T x the view's view-projection
    vec4 frustum;        // x near, y far (view distance), zw world size of one uv unit
                         // (orthographic) or of one uv unit at unit distance (perspective)
    vec4 texel;          // x world size of a texel (perspective: at unit distance), y 1 if
                         // perspective (2: a point light's cube face, also perspective), z the
                         // view's layer in the maps, w the light's size as
                         // this view sees it: radius (perspective) or tan(half angular diameter)
    vec4 cascade;        // x the camera view distance where this view's slice ends, y where it
                         // starts blending into the next view (both huge: not a cascade), z the
                         // kernel scale (the first cascade's texel size over this view's)
    vec4 moments;        // the part of the view's depth range the moment techniques spread
                         // their [0, 1] over (momentDepth), in the range's linear [0, 1]: from
                         // x to 1 - y (zero: the whole range)
    vec4 fromFirst;      // this view's (u, v) = xy * (u, v) of its light's first view + zw, the
                         // depth the same: a sun's cascades share one orientation and depth
                         // range (src/core/cascades.cpp), so the visibility pass maps the first
                         // cascade's receiver plane and footprint by xy (cascadeReceiver; it
                         // projects (u, v) itself, which rounds as the shadow pass does).
                         // (1, 1, 0, 0) for a light's first view.
};

// How much of the next cascade a pixel at camera view distance z takes, in a cascade whose slice
// ends at `splitFar` and starts blending at `blendStart`: 0 up to the band, rising linearly to 1
// at the split, where the next cascade alone takes over (no seam on either side of the band).
SHARED float cascadeBlendWeight(float z, float blendStart, float splitFar) {
    return splitFar > blendStart ? clamp((z - blendStart) / (splitFar - blendStart), 0.0f, 1.0f)
                                 : (z > splitFar ? 1.0f : 0.0f);
}

// The face of a point light's cube that holds direction `d` from the light: its major axis, in
// the order of src/core/light_space.h (+x, -x, +y, -y, +z, -z). Ties go to the earlier axis;
// the faces' guard bands make either choice correct.
SHARED uint cubeFace(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0u : 1u;
    if (a.y >= a.z) return d.y >= 0.0f ? 2u : 3u;
    return d.z >= 0.0f ? 4u : 5u;
}

// PCSS [Fernando 2005; seed 001] geometry of one shadow view (docs/techniques.md). Light view
// distance of a normalised light depth (inverse of the seeds' depth mappings).
SHARED float viewDistance(IN(ShadowViewData) view, float depth) {
    float n = view.frustum.x, f = view.frustum.y;
    return view.texel.y > 0.5f ? n * f / (f - depth * (f - n)) : n + depth * (f - n);
}

// Texels per world unit laterally at view distance z (u axis).
SHARED float texelsPerWorld(IN(ShadowViewData) view, float z, uint mapSize) {
    float worldPerUv = view.frustum.z * (view.texel.y > 0.5f ? z : 1.0f);
    return float(mapSize) / worldPerUv;
}

// The soft members' kernel cap in `view`: a point light's cube face (texel.y 2) has no coarser
// view to move a wide kernel to, as a sun's cascades do, so it takes the technique's own cube cap
// (`<family>.cubeRadius`, guard band as wide); spots and cascades `<family>.maxRadius`.
SHARED float kernelCap(IN(ShadowViewData) view, float maxRadius, float cubeRadius) {
    return view.texel.y > 1.5f ? cubeRadius : maxRadius;
}

// Search radius (texels): the light seen from the receiver, cut by the near plane, where the
// nearest possible blocker lies. Perspective: R (z_r - n) / z_r at the near plane;
// orthographic: (z_r - n) tan(half angle).
SHARED float blockerSearchRadius(IN(ShadowViewData) view, float zReceiver, uint mapSize) {
    float n = view.frustum.x, size = view.texel.w;
    float world = view.texel.y > 0.5f ? size * (zReceiver - n) / zReceiver : (zReceiver - n) * size;
    return world * texelsPerWorld(view, view.texel.y > 0.5f ? n : 1.0f, mapSize);
}

// Penumbra radius (texels at the receiver): perspective, the seed's
// w = (d_receiver - d_blocker) w_light / d_blocker with distances along the light; orthographic,
// (z_r - z_b) tan(half angle).
SHARED float penumbraRadius(IN(ShadowViewData) view, float zReceiver, float zBlocker, uint mapSize) {
    float size = view.texel.w;
    float world = view.texel.y > 0.5f ? (zReceiver - zBlocker) * size / zBlocker
                                      : (zReceiver - zBlocker) * size;
    return world * texelsPerWorld(view, zReceiver, mapSize);
}

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(LightData) == 96 && offsetof(LightData, cone) == 48 &&
              offsetof(LightData, bias) == 64 && offsetof(LightData, views) == 80);
static_assert(sizeof(ShadowViewData) == 144 && offsetof(ShadowViewData, frustum) == 64 &&
              offsetof(ShadowViewData, texel) == 80 && offsetof(ShadowViewData, cascade) == 96 &&
              offsetof(ShadowViewData, moments) == 112 &&
              offsetof(ShadowViewData, fromFirst) == 128);
static_assert(MAX_UNIFORM_VIEWS * sizeof(ShadowViewData) <= 65536 &&
              MAX_UNIFORM_LIGHTS * sizeof(LightData) <= 65536);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
