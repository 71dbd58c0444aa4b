#version 460
// Depth peel for second-depth shadow maps [Wang and Molnar 1994]: keeps, per texel, the nearest
// surface behind the one the first shadow pass stored.
layout(set = 0, binding = 0) uniform sampler2D firstDepth;

void main() {
    float first = texelFetch(firstDepth, ivec2(gl_FragCoord.xy), 0).r;
    // The first layer itself: the same depth, up to a few ulps should another pipeline round
    // differently.
    if (gl_FragCoord.z <= first + 4e-7 * max(first, 1e-3)) discard;
}
