// The maths of the `sdf` technique, written once and compiled twice like kernels.h: as GLSL by
// the field's build passes (shaders/sdf_*.comp) and its tracer (shadow_sdf.glsl), as C++ by the
// CPU mirror (src/reference/distance_field.cpp). The CPU references of the field itself
// (closestPointOnTriangle, windingContribution) are written separately in double precision, so a
// bug here shows against them.
// clang-format off
#ifndef PENUMBRA_SDF_MATH_H
#define PENUMBRA_SDF_MATH_H
#include "bias.h"
#include "pass_types.h"

PENUMBRA_GPU_BEGIN

// The point of triangle (a, b, c) nearest to p, by p's Voronoi region among its vertices, edges
// and face [Ericson 2004, Real-Time Collision Detection 5.1.5].
SHARED vec3 nearestOnTriangle(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 ab = b - a, ac = c - a, ap = p - a;
    float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    vec3 bp = p - b;
    float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
    vec3 cp = p - c;
    float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    float sum = va + vb + vc;
    return a + ab * (vb / sum) + ac * (vc / sum);
}

// The distance from p to segment (a, b).
SHARED float segmentDistance(vec3 p, vec3 a, vec3 b) {
    vec3 ab = b - a;
    float t = clamp(dot(p - a, ab) / max(dot(ab, ab), 1e-30f), 0.0f, 1.0f);
    return length(p - (a + t * ab));
}

// The signed distance from p to the slab that gives open geometry its thickness: the triangle
// swept `thickness` along its normal both ways. Its outline stays where the triangle's is (a
// rounded offset would grow every card and close every hole by the thickness). In the
// triangle's plane, e is the distance to the triangle outside it; inside, minus the distance to
// its outline edges (FIELD_OUTLINE_*: those facing a hole), unbounded when it has none (the
// surface goes on in its neighbours: an inner edge must not thin the slab). Across it,
// h - thickness; the two combine as a box's distance.
SHARED float slabDistance(vec3 p, vec3 a, vec3 b, vec3 c, uint flags, float thickness) {
    vec3 n = cross(b - a, c - a);
    n = n / max(length(n), 1e-30f);
    float across = dot(p - a, n);
    vec3 q = p - across * n;
    bool inside = dot(cross(b - a, q - a), n) >= 0.0f && dot(cross(c - b, q - b), n) >= 0.0f &&
                  dot(cross(a - c, q - c), n) >= 0.0f;
    float e;
    if (inside) {
        float edge = 3.4e38f;
        if ((flags & FIELD_OUTLINE_AB) != 0u) edge = min(edge, segmentDistance(q, a, b));
        if ((flags & FIELD_OUTLINE_BC) != 0u) edge = min(edge, segmentDistance(q, b, c));
        if ((flags & FIELD_OUTLINE_CA) != 0u) edge = min(edge, segmentDistance(q, c, a));
        e = -edge;
    } else {
        e = length(q - nearestOnTriangle(q, a, b, c));
    }
    vec2 w = vec2(e, abs(across) - thickness);
    return length(max(w, vec2(0.0f))) + min(max(w.x, w.y), 0.0f);
}

// The distance from p to a field triangle: exact for closed geometry, to its slab of
// half-thickness `thickness` for open geometry (flags FIELD_OPEN). The quantity the field's build
// minimises over triangles.
SHARED float fieldTriangleDistance(vec3 p, vec3 a, vec3 b, vec3 c, uint flags, float thickness) {
    if ((flags & FIELD_OPEN) != 0u) return slabDistance(p, a, b, c, flags, thickness);
    return length(p - nearestOnTriangle(p, a, b, c));
}

// The edge function of edge (a, b) at p in the xy plane, computed from the endpoints in a fixed
// order (the lexicographically smaller first) so that the two triangles sharing an edge get
// exactly opposite values: a column through the edge meets exactly one of them.
SHARED float columnEdge(vec2 a, vec2 b, vec2 p) {
    bool swapped = b.x < a.x || (b.x == a.x && b.y < a.y);
    vec2 s = swapped ? b : a, e = swapped ? a : b;
    float v = (e.x - s.x) * (p.y - s.y) - (e.y - s.y) * (p.x - s.x);
    return swapped ? -v : v;
}

