// The translucent casters' shadow maps, compiled as GLSL and as C++ like moments.h: what a
// shadow map texel keeps of the translucent surfaces along its ray from the light, and the
// transmittance a receiver at depth z behind the texel reads from it (docs/translucency.md,
// "Techniques"). Depths z are in [0, 1] along the texel's ray, the light's end at 0.
// clang-format off
#ifndef PENUMBRA_TRANSLUCENT_H
#define PENUMBRA_TRANSLUCENT_H
#include "moments.h"

PENUMBRA_GPU_BEGIN

// A surface keeps back at most this much absorbance, -ln(1e-4) = 9.2 per channel: a surface that
// lets nothing through would add an infinite one, which a sum of floats cannot hold.
#define TRANSLUCENT_MIN_TRANSMITTANCE 1e-4f
// A texel whose surfaces keep back less absorbance than this in a channel holds none there: its
// moments are not divided by it.
#define TRANSLUCENT_NO_ABSORBANCE 1e-6f

// A surface's absorbance per channel, -ln T: additive where transmittances multiply.
SHARED vec3 layerAbsorbance(vec3 transmittance) {
    return -log(max(transmittance, vec3(TRANSLUCENT_MIN_TRANSMITTANCE)));
}

// Coloured transmittance map: the product of the texel's translucent surfaces' transmittances
// and the depth of the nearest. A receiver behind the nearest (z past it) keeps the product,
// one in front of it everything. Exact where a receiver lies behind all the texel's surfaces or
// in front of them all; a receiver between two of them keeps too little (the product of all).
SHARED vec3 colouredMapTransmittance(vec3 product, float nearest, float z) {
    return z > nearest ? product : vec3(1.0f);
}

// Moment-based transmittance [Muenstermann et al. 2018, 'Moment-based order-independent
// transparency', with their shadows for translucent casters], per channel: each surface adds
// its absorbance a and a times the powers of x = 2 z - 1 (b1..b4); additive, so the order the
// surfaces arrive in does not matter. What one surface at depth z adds to a channel's moments:
SHARED vec4 layerMoments(float absorbance, float z) {
    float x = 2.0f * z - 1.0f;
    float x2 = x * x;
    return absorbance * vec4(x, x2, x2 * x, x2 * x2);
}

// A channel's transmittance at depth z: the four normalised moments' Hamburger reconstruction
// (moments.h, pulled by `bias`) bounds the fraction F of the absorbance in front of z from below
// (the atoms in front) and above (with the atom at z itself); `overestimation` in [0, 1] goes
// that far from the lower bound to the upper one. The channel keeps exp(-absorbance F): exact,
// up to the bias, for one or two surfaces, and bounded for more.
SHARED float momentTransmittance(float absorbance, vec4 moments, float z, float bias,
                                 float overestimation) {
    if (absorbance <= TRANSLUCENT_NO_ABSORBANCE) return 1.0f;
    vec4 b = biasedMoments(moments / absorbance, bias);
    float d = 2.0f * z - 1.0f;
    vec2 atoms = hamburgerAtoms(b, d);
    float atZ = atomWeight(b, d, atoms.x, atoms.y);
    float lower = d <= atoms.x ? 0.0f
                : d <= atoms.y ? atomWeight(b, atoms.x, d, atoms.y)
                               : 1.0f - atZ;
    float front = clamp(lower + overestimation * atZ, 0.0f, 1.0f);
    return exp(-absorbance * front);
}

PENUMBRA_GPU_END

#endif
// clang-format on
