#version 460
// Summed-area VSM: fixed-point offset moments summed along rows.
#define AXIS 0
#define MOMENTS MOMENTS_VSM
#define FORMAT rg32ui
#define SCALE savsm.tableScale
#include "sat_scan.glsl"