// Whether an edge function value puts p inside for a counter-clockwise triangle: positive, or
// zero on an edge that owns its points (its direction (dx, dy) points down, or left when level).
SHARED bool ownsEdgePoint(float e, vec2 direction) {
    return e > 0.0f || (e == 0.0f && (direction.y < 0.0f || (direction.y == 0.0f && direction.x > 0.0f)));
}

// Where the column (p.x, p.y, z), z from below, crosses triangle (a, b, c): its z in `z`, and +1
// when it enters the solid there (the triangle faces down: normal z < 0), -1 when it leaves, 0
// when it misses or the triangle is edge-on.
SHARED int columnCrossing(vec2 p, vec3 a, vec3 b, vec3 c, OUT(float) z) {
    z = 0.0f;
    float area = columnEdge(vec2(a), vec2(b), vec2(c));
    if (area == 0.0f) return 0;
    // Counter-clockwise in xy: (a, q, r), inside where every edge function is positive.
    vec3 q = area > 0.0f ? b : c, r = area > 0.0f ? c : b;
    float e0 = columnEdge(vec2(a), vec2(q), p);
    float e1 = columnEdge(vec2(q), vec2(r), p);
    float e2 = columnEdge(vec2(r), vec2(a), p);
    if (!ownsEdgePoint(e0, vec2(q) - vec2(a)) || !ownsEdgePoint(e1, vec2(r) - vec2(q)) ||
        !ownsEdgePoint(e2, vec2(a) - vec2(r)))
        return 0;
    float total = e0 + e1 + e2;
    z = (e1 * a.z + e2 * q.z + e0 * r.z) / total;
    return area > 0.0f ? -1 : 1;
}

// The closest approach to the scene of the ray between two sphere-tracing samples [Aaltonen
// 2018]: the sample `step` back had free distance hPrevious, this one h; the spheres of those
// radii meet on a circle at distance y back from this sample and radius d from the ray. Returns
// (d, distance along the ray to that point); (h, t) when there is no such circle (the first step,
// a sample inside, or spheres that do not meet).
SHARED vec2 closestApproach(float h, float hPrevious, float step, float t) {
    if (hPrevious <= 0.0f || h <= 0.0f || step <= 0.0f) return vec2(h, t);
    float y = (h * h - hPrevious * hPrevious + step * step) / (2.0f * step);
    if (y <= 0.0f || y >= h || y >= step) return vec2(h, t);
    return vec2(sqrt(h * h - y * y), t - y);
}

// Where the light's edge sits, in light radii from the cone's axis, for a miss at distance d
// from a ray travelled t: the angle asin(d / t) over the light's angular radius asin(sinRadius),
// or k d / t with a given sharpness k [Quilez 2010]. A point-like light: +-1 (open or blocked).
SHARED float coneEdge(float d, float t, float sinRadius, float k) {
    if (k > 0.0f) return k * d / max(t, 1e-6f);
    if (sinRadius <= 0.0f) return d > 0.0f ? 1.0f : -1.0f;
    return asin(clamp(d / max(t, 1e-6f), -1.0f, 1.0f)) / asin(min(sinRadius, 1.0f));
}

// Where a receiver's ray towards the light starts: along the ray itself until `height` above the
// receiver's tangent plane (so the ray is the receiver's own, not one beside it: an offset along
// the normal would move the shadow by height x sin of the light's angle to it), at most
// 4 x height along it at grazing angles, the rest along the face normal turned to the light's
// side. `along`: the distance along the ray from the receiver to the start.
SHARED vec3 traceStart(vec3 world, vec3 face, vec3 toLight, float height, OUT(float) along) {
    float nDotL = dot(face, toLight);
    vec3 normal = nDotL < 0.0f ? -face : face;
    nDotL = abs(nDotL);
    along = min(height / max(nDotL, 1e-4f), 4.0f * height);
    return world + toLight * along + normal * max(height - along * nDotL, 0.0f);
}

