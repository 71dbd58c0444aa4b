#version 460
// Exponential shadow maps: the row-blurred exponentials, blurred along columns.
#define AXIS 1
#define MOMENTS MOMENTS_ESM
#define FORMAT r32f
#define PARAMS esm
#define EXPONENTS vec2(esm.c)
#include "moments_blur.glsl"
