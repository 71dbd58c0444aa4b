#version 460
// Moment shadow maps: the row-blurred moments, blurred along columns.
#define AXIS 1
#define MOMENTS MOMENTS_MSM
#define PARAMS msm
#define STORE16 (msm.bits == 16u)
#include "moments_blur.glsl"
