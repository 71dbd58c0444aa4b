// Depth bias, compiled as GLSL and as C++ like kernels.h: the depth test of one texel, the
// receiver-plane bias [Tuft 2010] and its gradients, bias.mode=adaptive's terms [Dou et al.
// 2014], and the receiver's own horizon and back face (what no shadow map holds).
// clang-format off
#ifndef PENUMBRA_BIAS_H
#define PENUMBRA_BIAS_H
#include "shared_prelude.h"

// bias.receiver, bias.mode and bias.horizon: indices of their choices in the registry.
#define RECEIVER_OFF 0u
#define RECEIVER_SCREEN 1u
#define RECEIVER_LIGHT 2u
#define BIAS_FIXED 0u
#define BIAS_ADAPTIVE 1u
#define HORIZON_OFF 0u
#define HORIZON_SOFT 1u
#define HORIZON_ALL 2u

PENUMBRA_GPU_BEGIN

// The comparison of one texel [Williams 1978]: lit (1) when the receiver's depth, corrected by
// receiver-plane bias to the texel's centre (`offset` = texel centre - receiver, in uv), lies at or
// in front of the stored depth. The correction is clamped to `dzRange`.
SHARED float receiverDepthAt(float depth, vec2 gradient, vec2 offset, vec2 dzRange) {
    return depth + clamp(dot(gradient, offset), dzRange.x, dzRange.y);
}

SHARED float depthTest(float receiver, float stored) { return receiver <= stored ? 1.0f : 0.0f; }

// A tap's reference depth under bias.mode=adaptive [Dou et al. 2014]: the receiver-plane depth
// at the texel's centre (the paper's adaptive offset, for every tap of a kernel), its correction
// clamped to dzRange, lifted towards the light by what the surface's curvature can bring within
// the tap's distance |offset| (uv): min(curve.x |offset|^2, curve.y |offset|), light depth (see
// adaptiveBiasTerms). curve = 0 leaves receiverDepthAt's value.
SHARED float tapDepth(float depth, vec2 gradient, vec2 offset, vec2 dzRange, vec2 curve) {
    float s2 = dot(offset, offset);
    return receiverDepthAt(depth, gradient, offset, dzRange) -
           min(curve.x * s2, curve.y * sqrt(s2));
}

// bias.mode=adaptive's crease rule, for the four texels of one gather: taken as one plane (the
// gradient of their depths, d depth / d uv, `texel` uv apart) and continued to the receiver,
// `offset` uv from the gather's centre. A plane the light sees that passes at or behind the
// receiver there leaves the receiver on the light's side of it, and nothing on that plane can
// hide the light from it: a wall rising from the floor the receiver lies on, the face of a box
// standing on it, a convex caster's tangent plane. Those texels test lit. A gather steeper than
// `slopeLimit` (d depth / d uv; 0: the rule is off) is taken to straddle a caster's edge, not
// one surface, and keeps its tests.
// The plane of a gather's four depths (textureGather's order), `texel` uv apart: d depth / d uv.
SHARED vec2 gatherGradient(vec4 depths, float texel) {
    return vec2((depths.y - depths.x) + (depths.z - depths.w),
                (depths.x - depths.w) + (depths.y - depths.z)) * (0.5f / texel);
}

SHARED vec4 creaseTests(vec4 tests, vec4 depths, vec2 offset, float texel, float receiverDepth,
                        float slopeLimit, float margin) {
    vec2 g = gatherGradient(depths, texel);
    // Only a gather wholly in front of the receiver: one that holds a lit texel straddles a crease
    // or an edge, and its plane mixes two surfaces (the floor the receiver lies on continued in
    // front of a wall it stands behind).
    if (slopeLimit <= 0.0f || length(g) > slopeLimit) return tests;
    float centre = 0.25f * (depths.x + depths.y + depths.z + depths.w);
    return centre + dot(g, offset) >= receiverDepth + margin ? vec4(1.0f) : tests;
}

// How far behind the receiver a plane must pass for the crease rule, in texels of a 45-degree
// surface: the receiver's own bias (its lift and normal offset) moves it towards the light, and
// a plane meeting its surface at a shallow angle (a ramp's foot on the floor) would otherwise
// pass behind the moved receiver while the receiver itself lies beyond it.
#define CREASE_MARGIN_TEXELS 2.0f

