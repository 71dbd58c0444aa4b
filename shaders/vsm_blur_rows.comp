#version 460
// Variance shadow maps: moments of the light's depth, blurred along rows.
#define AXIS 0
#define MOMENTS MOMENTS_VSM
#define FORMAT rg32f
#define PARAMS vsm
#include "moments_blur.glsl"
