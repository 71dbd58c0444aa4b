#version 460
// Exponential shadow maps: e^(c z) of the light's depth, blurred along rows.
#define AXIS 0
#define MOMENTS MOMENTS_ESM
#define FORMAT r32f
#define PARAMS esm
#define EXPONENTS vec2(esm.c)
#include "moments_blur.glsl"
