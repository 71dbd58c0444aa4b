#version 460
// Moment shadow maps: four moments of the light's depth, blurred along rows.
#define AXIS 0
#define MOMENTS MOMENTS_MSM
#define FORMAT rgba32f
#define PARAMS msm
#define STORE16 (msm.bits == 16u)
#include "moments_blur.glsl"
