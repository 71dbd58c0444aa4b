#version 460
// Summed-area VSM: offset moments summed along rows.
#define AXIS 0
#include "sat_scan.glsl"
