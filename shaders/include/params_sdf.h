// sdf's parameter block (src/shadows/sdf.cpp packs it; shadow_sdf.glsl reads it as `sdf`).
// clang-format off
#ifndef PENUMBRA_PARAMS_SDF_H
#define PENUMBRA_PARAMS_SDF_H
#include "technique_block.h"

PENUMBRA_GPU_BEGIN
struct SdfParams {       // std140
    float steps;         // sdf.steps: the march's largest step count
    float startOffset;   // sdf.startOffset: voxels off the surface
    float k;             // sdf.k: penumbra sharpness (0: from the light's size)
    float minStep;       // the smallest step, voxels
    float thickness;     // sdf.thickness: open geometry's half-thickness, voxels (ownSurface)
    float pad0, pad1, pad2;
};
PENUMBRA_GPU_END

PENUMBRA_TECHNIQUE_BLOCK(SdfBlock, SdfParams, sdf)

#endif
// clang-format on
