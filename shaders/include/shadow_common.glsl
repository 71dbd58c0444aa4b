// Per-pixel shadow lookup set-up shared by every technique: normal offset, projection into the
// shadow map, and the frustum test.
#ifndef PENUMBRA_SHADOW_COMMON_GLSL
#define PENUMBRA_SHADOW_COMMON_GLSL
#include "light_geometry.h"

// The light's LIGHT_* kind. A pass that runs once per light defines LIGHT_TYPE_OF as its
// specialization constant before including this: lavapipe 22.3 runs both sides of every branch,
// so a kind known when the pipeline is built drops the other kinds' code.
#ifndef LIGHT_TYPE_OF
#define LIGHT_TYPE_OF(light) uint((light).positionType.w)
#endif

struct ShadowCoord {
    vec2 uv;       // shadow-map texture coordinates, [0,1]^2 inside the map
    float depth;   // d(p), the receiver's light depth in [0,1]
    bool inside;   // false: outside the light's frustum, which nothing in the map can shadow
};

vec3 directionToLight(LightData light, vec3 world) {
    return LIGHT_TYPE_OF(light) == LIGHT_DIRECTIONAL
               ? -light.directionRange.xyz
               : normalize(light.positionType.xyz - world);
}

// The sine of the light's angular radius seen from `world` (0: a point-like light).
float lightSine(LightData light, ShadowViewData view, vec3 world) {
    float size = view.texel.w;
    if (view.texel.y < 0.5) return size / sqrt(1.0 + size * size); // a sun: tan of half its angle
    return min(size / max(length(light.positionType.xyz - world), 1e-6), 1.0);
}

// Which of the light's shadow views holds `world`, counted from its first: a point light's cube
// face (by the direction from the light), else 0 (a sun's cascade is chosen by view distance).
uint lightViewOf(LightData light, vec3 world) {
    return LIGHT_TYPE_OF(light) == LIGHT_POINT ? cubeFace(world - light.positionType.xyz) : 0u;
}

// Normal offset [Holbert 2010 'Normal offset shadows']: move the receiver along its normal by
// bias.z texels of the view, scaled by 1 - N.L (none where the light is head-on, most at grazing
// angles).
vec3 offsetReceiver(LightData light, ShadowViewData view, vec3 world, vec3 normal) {
    float nDotL = max(dot(normal, directionToLight(light, world)), 0.0);
    float texelWorld = view.texel.x;
    if (view.texel.y > 0.5) // perspective: texels grow with distance along the view's axis (w)
        texelWorld *= max((view.shadowMatrix * vec4(world, 1.0)).w, 0.0);
    return world + normal * (light.bias.z * texelWorld * (1.0 - nDotL));
}

// Whether (uv, depth) lies in a view's map: what its map can shadow.
bool insideMap(vec2 uv, float depth) {
    return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) &&
           depth <= 1.0;
}

ShadowCoord projectToShadowMap(ShadowViewData view, vec3 world) {
    vec4 s = view.shadowMatrix * vec4(world, 1.0);
    ShadowCoord c;
    c.inside = s.w > 0.0;
    c.uv = s.xy / s.w;
    c.depth = s.z / s.w;
    c.inside = c.inside && insideMap(c.uv, c.depth);
    return c;
}

#endif
