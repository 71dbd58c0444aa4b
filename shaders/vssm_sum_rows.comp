#version 460
// Variance soft shadow maps: fixed-point offset moments summed along rows.
#define AXIS 0
#define MOMENTS MOMENTS_VSM
#define FORMAT rg32ui
#define SCALE vssm.tableScale
#include "sat_scan.glsl"
