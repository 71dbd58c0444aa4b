#version 460
// Moment soft shadows: the row sums summed down columns.
#define AXIS 1
#define MOMENTS MOMENTS_MSM
#define FORMAT rgba32ui
#define SCALE msmSoft.tableScale
#include "sat_scan.glsl"