// One sphere-tracing step towards the light: the sample at `t` along the ray (from its start,
// `apex` further from the receiver) has free distance h. Narrows the light's open edge (in light
// radii, see coneEdge) by this step's closest approach, then advances t by h (at least minStep,
// which also carries the ray through solids, where h is negative). False once the light is
// hidden whole.
struct ConeTrace {
    float edge;     // the narrowest so far (the horizon's to begin with)
    float t;        // along the ray, from its start
    float previous; // the last sample's free distance (-1: none yet)
    float step;     // the last step's length
};

// Whether a sample's free distance h is the receiver's own surface: no nearer than the receiver's
// tangent plane, `plane` below the sample, less `shell` (open geometry's sdf.thickness, the
// field's shell round an open receiver), within `slack`. That
// surface's shadow is the horizon's, which the trace starts from (bias.horizon); counted again as
// a miss it darkened every light wider than asin(1 - shell / height) seen from the start (under
// a bulb of radius 0.5 over an open plane: 0.85 on fully lit ground).
SHARED bool ownSurface(float h, float plane, float shell, float slack) {
    return h >= plane - shell - slack;
}

// The light's cone's radius at distance t from the receiver: where coneEdge is 1.
SHARED float coneRadius(float t, float sinRadius, float k) {
    if (k > 0.0f) return t / k;
    return t * sinRadius / sqrt(max(1.0f - sinRadius * sinRadius, 1e-12f));
}

// Inside a solid the samples along the ray tell how deep it runs, not how far the solid reaches
// across the light's cone: a plate a few voxels thick hides a sun however wide the plate is, and
// its depth alone (coneEdge of h < 0) left the umbra half lit. So inside, the ray is moved across
// by the cone's radius r (four ways: +-u, +-v) and slid along itself back to the plane of the
// surface it runs in (normal n, the field's gradient): the probe lies at the sample's depth in the
// same solid, or past where the solid ends. Probe k of 4; the slide kept within 4 r (a ray
// running along its surface).
SHARED vec3 acrossProbe(vec3 p, vec3 toLight, vec3 n, float r, int k) {
    vec3 u = normalize(cross(toLight, abs(toLight.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f)
                                                           : vec3(0.0f, 1.0f, 0.0f)));
    vec3 v = cross(toLight, u);
    vec3 side = r * (k == 0 ? u : k == 1 ? -u : k == 2 ? v : -v);
    float along = dot(toLight, n);
    float slide = abs(along) > 0.25f ? dot(side, n) / along : 0.0f;
    return p + side - clamp(slide, -4.0f * r, 4.0f * r) * toLight;
}

// The edge (light radii, as coneEdge) the probes across give a sample inside (h < 0): the solid
// ends where the field crosses zero between the sample and a probe with a positive value
// (linearly), the nearest such way out sets it; -1 when every probe is inside.
SHARED float acrossEdge(float h, vec4 probes) {
    float wayOut = 1.0f;
    for (int k = 0; k < 4; ++k)
        if (probes[k] > 0.0f) wayOut = min(wayOut, h / (h - probes[k]));
    return -wayOut;
}

// `across`: acrossEdge for a sample inside (1 elsewhere).
SHARED bool coneTraceStep(INOUT(ConeTrace) c, float h, float apex, float sinRadius, float k,
                          float minStep, bool own, float across) {
    vec2 miss = closestApproach(h, c.previous, c.step, c.t);
    if (!own) c.edge = min(c.edge, min(coneEdge(miss.x, miss.y + apex, sinRadius, k), across));
    c.previous = own ? -1.0f : h; // no closest approach between the own surface and another
    c.step = max(abs(h), minStep);
    c.t += c.step;
    return c.edge > -1.0f;
}

PENUMBRA_GPU_END
#endif
// clang-format on
