#version 460
// The translucent layer's coloured map: each surface's transmittance, multiplied into the product
// by the blend (destination x source).
#include "translucent_caster.glsl"

layout(location = 0) out vec4 outProduct;

void main() {
    float depth;
    outProduct = vec4(translucentFragment(depth), 1.0);
}
