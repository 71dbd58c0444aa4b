#version 460
// Exponential variance shadow maps: both warps' moments, blurred along rows.
#define AXIS 0
#define MOMENTS MOMENTS_EVSM
#define FORMAT rgba32f
#include "moments_blur.glsl"
