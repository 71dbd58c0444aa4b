#version 460
// Exponential shadow maps: the row-blurred exponentials, blurred along columns.
#define AXIS 1
#define MOMENTS MOMENTS_ESM
#define FORMAT r32f
#include "moments_blur.glsl"