// The crease rule's slope limit for a light of angular radius a (sin a = sinRadius; 0: a point):
// a plane at angle b to the ray through the receiver, passing behind it, leaves the whole light
// on the receiver's side when the light's centre lies at least its radius from the plane, sin b
// >= sin a, so its slope cot b may reach cot a; and `maxSlope` (bias.crease) at most: a step
// from a caster's edge to the floor behind it is steeper wherever the gap exceeds that many
// texels' width. `perUv`: a 45-degree surface's d depth / d uv at the receiver. The result is in
// d depth / d uv, 0 where the rule is off.
SHARED float creaseLimit(float perUv, float sinRadius, float maxSlope) {
    float s = clamp(sinRadius, 0.0f, 1.0f);
    float slope = s > 0.0f ? min(maxSlope, sqrt(1.0f - s * s) / s) : maxSlope;
    return perUv * max(slope, 0.0f);
}

// A comparison tap of the texture unit (pcf.filter=hardware) tests its four texels against one
// depth: under bias.mode=adaptive the receiver comes nearer the light by its plane's largest rise
// over the tap's footprint (texel centres within a texel of it on each axis, `size` texels per
// uv), at most `limit` (bias.receiverClamp): the receiver's own slope-scaled bias.
SHARED float footprintLift(vec2 gradient, float size, float limit) {
    return min((abs(gradient.x) + abs(gradient.y)) / size, limit);
}

// The per-receiver terms of bias.mode=adaptive, from the receiver's geometry: texelWorld, a
// shadow-map texel's world size at the receiver (across the light's rays); mapSize, texels per
// uv; depthPerWorld, the light depth's change per world unit along the ray; cosine, N.L of the
// receiver's own triangle; curvature, how fast the surface's normal turns (radians per world
// unit; 0: flat); epsilonTexels (bias.adaptive) and curvatureScale (bias.curvature); gradient,
// the receiver plane's |d depth / d uv|. Returns x: the constant lift (light depth), the
// paper's adaptive epsilon, here a fraction of a texel's footprint along the ray (texelWorld /
// cosine) so that it scales with the map's resolution and the surface's slope; yz: curve for
// tapDepth: a surface of curvature k leaves its tangent plane by k L^2 / 2 over a distance L
// along it, L = s / cosine for a distance s across the rays, which the ray sees stretched by
// 1 / cosine again (y, per uv^2), never more than the tap's own distance across the rays (z, per
// uv: a 45-degree bound); w: the plane's reach, how far its correction is trusted (|gradient|
// times the distance across the rays where the surface has turned by one radian,
// cosine / curvature), the clamp that adapts to curvature (1e30: flat). curvatureScale scales
// the curvature in both.
SHARED vec4 adaptiveBiasTerms(float texelWorld, float mapSize, float depthPerWorld, float cosine,
                              float curvature, float epsilonTexels, float curvatureScale,
                              float gradient) {
    float c = clamp(cosine, 0.05f, 1.0f);
    float worldPerUv = texelWorld * mapSize;
    float lift = depthPerWorld * epsilonTexels * texelWorld / c;
    float k = curvature * curvatureScale;
    float curve = 0.5f * depthPerWorld * k * worldPerUv * worldPerUv / (c * c * c);
    float cap = depthPerWorld * worldPerUv;
    float reach = k > 0.0f ? gradient * c / (k * worldPerUv) : 1e30f;
    return vec4(lift, curve, cap, reach);
}

// The part of a unit disc on one side of a straight edge at signed distance x from its centre
// (positive: the centre is uncovered): 1/2 + (x sqrt(1 - x^2) + asin x) / pi, clamped to [-1, 1].
// The ends are exact: Vulkan lets asin(-1) miss -pi/2 (a GPU gave 6e-9 for a disc wholly under
// the edge), and a receiver facing away from a sun must read 0, not nearly 0.
SHARED float discFraction(float x) {
    if (x <= -1.0f) return 0.0f;
    if (x >= 1.0f) return 1.0f;
    return clamp(0.5f + (x * sqrt(1.0f - x * x) + asin(x)) / 3.14159265f, 0.0f, 1.0f);
}

