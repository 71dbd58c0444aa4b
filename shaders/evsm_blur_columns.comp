#version 460
// Exponential variance shadow maps: the row-blurred moments, blurred along columns.
#define AXIS 1
#define MOMENTS MOMENTS_EVSM
#define FORMAT rgba32f
#define PARAMS evsm
#define EXPONENTS vec2(evsm.positive, evsm.negative)
#include "moments_blur.glsl"
