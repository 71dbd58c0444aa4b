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
    uint skipLit;        // smrt.skipLit: 1: pixels the map's bounds prove fully lit trace no ray
    uint cubeAdaptive;   // smrt.cubeAdaptive: smrt.adaptive on a point light's cube faces
    uint gapSamples;     // smrt.gapSamples: samples added inside a long step in front of the
                         // surface that the map's bounds cannot prove clear (0: off)
    uint cubeGapSamples; // smrt.cubeGapSamples: smrt.gapSamples on a point light's cube faces
    uint hidden;         // smrt.hidden: 1: a ray that comes out from behind a caster crossed the
                         // surface it comes out over where that surface, continued, hid it
                         // (smrtCrossedHidden; spots and suns)
    uint cubeHidden;     // smrt.cubeHidden: smrt.hidden on a point light's cube faces
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

// The rim rays traced before the adaptive stop may end the pixel's march (smrtBudget's faces take
// their own).
SHARED uint smrtAdaptive(IN(ShadowViewData) view, IN(SmrtParams) params) {
    return view.texel.y > 1.5f ? params.cubeAdaptive : params.adaptive;
}

// smrt.hidden where it applies (smrtBudget's faces take their own, smrt.cubeHidden).
SHARED uint smrtHiddenOn(IN(ShadowViewData) view, IN(SmrtParams) params) {
    return view.texel.y > 1.5f ? params.cubeHidden : params.hidden;
}

// The samples added inside a long step (smrt.gapSamples; smrtBudget's faces take their own).
SHARED uint smrtGapSamples(IN(ShadowViewData) view, IN(SmrtParams) params) {
    return view.texel.y > 1.5f ? params.cubeGapSamples : params.gapSamples;
}

// A point of the view's space from its map coordinates (uv) and light view distance z.
SHARED vec3 smrtViewPoint(IN(ShadowViewData) view, vec2 uv, float z) {
    float scale = view.texel.y > 0.5f ? z : 1.0f;
    return vec3((uv.x - 0.5f) * view.frustum.z * scale, (uv.y - 0.5f) * view.frustum.w * scale, z);
}

// The view's quotients the march takes at every read, once a pixel (smrtScaleOf): in the march's
// loop a division costs several multiplications, and on lavapipe the bulbs' visibility pass ran
// 7-11% longer with these in it.
struct SmrtScale {
    vec2 uvPerWorld;  // 1 / frustum.zw: uv units a world unit (perspective: at unit distance)
    float texelWorld; // a texel's world size, frustum.z / mapSize (perspective: at unit distance)
};

SHARED SmrtScale smrtScaleOf(IN(ShadowViewData) view, uint mapSize) {
    SmrtScale scale;
    scale.uvPerWorld = vec2(1.0f / view.frustum.z, 1.0f / view.frustum.w);
    scale.texelWorld = view.frustum.z / float(mapSize);
    return scale;
}

// Where point q of the view's space falls in the map (uv).
SHARED vec2 smrtProject(IN(ShadowViewData) view, IN(SmrtScale) scale, vec3 q) {
    float inverse = view.texel.y > 0.5f ? 1.0f / q.z : 1.0f; // one division a read
    return vec2(q.x * (inverse * scale.uvPerWorld.x), q.y * (inverse * scale.uvPerWorld.y)) +
           0.5f;
}

// World size of a texel of the map at light view distance z.
SHARED float smrtTexelWorld(IN(ShadowViewData) view, IN(SmrtScale) scale, float z) {
    return scale.texelWorld * (view.texel.y > 0.5f ? z : 1.0f);
}

// The cosine of the half-angle of the cone the light fills seen from p: a sphere of radius
// texel.w (perspective), a sun of angular radius atan(texel.w).
SHARED float smrtConeCos(IN(ShadowViewData) view, vec3 p) {
    float size = view.texel.w;
    return view.texel.y > 0.5f
               ? sqrt(max(1.0f - min(size * size / max(dot(p, p), 1e-20f), 1.0f), 0.0f))
               : 1.0f / sqrt(1.0f + size * size);
}

