#version 460
// Summed-area VSM: the row sums summed down columns.
#define AXIS 1
#include "sat_scan.glsl"
