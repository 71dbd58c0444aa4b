// A technique's parameter block: each module packs its own std140 struct (declared in
// shaders/include/params_<family>.h) into one uniform buffer of TECHNIQUE_BLOCK_BYTES, which
// every pass that evaluates or prefilters the technique binds at TECH_PARAMS. In GLSL,
// PENUMBRA_TECHNIQUE_BLOCK declares the block under the technique's own name (the blocks of
// every technique alias that one binding: a pass reads the one its TECHNIQUE selects); in C++ it
// checks the struct fits.
// clang-format off
#ifndef PENUMBRA_TECHNIQUE_BLOCK_H
#define PENUMBRA_TECHNIQUE_BLOCK_H
#include "bindings.h"
#include "shared_prelude.h"

#define TECHNIQUE_BLOCK_BYTES 256

#ifdef __cplusplus
#define PENUMBRA_TECHNIQUE_BLOCK(Block, Params, name)                                             \
    static_assert(sizeof(penumbra::gpu::Params) % 16 == 0 &&                                       \
                      sizeof(penumbra::gpu::Params) <= TECHNIQUE_BLOCK_BYTES,                      \
                  #Params " must fill whole std140 vec4s within the technique block");
#define PENUMBRA_LAYER_BLOCK(Block, Params, name) PENUMBRA_TECHNIQUE_BLOCK(Block, Params, name)
#else
#define PENUMBRA_TECHNIQUE_BLOCK(Block, Params, name)                                             \
    layout(set = 0, binding = TECH_PARAMS, std140) uniform Block { Params name; };
// A layer's block (src/shadows/layer.h), the same size, at LAYER_PARAMS.
#define PENUMBRA_LAYER_BLOCK(Block, Params, name)                                                 \
    layout(set = 0, binding = LAYER_PARAMS, std140) uniform Block { Params name; };
#endif

#endif
// clang-format on
