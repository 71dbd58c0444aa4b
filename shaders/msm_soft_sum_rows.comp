#version 460
// Moment soft shadows: fixed-point moments summed along rows.
#define AXIS 0
#define MOMENTS MOMENTS_MSM
#define FORMAT rgba32ui
#define SCALE msmSoft.tableScale
#include "sat_scan.glsl"
