#version 460
// Variance shadow maps: the row-blurred moments, blurred along columns.
#define AXIS 1
#define MOMENTS MOMENTS_VSM
#define FORMAT rg32f
#define PARAMS vsm
#include "moments_blur.glsl"
