// The technique table of the visibility pass: TECHNIQUE (a specialization constant) picks one
// entry; the probe shader used by the parity tests calls the same function.
#ifndef PENUMBRA_TECHNIQUES_GLSL
#define PENUMBRA_TECHNIQUES_GLSL
#include "shadow_hard.glsl"
#include "shadow_pcf.glsl"

float evaluateTechnique(uint technique, sampler2D map, sampler2DShadow mapCompare, Receiver r,
                        uint mapSize, uvec2 pixel) {
    switch (technique) {
    case TECHNIQUE_PCF: return shadowPcf(map, mapCompare, r, mapSize, pixel);
    case TECHNIQUE_HARD:
    default: return shadowHard(map, r, mapSize, frame.biasParams.xy);
    }
}

#endif
