// The summed-area members' parameter blocks (src/shadows/savsm.cpp, vssm.cpp, msm_soft.cpp pack
// them; shadow_sat.glsl and the scans, sat_scan.glsl, read them as `savsm`, `vssm` and
// `msmSoft`).
// clang-format off
#ifndef PENUMBRA_PARAMS_TABLES_H
#define PENUMBRA_PARAMS_TABLES_H
#include "technique_block.h"

PENUMBRA_GPU_BEGIN
struct SavsmParams {     // std140
    float size;          // savsm.size: the box's width in texels
    float minVariance;   // savsm.minVariance
    float bleedReduction;// savsm.bleedReduction
    float tableScale;    // fixed-point steps per unit of the table (fixedPointScale)
};

// vssm and msm-soft: the search and filter cap, the kernel subdivision and the refining search
// (shadows::SoftSearch), the table's scale, and each one's own bound settings.
struct SoftParams {      // std140
    float maxRadius;     // <family>.maxRadius: texels of the map sampled (spots, cascades)
    float tableScale;    // fixed-point steps per unit of the table
    uint subdivision;    // <family>.subdivision: sub-kernels per axis
    uint refine;         // <family>.refine: 1, search again over the penumbra's own box
    float minVariance;   // vssm.minVariance
    float bleedReduction;// vssm.bleedReduction
    float momentBias;    // msm-soft.bias
    float cubeRadius;    // <family>.cubeRadius: maxRadius on a point light's cube faces
};
PENUMBRA_GPU_END

PENUMBRA_TECHNIQUE_BLOCK(SavsmBlock, SavsmParams, savsm)
PENUMBRA_TECHNIQUE_BLOCK(VssmBlock, SoftParams, vssm)
PENUMBRA_TECHNIQUE_BLOCK(MsmSoftBlock, SoftParams, msmSoft)

#endif
// clang-format on
