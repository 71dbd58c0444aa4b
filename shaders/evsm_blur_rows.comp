#version 460
// Exponential variance shadow maps: both warps' moments, blurred along rows.
#define AXIS 0
#define MOMENTS MOMENTS_EVSM
#define FORMAT rgba32f
#define PARAMS evsm
#define EXPONENTS vec2(evsm.positive, evsm.negative)
#include "moments_blur.glsl"
