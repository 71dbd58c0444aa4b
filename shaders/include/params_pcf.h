// pcf's and pcss's parameter blocks (src/shadows/pcf.cpp and pcss.cpp pack them; shadow_pcf.glsl
// and shadow_pcss.glsl read them as `pcf` and `pcss`).
// clang-format off
#ifndef PENUMBRA_PARAMS_PCF_H
#define PENUMBRA_PARAMS_PCF_H
#include "technique_block.h"

PENUMBRA_GPU_BEGIN
struct PcfParams {       // std140
    uint kernel;         // pcf.filter: FILTER_* (also the specialization constant FILTER)
    uint size;           // pcf.size: N of the N x N grid
    uint samples;        // pcf.samples: Poisson taps
    uint rotation;       // pcf.rotation: ROTATION_*
    float radius;        // pcf.radius: the Poisson disk's, in texels
    float sigma;         // the Gaussian's standard deviation in texels (pcf.sigma, else size / 4)
    uint edgeOnly;       // pcf.adaptive: 1, edge-only PCF [Isidoro 2006]
    uint pad;
};

struct PcssParams {      // std140
    uint blockerSamples; // pcss.blockerSamples: gathers of the blocker search
    uint filterSamples;  // pcss.filterSamples: bilinear taps of the filter
    uint rotation;       // pcss.rotation: ROTATION_*
    float maxRadius;     // pcss.maxRadius: texels of the view sampled (spots, cascades)
    float cubeRadius;    // pcss.cubeRadius: the same on a point light's cube faces (kernelCap)
    float pad0, pad1, pad2;
};
PENUMBRA_GPU_END

PENUMBRA_TECHNIQUE_BLOCK(PcfBlock, PcfParams, pcf)
PENUMBRA_TECHNIQUE_BLOCK(PcssBlock, PcssParams, pcss)

#endif
// clang-format on
