// Shadow-map ray tracing (`smrt`, src/shadows/smrt.cpp; shaders/include/shadow_smrt.glsl): the
// parameter block and the march's maths, compiled as GLSL and as C++ (the CPU reference), so
// that the shader and its mirror share every decision and differ only in how they fetch texels.
// Everything happens in the shadow view's own space: x, y lateral world units, z the light view
// distance (viewDistance); a perspective view's light sits at the origin, an orthographic one's
// light lies towards -z. docs/techniques.md ("Shadow-map ray tracing") derives each step.
// clang-format off
#ifndef PENUMBRA_SMRT_MARCH_H
#define PENUMBRA_SMRT_MARCH_H
#include "light_geometry.h"
#include "technique_block.h"

PENUMBRA_GPU_BEGIN

struct SmrtParams {      // std140
    uint rays;           // smrt.rays: rays per pixel towards points of the light
    uint samples;        // smrt.samples: map samples along each ray
    uint rotation;       // smrt.rotation: ROTATION_* (the per-pixel rotation of the ray set)
    float maxRadius;     // smrt.maxRadius: how far (texels) a ray's samples may move from the
                         // receiver's texel; beyond, the ray is extrapolated
    float slope;         // smrt.slope: the steepest surface (depth per lateral unit) a crossing
                         // may have; steeper changes between samples are silhouettes
    uint refine;         // smrt.refine: halvings of an interval where the ray changes side of
                         // the surface, before the crossing test
    uint adaptive;       // smrt.adaptive: rays traced first (round the light's rim); no more
                         // where they agree (0: off)
    uint cubeRays;       // smrt.cubeRays, smrt.cubeSamples: rays and samples on a point
    uint cubeSamples;    // light's cube faces (smrtBudget)
    uint pad0;
    uint pad1;
    uint pad2;
};

// The rays per pixel (x) and samples per ray (y) in `view`. A point light's cube face (texel.y 2)
// takes its own: with the light inside the scene, a ray towards the light's rim sweeps hundreds
// of texels of the 90-degree face as it nears the light, so the march's spacing, not the rays'
// noise, is what limits it there (docs/techniques.md, "Shadow-map ray tracing").
SHARED uvec2 smrtBudget(IN(ShadowViewData) view, IN(SmrtParams) params) {
    return view.texel.y > 1.5f ? uvec2(params.cubeRays, params.cubeSamples)
                               : uvec2(params.rays, params.samples);
}

// A point of the view's space from its map coordinates (uv) and light view distance z.
SHARED vec3 smrtViewPoint(IN(ShadowViewData) view, vec2 uv, float z) {
    float scale = view.texel.y > 0.5f ? z : 1.0f;
    return vec3((uv.x - 0.5f) * view.frustum.z * scale, (uv.y - 0.5f) * view.frustum.w * scale, z);
}

// Where point q of the view's space falls in the map (uv).
SHARED vec2 smrtProject(IN(ShadowViewData) view, vec3 q) {
    float scale = view.texel.y > 0.5f ? q.z : 1.0f;
    float inverse = 1.0f / scale; // one division a sample: the march's inner loop
    return vec2(q.x * inverse / view.frustum.z, q.y * inverse / view.frustum.w) + 0.5f;
}

// World size of a texel of a map of `mapSize` at light view distance z.
SHARED float smrtTexelWorld(IN(ShadowViewData) view, float z, uint mapSize) {
    return view.frustum.z * (view.texel.y > 0.5f ? z : 1.0f) / float(mapSize);
}

