#version 460
// Evaluates the technique's shadow-map filter for given receivers on a given map: the GPU side
// of the CPU/GPU parity tests (src/reference/filter_reference.cpp is the CPU side).
#include "kernels.h"
#include "light_geometry.h"
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_TECHNIQUE) const uint TECHNIQUE = TECHNIQUE_HARD;
layout(constant_id = SPEC_FILTER) const uint FILTER = FILTER_BOX;
#include "techniques.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = PROBE_RECEIVERS, std430) readonly buffer Probes {
    ProbeReceiver probes[];
};
layout(set = 0, binding = PROBE_SHADOW_MAP) uniform sampler2DArray shadowMap; // one layer
layout(set = 0, binding = PROBE_SHADOW_COMPARE) uniform sampler2DArrayShadow shadowMapCmp;
layout(set = 0, binding = PROBE_SHADOW_TABLE) uniform usampler2DArray shadowTable;
layout(set = 0, binding = PROBE_RESULTS, std430) writeonly buffer Results { vec4 results[]; };
layout(set = 0, binding = PROBE_VIEW, std430) readonly buffer Views { ShadowViewData view; };
layout(push_constant) uniform Push { ProbePush push; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.counts.x) return;
    ProbeReceiver probe = probes[i];
    Receiver r;
    r.uv = probe.uvDepth.xy;
    r.depth = probe.uvDepth.z;
    r.gradient = probe.gradientPixel.xy;
    r.uvDx = probe.footprint.xy;
    r.uvDy = probe.footprint.zw;
    r.layer = 0.0;
    r.kernelScale = 1.0;
    r.curve = probe.adaptive.xy;
    r.planeRange = probe.adaptive.zw;
    results[i] = evaluateTechnique(TECHNIQUE, shadowMap, shadowMapCmp, shadowTable, r,
                                   push.counts.y, view, uvec2(probe.gradientPixel.zw));
}
