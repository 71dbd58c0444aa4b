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

// The translucent layer's methods (translucent.method) and what a caster draw writes.
#define TRANSLUCENT_OFF 0u
#define TRANSLUCENT_COLOURED 1u         // coloured transmittance map
#define TRANSLUCENT_MOMENTS 2u          // moment-based transmittance
#define TRANSLUCENT_DRAW_NEAREST 0u     // the nearest surface's depth and transmittance (depth test)
#define TRANSLUCENT_DRAW_PRODUCT 1u     // the product of the transmittances (multiplied in)
#define TRANSLUCENT_DRAW_MOMENTS 2u     // the absorbances and their moments (added in)
#define TRANSLUCENT_DRAW_SECOND 3u      // the second nearest surface's depth (a peel)
// TranslucentCasterPush::flags.x: what the material does.
#define TRANSLUCENT_TEXTURE 1u          // it has a base colour texture
#define TRANSLUCENT_BLEND 2u            // alphaMode BLEND: alpha is the covered fraction
#define TRANSLUCENT_VOLUME 4u           // KHR_materials_volume: the square root of the tint a face
#define TRANSLUCENT_MASK 8u             // alphaMode MASK: coverage under the cutoff is a hole
// How far the translucent layer's maps push each surface from the light (translucent_caster.glsl):
// its depth's slope over this many texels, and at least this much of the [0, 1] depth range.
#define TRANSLUCENT_SLOPE_TEXELS 2.0f
#define TRANSLUCENT_DEPTH_BIAS 1e-5f
// The moment bias for 32-bit power moments [Muenstermann et al. 2018] (docs/translucency.md).
#define TRANSLUCENT_MOMENT_BIAS 5e-7f
// Rec. 709 luminance: the one-channel visibility the metrics read of an RGB transmittance.
#define TRANSLUCENT_LUMINANCE vec3(0.2126f, 0.7152f, 0.0722f)

// Push constants of a translucent caster's draw (translucent_caster.vert/.frag): the shadow
// pass's (its bias.y the alpha cutoff, bias.z the transmission factor), then the material.
struct TranslucentCasterPush {
    mat4 viewProj;
    vec4 bias;           // x constant depth offset, y alpha cutoff, z transmission factor
    vec4 baseColor;      // linear RGBA factor
    vec4 attenuation;    // xyz: what a volume's face keeps of its path, exp(-sigma thickness / 2)
    uvec4 flags;         // x TRANSLUCENT_* material flags, y the view's layer, zw unused
};

// The translucent layer's parameter block (LAYER_PARAMS).
struct TranslucentParams {
    uvec4 method;        // x TRANSLUCENT_*
    vec4 moments;        // x the moment bias, y overestimation
};

// A surface's absorbance per channel, -ln T: additive where transmittances multiply.
SHARED vec3 layerAbsorbance(vec3 transmittance) {
    return -log(max(transmittance, vec3(TRANSLUCENT_MIN_TRANSMITTANCE)));
}

// Coloured transmittance map: the nearest translucent surface's depth and transmittance (`front`,
// what a depth test keeps), the second nearest's depth (a depth peel past the nearest) and the
// product of every surface's transmittance (multiplicative blending). A receiver at depth z in
// front of the nearest keeps everything; between the nearest and the second, the nearest's
// transmittance; behind the second, the product. Exact wherever a receiver has at most one
// surface of its texel in front of it, and behind them all; a receiver between the second and
// the last keeps the product of all (too dark, and tinted by its own surface).
SHARED vec3 colouredMapTransmittance(vec3 front, vec3 product, float nearest, float second,
                                     float z) {
    return z > second ? product : z > nearest ? front : vec3(1.0f);
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

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::TranslucentCasterPush) == 128 &&
              offsetof(penumbra::gpu::TranslucentCasterPush, flags) == 112);
static_assert(sizeof(penumbra::gpu::TranslucentParams) == 32);
#endif

#endif
// clang-format on
