#version 460
// Exponential variance shadow maps: the row-blurred moments, blurred along columns.
#define AXIS 1
#define MOMENTS MOMENTS_EVSM
#define FORMAT rgba32f
#include "moments_blur.glsl"
