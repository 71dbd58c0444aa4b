#version 460
// Evaluates the technique's shadow-map filter for given receivers on a given map: the GPU side
// of the CPU/GPU parity tests (each module's CPU reference, src/shadows/<name>.cpp, is the
// other side). The same entry point as the visibility pass's (techniques.glsl).
#include "kernels.h"
#include "light_geometry.h"
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_TECHNIQUE) const uint TECHNIQUE = 0u;
// The probed view's light kind, as the visibility pass has it (filter_probe.cpp).
layout(constant_id = SPEC_LIGHT_TYPE) const uint LIGHT_TYPE = LIGHT_DIRECTIONAL;
layout(constant_id = SPEC_PROBE_SLOTS) const uint PROBE_SLOTS = 0u;
#include "techniques.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = PROBE_RECEIVERS, std430) readonly buffer Probes {
    ProbeReceiver probes[];
};
layout(set = 0, binding = PROBE_RESULTS, std430) writeonly buffer Results { vec4 results[]; };
layout(set = 0, binding = PROBE_VIEW, std430) readonly buffer Views { ShadowViewData view; };
layout(push_constant) uniform Push { ProbePush push; };

#if TECH_MAX_MAPS != 4
#error "the slot reads below name four slots of each kind"
#endif
// The texel under `uv` of level 0 of a map slot, whatever its size (smrt's bounds are half).
#define SLOT_TEXEL(map, uv) ivec3(min(ivec2((uv) * vec2(textureSize(map, 0).xy)), \
                                      textureSize(map, 0).xy - 1), 0)
#define FLOAT_SLOT(k, uv) texelFetch(shadowMaps[k], SLOT_TEXEL(shadowMaps[k], uv), 0).r
#define INTEGER_SLOT(k, uv) \
    uintBitsToFloat(texelFetch(shadowTables[k], SLOT_TEXEL(shadowTables[k], uv), 0).r)

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.counts.x) return;
    ProbeReceiver probe = probes[i];
    vec2 uv = probe.uvDepth.xy;
    if (PROBE_SLOTS == 1u) { // constant indices: no dynamic indexing of the arrays
        results[i] = vec4(FLOAT_SLOT(0, uv), FLOAT_SLOT(1, uv), FLOAT_SLOT(2, uv),
                          FLOAT_SLOT(3, uv));
        return;
    }
    if (PROBE_SLOTS == 2u) {
        results[i] = vec4(INTEGER_SLOT(0, uv), INTEGER_SLOT(1, uv), INTEGER_SLOT(2, uv),
                          INTEGER_SLOT(3, uv));
        return;
    }
    if (PROBE_SLOTS == 3u) { // a summed-area table as the post passes left it, every channel
        ivec3 texel = SLOT_TEXEL(shadowTables[0], uv);
        results[i] = uintBitsToFloat(texelFetch(shadowTables[0], texel, 0));
        return;
    }
    TechniqueInput at;
    at.r.uv = probe.uvDepth.xy;
    at.r.depth = probe.uvDepth.z;
    at.r.gradient = probe.gradientPixel.xy;
    at.r.uvDx = probe.footprint.xy;
    at.r.uvDy = probe.footprint.zw;
    at.r.layer = 0.0;
    at.r.kernelScale = 1.0;
    at.r.curve = probe.adaptive.xy;
    at.r.planeRange = probe.adaptive.zw;
    at.r.creaseLimit = probe.uvDepth.w;
    at.view = view;
    at.mapSize = push.counts.y;
    at.pixel = uvec2(probe.gradientPixel.zw);
    at.stage = STAGE_WHOLE;
    at.blockers = vec2(0.0);
    at.zBlocker = 0.0;
    at.world = vec3(0.0);
    at.face = vec3(0.0);
    at.sinRadius = 0.0;
    at.horizon = false;
    results[i] = evaluateTechnique(TECHNIQUE, at);
}
