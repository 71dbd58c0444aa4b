#version 460
// Page draws of the opaque casters (page_draw.glsl): positions only, as shadow_position.vert.
#include "page_draw.glsl"

layout(location = 0) in vec3 inPosition;

void main() { placeInPage(inPosition); }
