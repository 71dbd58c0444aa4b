#version 460
// smrt.skipLit's bounds, level 0, from the depth map (shaders/include/smrt_bounds.glsl).
#define BOUNDS_ABOVE sampler2D
#define BOUNDS_BITS(v) floatBitsToUint(max(v, vec4(0.0)))
#include "smrt_bounds.glsl"
