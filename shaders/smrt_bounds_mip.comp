#version 460
// smrt.skipLit's bounds, levels 1.., each from the level above (shaders/include/smrt_bounds.glsl).
#define BOUNDS_ABOVE usampler2D
#define BOUNDS_BITS(v) (v)
#include "smrt_bounds.glsl"
