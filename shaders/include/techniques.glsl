// Every technique's shader include, and the dispatch on the technique: TECHNIQUE (a
// specialization constant) picks one entry point of the list (technique_list.h). The including
// pass is compiled once per technique, PENUMBRA_ONLY_TECHNIQUE its id (cmake/Shaders.cmake,
// PER_TECHNIQUE): glslang leaves the other entry points' code out of the module, which a driver
// would otherwise translate whole for every pipeline. The visibility pass and the filter probe
// of the parity tests call the same function. The including pass declares the frame block as
// `frame`.
#ifndef PENUMBRA_TECHNIQUES_GLSL
#define PENUMBRA_TECHNIQUES_GLSL
#ifndef PENUMBRA_ONLY_TECHNIQUE
#error "compiled once per technique: cmake/Shaders.cmake, PER_TECHNIQUE"
#endif
// Each technique's shader named by the list, once (written by cmake/Shaders.cmake).
#include "technique_shaders.glsl"

// x: visibility; yzw: intermediate results the parity tests and the viewer read (PCSS: average
// blocker depth, blocking texels found, filter radius in texels; VSM: the two filtered moments
// and the receiver's moment depth; ESM, EVSM, MSM: see shadow_moments.glsl; SAVSM, VSSM,
// MSM-soft: see shadow_sat.glsl; zero for the others).
vec4 evaluateTechnique(uint technique, TechniqueInput at) {
#define PENUMBRA_TECHNIQUE(id, Name, module, shader) \
    if (id == PENUMBRA_ONLY_TECHNIQUE && technique == id) return evaluate##Name(at);
#include "technique_list.h"
    return vec4(1.0, 0.0, 0.0, 0.0); // not a technique: lit
}

#endif
