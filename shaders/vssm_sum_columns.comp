#version 460
// Variance soft shadow maps: the row sums summed down columns.
#define AXIS 1
#define MOMENTS MOMENTS_VSM
#define FORMAT rg32ui
#define SCALE vssm.tableScale
#include "sat_scan.glsl"
