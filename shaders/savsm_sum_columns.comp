#version 460
// Summed-area VSM: the row sums summed down columns.
#define AXIS 1
#define MOMENTS MOMENTS_VSM
#define FORMAT rg32ui
#define SCALE savsm.tableScale
#include "sat_scan.glsl"
