#version 460
// Evaluates the technique's shadow-map filter for given receivers on a given map: the GPU side
// of the CPU/GPU parity tests (src/reference/filter_reference.cpp is the CPU side).
#include "gpu_types.h"
layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_TECHNIQUE) const uint TECHNIQUE = TECHNIQUE_HARD;
layout(constant_id = SPEC_FILTER) const uint FILTER = FILTER_BOX;
#include "techniques.glsl"

layout(local_size_x = 64) in;

struct Probe {
    vec4 uvDepth;       // u, v, depth
    vec4 gradientPixel; // d depth / du, d depth / dv, pixel x, pixel y
};

layout(set = 0, binding = 1, std430) readonly buffer Probes { Probe probes[]; };
layout(set = 0, binding = 2) uniform sampler2DArray shadowMap;          // one layer
layout(set = 0, binding = 3) uniform sampler2DArrayShadow shadowMapCmp;
layout(set = 0, binding = 4, std430) writeonly buffer Results { vec4 results[]; };
layout(set = 0, binding = 5, std430) readonly buffer Views { ShadowViewData view; };
layout(push_constant) uniform Push { uvec4 counts; }; // x probes, y map size

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= counts.x) return;
    Probe probe = probes[i];
    Receiver r;
    r.uv = probe.uvDepth.xy;
    r.depth = probe.uvDepth.z;
    r.gradient = probe.gradientPixel.xy;
    r.layer = 0.0;
    results[i] = evaluateTechnique(TECHNIQUE, shadowMap, shadowMapCmp, r, counts.y, view,
                                   uvec2(probe.gradientPixel.zw));
}
