// Technique `sdf` (src/shadows/sdf.cpp): the light's visible fraction at a receiver by sphere
// tracing the scene's distance field towards it. Each step's free distance h bounds how close the
// ray passes to the scene; with the previous step's it gives the closest approach d of the ray
// between them (closestApproach), at a distance t along it. Seen from the receiver, that miss
// puts the light's edge at coneEdge(d, t): asin(d / t) over the light's angular radius, in light
// radii from the cone's axis, negative once the ray runs inside a solid. The narrowest over the
// ray, with the receiver's own horizon (bias.horizon), is the straight edge that cuts the light's
// disc: discFraction of it is open. Inside a solid the ray keeps going (a step of at least
// a quarter voxel) until the edge passes the far side of the disc.
#ifndef PENUMBRA_SHADOW_SDF_GLSL
#define PENUMBRA_SHADOW_SDF_GLSL
#include "bias.h"
#include "params_sdf.h"
#include "shadow_common.glsl"
#include "sdf_math.h"
#include "technique_input.glsl"

// The field at world position p (trilinear; the box's voxel centres hold the samples).
float fieldAt(sampler3D field, vec3 p) {
    vec3 uvw = (p - frame.fieldOrigin.xyz) / (frame.fieldOrigin.w * vec3(frame.fieldSize.xyz));
    return texture(field, uvw).r;
}

bool insideFieldBox(vec3 p) {
    vec3 extent = frame.fieldOrigin.w * vec3(frame.fieldSize.xyz);
    return all(greaterThanEqual(p, frame.fieldOrigin.xyz)) &&
           all(lessThanEqual(p, frame.fieldOrigin.xyz + extent));
}

// acrossEdge at p, inside a solid: the field's gradient (central differences, half a voxel) gives
// the surface's plane; a probe outside the field's box is outside every solid.
float acrossField(sampler3D field, vec3 p, vec3 toLight, float h, float r) {
    float e = 0.5 * frame.fieldOrigin.w;
    vec3 g = vec3(fieldAt(field, p + vec3(e, 0, 0)) - fieldAt(field, p - vec3(e, 0, 0)),
                  fieldAt(field, p + vec3(0, e, 0)) - fieldAt(field, p - vec3(0, e, 0)),
                  fieldAt(field, p + vec3(0, 0, e)) - fieldAt(field, p - vec3(0, 0, e)));
    vec3 n = dot(g, g) > 0.0 ? normalize(g) : toLight;
    vec4 probes;
    for (int k = 0; k < 4; ++k) {
        vec3 q = acrossProbe(p, toLight, n, r, k);
        probes[k] = insideFieldBox(q) ? fieldAt(field, q) : r;
    }
    return acrossEdge(h, probes);
}

// `face`: the receiver's triangle normal (towards the viewer); `sinRadius`: the sine of the
// light's angular radius at the receiver; `horizon`: whether its tangent plane clips the light.
float shadowSdf(sampler3D field, LightData light, vec3 world, vec3 face, float sinRadius,
                bool horizon) {
    if (frame.fieldSize.x == 0u) return 1.0;
    float voxel = frame.fieldOrigin.w;
    vec3 toLight;
    float reach; // how far the ray may go: to the light's surface, or out of the field's box
    if (LIGHT_TYPE_OF(light) == LIGHT_DIRECTIONAL) {
        toLight = -light.directionRange.xyz;
        reach = 3.4e38;
    } else {
        vec3 offset = light.positionType.xyz - world;
        float distance = length(offset);
        toLight = offset / max(distance, 1e-20);
        reach = distance * (1.0 - sinRadius);
    }
    float k = sdf.k;
    ConeTrace c;
    c.edge = horizon && (sinRadius > 0.0 || k > 0.0)
                 ? coneEdge(dot(face, toLight), 1.0, sinRadius, k)
                 : 1.0;
    if (c.edge <= -1.0) return 0.0;
    c.t = 0.0;
    c.previous = -1.0;
    c.step = 0.0;
    float apex;
    vec3 origin = traceStart(world, face, toLight, sdf.startOffset * voxel, apex);
    float minStep = sdf.minStep * voxel;
    uint steps = uint(sdf.steps);
    vec3 up = dot(face, toLight) < 0.0 ? -face : face; // the tangent plane's light side
    for (uint i = 0u; i < steps && c.t < reach - apex; ++i) {
        vec3 p = origin + c.t * toLight;
        if (!insideFieldBox(p)) break;
        float h = fieldAt(field, p);
        bool own = horizon && ownSurface(h, dot(p - world, up), sdf.thickness * voxel, 0.05 * voxel);
        float across = 1.0;
        if (h < 0.0 && !own && (sinRadius > 0.0 || k > 0.0))
            across = acrossField(field, p, toLight, h, coneRadius(c.t + apex, sinRadius, k));
        if (!coneTraceStep(c, h, apex, sinRadius, k, minStep, own, across)) return 0.0;
    }
    return discFraction(c.edge);
}

// No shadow map: the field holds the whole scene, and the tracer clips the light at the
// receiver's own horizon itself (at.horizon).
vec4 evaluateSdf(TechniqueInput at) {
    float v = shadowSdf(distanceField, at.light, at.world, at.face, at.sinRadius, at.horizon);
    return vec4(v, 0.0, 0.0, 0.0);
}

#endif