// The k-th of n ray directions from receiver p towards the light, uniform in solid angle over the
// cone the light subtends (a sphere of radius texel.w seen from p; a sun's cone of half-angle
// atan(texel.w)): stratified along the cone's radius (jittered within each stratum), a
// golden-angle spiral round it turned by the pixel's `turns` (a rotated low-discrepancy set per
// pixel). Rays n - 1, n - 2, ... lie round the rim, a golden angle apart.
SHARED vec3 smrtRayDirection(IN(ShadowViewData) view, vec3 p, uint k, uint n, float turns) {
    bool perspective = view.texel.y > 0.5f;
    vec3 w = perspective ? -p / max(length(p), 1e-20f) : vec3(0.0f, 0.0f, -1.0f);
    float size = view.texel.w;
    float cosAlpha = perspective ? sqrt(max(1.0f - min(size * size / max(dot(p, p), 1e-20f), 1.0f), 0.0f))
                                 : 1.0f / sqrt(1.0f + size * size);
    float a = (float(k) + fract(turns * 1.618034f + 0.5f)) / float(n); // ray n - 1: the rim
    float b = fract(float(k) * 0.618034f + turns);
    float cosTheta = 1.0f - a * (1.0f - cosAlpha);
    float sinTheta = sqrt(max(1.0f - cosTheta * cosTheta, 0.0f));
    float phi = 6.2831853f * b;
    vec3 helper = abs(w.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    vec3 t1 = normalize(cross(w, helper));
    vec3 t2 = cross(w, t1);
    return cosTheta * w + sinTheta * (cos(phi) * t1 + sin(phi) * t2);
}

// C of a perspective view: a point s along the ray lies s C / (z (z + s d.z)) texels from p's.
SHARED float smrtPerspectiveRate(IN(ShadowViewData) view, vec3 p, vec3 d, uint mapSize) {
    vec2 rate = vec2((d.x * p.z - p.x * d.z) / view.frustum.z, (d.y * p.z - p.y * d.z) / view.frustum.w);
    return length(rate) * float(mapSize);
}

// The s at which a perspective march's point falls `texels` from p's in the map (1e30: never).
SHARED float smrtPerspectiveReach(vec3 p, vec3 d, float c, float texels) {
    float denominator = c - texels * p.z * d.z;
    return denominator > 1e-20f ? texels * p.z * p.z / denominator : 1e30f;
}

// How far along direction d from p the march goes: to the near plane (no caster lies nearer the
// light), and no farther than where its point falls maxTexels texels from p's in the map. The
// map offset grows with s as s C / (z (z + s d.z)) (perspective) or s C (orthographic), C the
// lateral rate; solved for maxTexels.
// `rate`: smrtPerspectiveRate for a perspective view (its caller has it), unused otherwise.
SHARED float smrtMarchLength(IN(ShadowViewData) view, vec3 p, vec3 d, float maxTexels, uint mapSize,
                             float rate) {
    float nearPlane = view.frustum.x;
    float toNear = d.z < -1e-6f ? (p.z - nearPlane) / -d.z : 1e30f;
    float size = float(mapSize);
    float toCap;
    if (view.texel.y > 0.5f) {
        toCap = smrtPerspectiveReach(p, d, rate, maxTexels);
    } else {
        float c = length(vec2(d.x / view.frustum.z, d.y / view.frustum.w)) * size;
        toCap = c > 1e-20f ? maxTexels / c : 1e30f;
    }
    return max(min(toNear, toCap), 0.0f);
}

// Where a ray's samples go: squared spacing (dense near the receiver, where contact shadows are),
// in distance along the ray, except on a point light's cube face (texel.y 2), where it is squared
// in texels of the map: a ray towards a close light's rim sweeps most of its texels in its last
// stretch, which samples squared in distance cross in a few long steps. Once per ray: the march's
// length (extent), and on a cube face its lateral rate C and the texels its end lies from p's.
struct SmrtMarch {
    float extent;
    float rate;
    float texels;
    bool byTexels;
};

SHARED SmrtMarch smrtMarch(IN(ShadowViewData) view, vec3 p, vec3 d, float maxTexels, uint mapSize) {
    SmrtMarch march;
    march.rate = view.texel.y > 0.5f ? smrtPerspectiveRate(view, p, d, mapSize) : 0.0f;
    march.extent = smrtMarchLength(view, p, d, maxTexels, mapSize, march.rate);
    march.byTexels = view.texel.y > 1.5f;
    march.texels = march.byTexels ? march.extent * march.rate /
                                        max(p.z * (p.z + march.extent * d.z), 1e-20f)
                                  : 0.0f;
    return march;
}

// Sample i of n along the march, offset by `jitter` of a step.
SHARED float smrtSampleDistance(IN(SmrtMarch) march, vec3 p, vec3 d, uint i, uint n, float jitter) {
    float t = (float(i) + jitter) / float(n);
    if (!march.byTexels) return march.extent * t * t;
    return min(smrtPerspectiveReach(p, d, march.rate, march.texels * t * t), march.extent);
}

// A point of a ray's march: how far along the ray (s), its light view distance and map position,
// how far it lies behind the map's surface there (<= slack: on or in front of it) and that slack:
// the depth a surface of the steepest slope changes over the 0.75 texel between a point and its
// texel's centre.
struct SmrtPoint {
    float s;
    float z;
    vec2 uv;
    float behind;
    float slack;
};

// The point at s along direction d from p, before its texel is read.
SHARED SmrtPoint smrtPointAt(IN(ShadowViewData) view, vec3 p, vec3 d, float s) {
    vec3 q = p + s * d;
    SmrtPoint point;
    point.s = s;
    point.z = q.z;
    point.uv = smrtProject(view, q);
    point.behind = 0.0f;
    point.slack = 0.0f;
    return point;
}

// The point against the map's surface there (light view distance `stored`).
SHARED void smrtSetStored(INOUT(SmrtPoint) point, IN(ShadowViewData) view, float stored,
                          uint mapSize, float slope) {
    point.behind = point.z - stored;
    point.slack = 0.75f * slope * smrtTexelWorld(view, point.z, mapSize);
}

SHARED bool smrtIsBehind(IN(SmrtPoint) point) { return point.behind > point.slack; }

// Whether the ray crosses the map's surface between points a and b, one in front and one behind
// (the march halves the interval smrt.refine times first): the one behind lies no farther behind
// than the crossing can explain, the ray's own change of depth between them and what a surface of
// the steepest slope changes over their lateral distance. A larger gap is a silhouette: the ray
// passed beside an occluder, behind its visible side, without meeting it. `margin` is how near
// the comparison came to a tie, relative to the distance (the parity tests skip those).
SHARED bool smrtCrosses(IN(ShadowViewData) view, IN(SmrtPoint) a, IN(SmrtPoint) b, float slope,
                        OUT(float) margin) {
    bool bBehind = smrtIsBehind(b);
    float stored = bBehind ? b.z - b.behind : a.z - a.behind;
    float lateral = length((b.uv - a.uv) * vec2(view.frustum.z, view.frustum.w)) *
                    (view.texel.y > 0.5f ? stored : 1.0f);
    float reach = abs(b.z - a.z) + slope * lateral + max(a.slack, b.slack);
    float gap = bBehind ? b.behind : a.behind;
    margin = abs(gap - reach) / max(b.z, 1.0f);
    return gap <= reach;
}

PENUMBRA_GPU_END

PENUMBRA_TECHNIQUE_BLOCK(SmrtBlock, SmrtParams, smrt)

#endif
// clang-format on