// The k-th of n ray directions from receiver p towards the light, uniform in solid angle over the
// cone the light subtends (a sphere of radius texel.w seen from p; a sun's cone of half-angle
// atan(texel.w)): stratified along the cone's radius (jittered within each stratum), a
// golden-angle spiral round it turned by the pixel's `turns` (a rotated low-discrepancy set per
// pixel). Rays n - 1, n - 2, ... lie round the rim, a golden angle apart.
SHARED vec3 smrtRayDirection(IN(ShadowViewData) view, vec3 p, uint k, uint n, float turns) {
    bool perspective = view.texel.y > 0.5f;
    vec3 w = perspective ? -p / max(length(p), 1e-20f) : vec3(0.0f, 0.0f, -1.0f);
    float cosAlpha = smrtConeCos(view, p);
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
// length (extent), and on a cube face its lateral rate C and the texels its end lies from p's; a
// sample's share of it, 1 / samples, so that no sample divides by their count (SmrtScale).
struct SmrtMarch {
    float extent;
    float rate;
    float texels;
    bool byTexels;
    float perSample;
};

SHARED SmrtMarch smrtMarch(IN(ShadowViewData) view, vec3 p, vec3 d, float maxTexels, uint mapSize,
                           uint samples) {
    SmrtMarch march;
    march.perSample = 1.0f / float(samples);
    march.rate = view.texel.y > 0.5f ? smrtPerspectiveRate(view, p, d, mapSize) : 0.0f;
    march.extent = smrtMarchLength(view, p, d, maxTexels, mapSize, march.rate);
    march.byTexels = view.texel.y > 1.5f;
    march.texels = march.byTexels ? march.extent * march.rate /
                                        max(p.z * (p.z + march.extent * d.z), 1e-20f)
                                  : 0.0f;
    return march;
}

// Sample i along the march, offset by `jitter` of a step.
SHARED float smrtSampleDistance(IN(SmrtMarch) march, vec3 p, vec3 d, uint i, float jitter) {
    float t = (float(i) + jitter) * march.perSample;
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
SHARED SmrtPoint smrtPointAt(IN(ShadowViewData) view, IN(SmrtScale) scale, vec3 p, vec3 d,
                             float s) {
    vec3 q = p + s * d;
    SmrtPoint point;
    point.s = s;
    point.z = q.z;
    point.uv = smrtProject(view, scale, q);
    point.behind = 0.0f;
    point.slack = 0.0f;
    return point;
}

// The stop short of the light (smrt.skipLit's bounds): no read of a point nearer the light than
// the nearest depth its map layer holds can lie behind the surface, as every texel stores at least
// that distance, and then smrtIsBehind's `behind` is negative. On a ray that nears the light
// (d.z < 0: z only falls) the march stops before a read that near, with the last read in front:
// nothing after it changes side, so the ray is lit, as the march to its end would find it (the
// mirror, src/shadows/smrt.cpp, marches on, and the parity test holds the two equal). `depth`: the
// nearest stored depth (the bounds' last level). Less 1e-5 of the distance and 4e-7 of the depth
// range, for viewDistance's rounding: an orthographic view's distances may be negative or zero.
SHARED float smrtNearestBehind(IN(ShadowViewData) view, float depth) {
    float z = viewDistance(view, depth);
    return z - (1e-5f * abs(z) + 4e-7f * abs(view.frustum.y - view.frustum.x));
}

// The slack of a point at light view distance z (SmrtPoint).
SHARED float smrtSlack(IN(ShadowViewData) view, IN(SmrtScale) scale, float z, float slope) {
    return 0.75f * slope * smrtTexelWorld(view, scale, z);
}

// The point against the map's surface there (light view distance `stored`).
SHARED void smrtSetStored(INOUT(SmrtPoint) point, IN(ShadowViewData) view, IN(SmrtScale) scale,
                          float stored, float slope) {
    point.behind = point.z - stored;
    point.slack = smrtSlack(view, scale, point.z, slope);
}

SHARED bool smrtIsBehind(IN(SmrtPoint) point) { return point.behind > point.slack; }

// A read of the march as the shader carries it from one iteration of its loop to the next: how
// far along the ray, and how far behind the map's surface. The rest of its SmrtPoint follows from
// these and the ray (smrtMarkPoint), with no read of the map. lavapipe keeps a group's loop state
// in the CPU's sixteen vector registers; six floats a point, for the last read, the ends of a
// halving and the hidden stretch, spilled to memory at every sample, and the bulbs' pass ran a
// tenth longer for it (docs/techniques.md, "Shadow-map ray tracing", step 13).
struct SmrtMark {
    float s;
    float behind;
};

SHARED SmrtMark smrtMarkOf(IN(SmrtPoint) x) {
    SmrtMark m;
    m.s = x.s;
    m.behind = x.behind;
    return m;
}

// The point a mark stands for on the ray from p along d: the same arithmetic as the read's.
SHARED SmrtPoint smrtMarkPoint(IN(ShadowViewData) view, IN(SmrtScale) scale, vec3 p, vec3 d,
                               IN(SmrtMark) m, float slope) {
    SmrtPoint x = smrtPointAt(view, scale, p, d, m.s);
    x.behind = m.behind;
    x.slack = smrtSlack(view, scale, x.z, slope);
    return x;
}

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

// Fully lit, proven (smrt.skipLit; docs/techniques.md, "Shadow-map ray tracing", step 9). A ray's
// point q falls behind the map only where the stored light view distance is below q.z - slack(q.z)
// at its texel. This bounds that for every ray of the pixel at once: no point of a ray from p
// towards the light that falls `texels` or more from p's position in the map lies behind a texel
// whose stored distance is at least the value returned. Perspective: a point s along direction d
// falls s C / (z (z + s d.z)) texels from p's (smrtPerspectiveRate), at light view distance
// p.z / (1 + texels p.z (-d.z) / C); over the light's cone |p x d| <= R (so C <= R / texel) and
// -d.z >= cos(alpha + beta) (alpha the cone's half-angle, beta p's angle off the view axis; past
// 90 degrees nothing is proven).
// Orthographic: the ray drops texels * texel / tan(alpha) or more towards the light. Rounding is
// allowed for (the cone as the rays' float cosine has it, a hundredth of a texel, 1e-5 p.z), so
// that it cannot make the proof claim what the march would not.
struct SmrtCeiling {
    float top;    // the ceiling at 0 texels (less the margin) ...
    float k;      // ... over 1 + texels k (perspective), ...
    float fall;   // ... less texels fall (orthographic) ...
    float margin; // ... plus this
};

// The ceiling's terms for receiver p, once a pixel (smrtLitCeiling evaluates them).
SHARED SmrtCeiling smrtCeilingOf(IN(ShadowViewData) view, vec3 p, uint mapSize, float slope) {
    float size = float(mapSize);
    float texel = min(view.frustum.z, view.frustum.w) / size; // uv units x frustum, the finer axis
    float slack = 0.75f * slope * view.frustum.z / size;      // smrtSetStored's, per unit of z
    // The cone as the rays have it (smrtRayDirection): its sine from the same float cosine, which
    // for a small light rounds far more than R / |p| does, and a little more for the rest.
    float cosAlpha = smrtConeCos(view, p);
    float sinAlpha = sqrt(max(1.0f - cosAlpha * cosAlpha, 0.0f)) * 1.0001f + 2e-7f;
    SmrtCeiling c;
    // Rounding: 1e-5 of the distance, and a few steps of the stored depth's float, which in a
    // perspective view stand for z^2 / near each (smrtDepthOf).
    float n = view.frustum.x, f = view.frustum.y;
    float depthStep = view.texel.y > 0.5f ? p.z * p.z / max(n, 1e-6f) : abs(f - n);
    c.margin = 1e-5f * abs(p.z) + 4e-7f * depthStep;
    c.k = 0.0f;
    c.fall = 0.0f;
    if (view.texel.y > 0.5f) {
        float distance = max(length(p), 1e-30f);
        float cosAlphaBeta = (cosAlpha * p.z - sinAlpha * length(vec2(p.x, p.y))) / distance;
        c.top = max(1.0f - slack, 0.0f) * p.z; // z - slack(z) = (1 - slack) z
        c.k = p.z * cosAlphaBeta * texel / (distance * sinAlpha);
        // A cone past 90 degrees off the view axis has rays that move away from the light's plane:
        // no ceiling holds.
        if (cosAlphaBeta <= 1e-6f) c.top = 1e30f;
    } else {
        c.top = p.z - slack;
        c.fall = texel * cosAlpha / sinAlpha; // texel / tan(alpha): a texel's least fall
    }
    return c;
}

// The ceiling `texels` out. A point's distance in texels may round by a hundredth of a texel: the
// ceiling is taken that much nearer in.
SHARED float smrtLitCeiling(IN(SmrtCeiling) c, float texels) {
    float reach = max(texels - 0.01f, 0.0f);
    return c.top / (1.0f + reach * c.k) - reach * c.fall + c.margin;
}

// The depth the map stores for light view distance z (viewDistance's inverse): the proof compares
// stored depths with the ceiling's, one division a ring rather than one a texel.
SHARED float smrtDepthOf(IN(ShadowViewData) view, float z) {
    float n = view.frustum.x, f = view.frustum.y;
    return view.texel.y > 0.5f ? f * (z - n) / (max(z, 1e-30f) * (f - n)) : (z - n) / (f - n);
}

// What the map hides (smrt.hidden). A ray behind the map's surface for a stretch, in front of it
// again where smrtCrosses sees a silhouette, passed under what hid it, or through a surface the
// map cannot show there: a table top under the slats of a roof above it. Where the surface the
// ray comes out in front of, continued as a plane back to the stretch's first point, lies nearer
// the light than that point did, the ray crossed it, hidden. The plane is the stored depth's (a
// plane's depth is affine in the map, perspective or not), fitted through texels on the far
// side, away from what hid the ray (docs/techniques.md, "Shadow-map ray tracing", step 11).
// The march carries distances along the ray (`first`, `front`), not points (SmrtMark); the check
// makes their points again (smrtMarkPoint), and reads nothing for them.
struct SmrtHidden {
    float first; // how far along the ray the stretch's first point lies
    bool behind; // the last point lay behind the surface (the stretch goes on)
};

// A ray's stretches from its first point, the receiver (`first` is read only while `behind`).
SHARED SmrtHidden smrtHiddenFrom(bool receiverBehind) {
    SmrtHidden h;
    h.first = 0.0f;
    h.behind = receiverBehind;
    return h;
}

// The stretch after the march's point s along the ray, behind the surface or not (every point
// after the receiver, in order).
SHARED void smrtTrackHidden(INOUT(SmrtHidden) h, float s, bool behind) {
    if (behind && !h.behind) h.first = s;
    h.behind = behind;
}

SHARED bool smrtMayCrossHidden(IN(SmrtHidden) h, bool frontBehind) {
    return h.behind && !frontBehind;
}

// The place the march checks for a hidden surface: the first where the ray came out in front of
// the surface after a stretch behind it and the crossing test saw a silhouette, with that
// stretch. It is checked once, after the march, and not where it is found: lavapipe runs the
// check's reads for a group of pixels whenever one pixel of it needs them, and a march with the
// check inside cost the bulbs 30% against 13% (docs/techniques.md, step 11). A ray that meets
// the surface later is blocked anyway; only a second silhouette after a first that hid nothing
// goes unchecked.
struct SmrtHiddenCandidate {
    float first; // the stretch's first point (SmrtHidden), along the ray
    float front; // where the ray came out in front, along the ray
    bool found;
};

SHARED SmrtHiddenCandidate smrtNoHiddenCandidate() {
    SmrtHiddenCandidate c;
    c.first = 0.0f;
    c.front = 0.0f;
    c.found = false;
    return c;
}

// After a side change the crossing test called a silhouette, at the point `front` along the ray.
SHARED void smrtNoteHidden(INOUT(SmrtHiddenCandidate) c, IN(SmrtHidden) h, float front,
                           bool frontBehind) {
    if (!c.found && smrtMayCrossHidden(h, frontBehind)) {
        c.first = h.first;
        c.front = front;
        c.found = true;
    }
}

SHARED float smrtHiddenBaseline() { return 8.0f; }

// The texels where the surface in front of which the ray comes out is read: front's own (near.xy),
// smrtHiddenBaseline / 2 (near.zw) and smrtHiddenBaseline (far.xy) texels beyond it, away from
// the stretch's first point, and smrtHiddenBaseline texels to its side (far.zw).
struct SmrtHiddenTexels {
    ivec4 near;
    ivec4 far;
};

SHARED SmrtHiddenTexels smrtHiddenTexels(IN(SmrtPoint) first, IN(SmrtPoint) front, uint mapSize) {
    float size = float(mapSize);
    vec2 along = (front.uv - first.uv) * size;
    float texels = length(along);
    vec2 step = texels > 1e-6f ? along / texels : vec2(1.0f, 0.0f);
    vec2 side = vec2(-step.y, step.x);
    vec2 at = front.uv * size;
    ivec2 top = ivec2(int(mapSize) - 1, int(mapSize) - 1);
    float b = smrtHiddenBaseline();
    ivec2 own = clamp(ivec2(floor(at)), ivec2(0, 0), top);
    ivec2 mid = clamp(ivec2(floor(at + 0.5f * b * step)), ivec2(0, 0), top);
    ivec2 far = clamp(ivec2(floor(at + b * step)), ivec2(0, 0), top);
    ivec2 beside = clamp(ivec2(floor(at + b * side)), ivec2(0, 0), top);
    SmrtHiddenTexels t;
    t.near = ivec4(own.x, own.y, mid.x, mid.y);
    t.far = ivec4(far.x, far.y, beside.x, beside.y);
    return t;
}

// Whether the ray crossed a hidden surface before `front` (smrtMayCrossHidden): `depths` as the
// map stores them at smrtHiddenTexels' texels (x own, y mid, z far, w beside). The plane through
// the own, far and side texels' centres, where the midway texel lies on it (an edge or a curve is
// not continued), is continued to the first point; within two texels' change and the float's
// steps. `margin` as smrtCrosses'.
SHARED bool smrtCrossedHidden(IN(ShadowViewData) view, IN(SmrtPoint) first, IN(SmrtPoint) front,
                              IN(SmrtHiddenTexels) t, vec4 depths, uint mapSize,
                              OUT(float) margin) {
    float size = float(mapSize);
    vec2 own = vec2(t.near.x, t.near.y) + 0.5f, mid = vec2(t.near.z, t.near.w) + 0.5f;
    vec2 a = vec2(t.far.x, t.far.y) + 0.5f - own, b = vec2(t.far.z, t.far.w) + 0.5f - own;
    float det = a.x * b.y - a.y * b.x;
    // The depth's gradient per texel: g . a = far - own, g . b = beside - own.
    float da = depths.z - depths.x, db = depths.w - depths.x;
    vec2 g = abs(det) > 1.0f ? vec2(da * b.y - db * a.y, db * a.x - da * b.x) / det
                             : vec2(0.0f, 0.0f);
    float step = length(g);
    bool plane = abs(det) > 1.0f && abs(depths.y - depths.x - dot(g, mid - own)) <= step + 4e-7f;
    vec2 to = first.uv * size - own;
    float there = depths.x + dot(g, to);
    float point = smrtDepthOf(view, first.z - first.slack - front.slack);
    float tolerance = 2.0f * step + 4e-7f * (1.0f + length(to) / smrtHiddenBaseline());
    margin = abs(point - there - tolerance);
    return plane && point - there > tolerance;
}

// The rings of the proof: ring 0 is the 3x3 texels round p's; ring k >= 1 a 2x2 block of tiles of
// the map's bounds (the nearest light view depth over 2^(level+1) texels a side at `level`), the
// block holding every texel within 2^k of p. `rings`: how many it takes to cover a march of
// maxRadius texels (and a texel more, for rounding).
SHARED uint smrtBoundsRings(float maxRadius) {
    uint rings = 1u;
    while (float(1u << rings) < maxRadius + 1.0f) ++rings;
    return rings;
}

// Ring k's block at `level` (levelSize tiles a side): its first tile (xy) and last (zw). `at` is
// p's position in texels of the map. The block starts a tile before p's when p lies in its
// tile's first half, so that 2^level texels either side of p stay in it.
SHARED ivec4 smrtBoundsBlock(vec2 at, uint level, int levelSize) {
    float tile = float(2u << level);
    ivec2 first = ivec2(floor(at / tile - 0.5f));
    ivec2 last = first + ivec2(1, 1);
    ivec2 top = ivec2(levelSize - 1, levelSize - 1);
    return ivec4(clamp(first, ivec2(0, 0), top), clamp(last, ivec2(0, 0), top));
}

// The inner ring's block at ring k's children's level, whose children ring k passes over: ring k-1
// checks every texel of its own block at least as strictly as ring k would (at the ceiling of a
// distance no larger than the texel's; nearer texels belong to rings further in). Without this
// the outermost ring's tile round p, 512 texels wide under a 2048 map, held casters up to twice
// the rays' reach against the ceiling at its inner radius, and failed the proof of most lit
// pixels under a close bulb. None (an empty box) for ring 1, whose inner ring is p's 3x3 texels,
// and where the levels run out (ring k's level clamped: its children lie a level below ring
// k-1's block).
SHARED ivec4 smrtInnerBlock(vec2 at, uint k, int level, int boundsSize) {
    if (k < 2u || level != int(k)) return ivec4(1, 1, 0, 0);
    int child = level - 1;
    return smrtBoundsBlock(at, uint(child), max(boundsSize >> child, 1));
}

// Whether `tile` lies in `block` (first tile xy, last zw).
SHARED bool smrtInBlock(ivec2 tile, ivec4 block) {
    return tile.x >= block.x && tile.y >= block.y && tile.x <= block.z && tile.y <= block.w;
}

// A ring whose block fails as a whole is looked at once more, through its tiles' children (at
// level - 1), each against the ceiling at its own distance from p: the block reaches three times
// as far as the ring's inner radius, and a receiver's own tilted surface at its far side fails
// the ring's one ceiling where it would pass its own.
// The last child of `tile` of a level of levelSize tiles: two each, three for the last tile of an
// odd-sized child level.
SHARED int smrtLastChild(int tile, int levelSize, int childSize) {
    return tile == levelSize - 1 ? childSize - 1 : 2 * tile + 1;
}

// One past the last texel, along an axis, that `tile` of `level` covers (levelSize tiles a side;
// the last tile reaches the map's edge).
SHARED int smrtTileEnd(int tile, int level, int levelSize, uint mapSize) {
    return tile == levelSize - 1 ? int(mapSize) : (tile + 1) * (2 << level);
}

// The distance (texels) from `at` to the texels `tile` of `level` covers.
SHARED float smrtTileDistance(vec2 at, ivec2 tile, int level, int levelSize, uint mapSize) {
    vec2 low = vec2(tile * (2 << level));
    vec2 high = vec2(float(smrtTileEnd(tile.x, level, levelSize, mapSize)),
                     float(smrtTileEnd(tile.y, level, levelSize, mapSize)));
    vec2 gap = max(max(low - at, at - high), vec2(0.0f, 0.0f));
    return length(gap);
}

// smrt.gapSamples. Two samples in front of the map's surface say nothing of the stretch between
// them: a ray towards a wide light's far rim passes under a sphere's silhouette in a few texels
// and the march's long far steps (smrtSampleDistance) step over it, so the outer penumbra reads
// too bright. A step of more than smrtLongStep texels is checked against the bounds (the nearest
// depth over tiles, smrt.skipLit's): where a tile it crosses holds a depth nearer the light than
// its farther end, the step is sampled again at smrt.gapSamples evenly spaced points. Near the
// receiver, where the steps are short, nothing changes.
SHARED float smrtLongStep() { return 4.0f; }

// The step's length in texels of the map.
SHARED float smrtStepTexels(IN(SmrtPoint) a, IN(SmrtPoint) b, uint mapSize) {
    return length((b.uv - a.uv) * float(mapSize));
}

// Inside point j (1 .. n) of n evenly spaced between the points a and b along the ray.
SHARED float smrtGapDistance(float a, float b, uint j, uint n) {
    return a + (b - a) * float(j) / float(n + 1u);
}

// The texels the step reads (the march's reads are clamped to the map): the first (xy) and last
// (zw) of their box.
SHARED ivec4 smrtStepTexelBox(IN(SmrtPoint) a, IN(SmrtPoint) b, uint mapSize) {
    ivec2 top = ivec2(int(mapSize) - 1, int(mapSize) - 1);
    vec2 low = min(a.uv, b.uv) * float(mapSize), high = max(a.uv, b.uv) * float(mapSize);
    ivec2 first = clamp(ivec2(floor(low)), ivec2(0, 0), top);
    ivec2 last = clamp(ivec2(floor(high)), ivec2(0, 0), top);
    return ivec4(first.x, first.y, last.x, last.y);
}

// The bounds' level whose tiles (2^(level+1) texels a side) are as wide as the box, so that at most
// 2x2 of them hold it (the top level's one tile, the whole map, where none below is).
SHARED int smrtStepLevel(ivec4 box, int levels) {
    int widest = max(box.z - box.x, box.w - box.y) + 1; // (2 << level) >= widest
    return clamp(findMSB(max(widest - 1, 1)), 0, levels - 1);
}

// The box's tiles at `level` (levelSize tiles a side; the last takes the odd-sized leftovers).
SHARED ivec4 smrtStepTiles(ivec4 box, int level, int levelSize) {
    int side = 2 << level, last = levelSize - 1;
    return ivec4(min(box.x / side, last), min(box.y / side, last), min(box.z / side, last),
                 min(box.w / side, last));
}

// The stored depth a tile must hold at least for no point of the step from a to b to fall behind
// it. A point lies behind only past its slack: below its distance less its slack. Both are linear
// along the step (the slack is a texel's world size, linear in z), so the larger of the ends' is
// every point's bound. The rounding of viewDistance and smrtDepthOf is allowed for (1e-5 z and
// four steps of the depth's float, as smrtCeilingOf).
SHARED float smrtStepCeiling(IN(ShadowViewData) view, IN(SmrtPoint) a, IN(SmrtPoint) b) {
    float z = max(a.z - a.slack, b.z - b.slack);
    float n = view.frustum.x, f = view.frustum.y;
    float depthStep = view.texel.y > 0.5f ? z * z / max(n, 1e-6f) : abs(f - n);
    return smrtDepthOf(view, z + 1e-5f * abs(z) + 4e-7f * depthStep);
}

PENUMBRA_GPU_END

PENUMBRA_TECHNIQUE_BLOCK(SmrtBlock, SmrtParams, smrt)

#endif
// clang-format on
