// The blurred-moment members' parameter blocks (src/shadows/vsm.cpp, esm.cpp, evsm.cpp, msm.cpp
// pack them; shadow_moments.glsl and the blur passes, moments_blur.glsl, read them as `vsm`,
// `esm`, `evsm` and `msm`).
// clang-format off
#ifndef PENUMBRA_PARAMS_MOMENTS_H
#define PENUMBRA_PARAMS_MOMENTS_H
#include "technique_block.h"

PENUMBRA_GPU_BEGIN
struct VsmParams {       // std140
    float minVariance;   // vsm.minVariance, (depth range)^2
    float bleedReduction;// vsm.bleedReduction
    uint size;           // vsm.size: the blur's taps
    float anisotropy;    // vsm.filter=mip: vsm.anisotropy, taps along the footprint (0: blur)
};

struct EsmParams {       // std140
    float c;             // esm.c: the exponent over the [0, 1] moment depth
    uint size;           // esm.size: the blur's taps
    uint pad0, pad1;
};

struct EvsmParams {      // std140
    float positive;      // evsm.positive: c+ of the positive warp
    float negative;      // evsm.negative: c- of the negative warp
    float minVariance;   // evsm.minVariance, in moment-depth units
    float bleedReduction;// evsm.bleedReduction
    uint components;     // 2 (the positive warp alone) or 4
    uint size;           // evsm.size: the blur's taps
    uint pad0, pad1;
};

struct MsmParams {       // std140
    float momentBias;    // msm.bias: the paper's moment bias
    uint size;           // msm.size: the blur's taps
    uint bits;           // msm.precision: 16 (quantised, RGBA16 unorm) or 32 (RGBA32F)
    uint pad;
};
PENUMBRA_GPU_END

PENUMBRA_TECHNIQUE_BLOCK(VsmBlock, VsmParams, vsm)
PENUMBRA_TECHNIQUE_BLOCK(EsmBlock, EsmParams, esm)
PENUMBRA_TECHNIQUE_BLOCK(EvsmBlock, EvsmParams, evsm)
PENUMBRA_TECHNIQUE_BLOCK(MsmBlock, MsmParams, msm)

#endif
// clang-format on