// bias.horizon: the part of a light of angular radius a (sin a = sinRadius) above a receiver's
// tangent plane, its centre at elevation h over it (sin h = N.L): the segment of a disc of radius
// a cut at distance h from its centre (a small light's disc, seen flat). The surface hides the
// rest itself, which no shadow map holds. 1 for a point-like light.
SHARED float horizonVisibility(float nDotL, float sinRadius) {
    if (sinRadius <= 0.0f) return 1.0f;
    return discFraction(asin(clamp(nDotL, -1.0f, 1.0f)) / asin(min(sinRadius, 1.0f)));
}

// A receiver that faces away from the light (N.L <= 0, N its triangle's own normal) hides the
// light itself: 0 for a point-like light, else the part of the light's disc still above its
// tangent plane. One convention for render and reference (the truth counts every ray under the
// surface as blocked), whatever a shadow map says there; 1 where the receiver faces the light.
SHARED float backFacingVisibility(float nDotL, float sinRadius) {
    if (nDotL > 0.0f) return 1.0f;
    return sinRadius <= 0.0f ? 0.0f : horizonVisibility(nDotL, sinRadius);
}

// Receiver-plane depth bias [Tuft 2010; seed 000]: the receiver's light depth as a linear function
// of shadow-map (u, v) on its tangent plane. `light`: from the surface normal. The three rows of
// d(u, v, depth)/d(world) at `world` for the projective map S; the plane's normal in (u, v, depth)
// space is J^-T N, and J^-T is the cofactor matrix of J over det J (see techniques.md).
SHARED vec2 receiverGradientFromNormal(IN(mat4) S, vec3 world, vec3 normal) {
    vec4 s = S * vec4(world, 1.0f);
    vec3 rowW = vec3(S[0][3], S[1][3], S[2][3]);
    vec3 du = (vec3(S[0][0], S[1][0], S[2][0]) - (s.x / s.w) * rowW) / s.w;
    vec3 dv = (vec3(S[0][1], S[1][1], S[2][1]) - (s.y / s.w) * rowW) / s.w;
    vec3 dz = (vec3(S[0][2], S[1][2], S[2][2]) - (s.z / s.w) * rowW) / s.w;
    float nu = dot(cross(dv, dz), normal);
    float nv = dot(cross(dz, du), normal);
    float nz = dot(cross(du, dv), normal);
    if (abs(nz) <= 1e-6f * (abs(nu) + abs(nv))) return vec2(0.0f); // edge-on to the light
    return vec2(-nu, -nv) / nz;
}

// The world-space gradient of the light depth of the projective map S at `world`.
SHARED vec3 lightDepthGradient(IN(mat4) S, vec3 world) {
    vec4 s = S * vec4(world, 1.0f);
    vec3 rowW = vec3(S[0][3], S[1][3], S[2][3]);
    return (vec3(S[0][2], S[1][2], S[2][2]) - (s.z / s.w) * rowW) / s.w;
}

// `screen`: from the light-space offsets to two neighbouring pixels (seed 000's 2x2 solve):
// [dz/du, dz/dv] = [dz/dx, dz/dy] [[du/dx, dv/dx], [du/dy, dv/dy]]^-1.
SHARED vec2 receiverGradientFromOffsets(vec3 alongX, vec3 alongY) {
    float det = alongX.x * alongY.y - alongX.y * alongY.x;
    if (abs(det) < 1e-20f) return vec2(0.0f);
    return vec2(alongX.z * alongY.y - alongY.z * alongX.y,
                alongX.x * alongY.z - alongY.x * alongX.z) / det;
}

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
inline constexpr const char* kReceiverChoices[] = {"off", "screen", "light"};
inline constexpr const char* kHorizonChoices[] = {"off", "soft", "all"};
inline constexpr const char* kBiasModeChoices[] = {"fixed", "adaptive"};
static_assert(BIAS_FIXED == 0 && BIAS_ADAPTIVE == 1 && std::size(kBiasModeChoices) == 2);
static_assert(RECEIVER_OFF == 0 && RECEIVER_SCREEN == 1 && RECEIVER_LIGHT == 2 &&
              std::size(kReceiverChoices) == 3);
static_assert(HORIZON_OFF == 0 && HORIZON_SOFT == 1 && HORIZON_ALL == 2 &&
              std::size(kHorizonChoices) == 3);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
