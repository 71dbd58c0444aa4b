#version 460
// The edge-aware spatial filter of a technique's visibility (smrt's screen passes, src/shadows/smrt_screen.cpp;
// shaders/include/visibility_filter_weights.h has the weights, src/shadows/visibility_filter.cpp mirrors
// it), one light's layer a dispatch. SPEC_FILTER_AXIS 0 reads the visibility (LAYER_VISIBILITY)
// and writes the rows' result to the scratch layer (LAYER_RESULTS); 1 reads the scratch and
// writes the columns' result back. Background pixels keep their NaN.
#include "frame_block.h"
#include "bindings.h"
#include "pass_types.h"
#include "visibility_filter_weights.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_FILTER_RADIUS) const int RADIUS = 1;
layout(constant_id = SPEC_FILTER_TOLERANCE) const float TOLERANCE = 0.5;
layout(constant_id = SPEC_FILTER_AXIS) const int AXIS = 0;
// The radius inside a wide penumbra (visibilityFilterWide; RADIUS where it is not larger).
layout(constant_id = SPEC_FILTER_WIDE) const int WIDE = 1;
#include "gbuffer.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = LAYER_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = LAYER_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = LAYER_VISIBILITY, r32f) uniform image2DArray visibility;
layout(set = 0, binding = LAYER_RESULTS, r32f) uniform image2DArray scratch;
layout(push_constant) uniform Push { VisibilityPush push; };

float readSource(ivec3 at) {
    return AXIS == 0 ? imageLoad(visibility, at).r : imageLoad(scratch, at).r;
}

void writeTarget(ivec3 at, float v) {
    if (AXIS == 0) imageStore(scratch, at, vec4(v));
    else imageStore(visibility, at, vec4(v));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    int layer = int(push.light.y);
    ivec3 at = ivec3(p, layer);
    float depth = texelFetch(gDepth, p, 0).r;
    float vp = readSource(at);
    if (isBackground(depth)) {
        writeTarget(at, vp);
        return;
    }
    vec3 world = worldPosition(frame.invViewProj, p, size, depth);
    vec3 normal = shadingNormal(texelFetch(gNormal, p, 0));
    // Not `AXIS == 0 ? ivec2(1, 0) : ivec2(0, 1)`: glslang folds that into a specialization
    // constant OpSelect on vectors, which lavapipe 22.3 evaluates to (1, 1).
    ivec2 axis = ivec2(1 - AXIS, AXIS);
    // Inside a wide penumbra the pixel reaches as far as its neighbours stay in it on both sides
    // (visibility_filter_weights.h, visibilityFilterInPenumbra), up to WIDE.
    int reach = RADIUS;
    if (WIDE > RADIUS && visibilityFilterInPenumbra(vp)) {
        int run = WIDE;
        for (int side = -1; side <= 1; side += 2)
            for (int o = 1; o <= WIDE; ++o) {
                ivec2 q = p + side * o * axis;
                bool onImage = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(uvec2(q), size));
                if (!onImage || isBackground(texelFetch(gDepth, q, 0).r) ||
                    !visibilityFilterInPenumbra(readSource(ivec3(q, layer)))) {
                    run = min(run, o - 1);
                    break;
                }
            }
        reach = max(RADIUS, run);
    }
    float weights = 0.0, sum = 0.0;
    for (int offset = -reach; offset <= reach; ++offset) {
        ivec2 q = p + offset * axis;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), size))) continue;
        float qDepth = texelFetch(gDepth, q, 0).r;
        if (isBackground(qDepth)) continue;
        float vq = readSource(ivec3(q, layer));
        float w = visibilityFilterWeight(world, normal, vp,
                                         worldPosition(frame.invViewProj, q, size, qDepth),
                                         shadingNormal(texelFetch(gNormal, q, 0)), vq, offset,
                                         reach, TOLERANCE);
        weights += w;
        sum += w * vq;
    }
    // The pixel itself weighs reach + 1. The clamp: a GPU's division may round sum / weights
    // past 1 by an ulp or two where every neighbour is lit (a reciprocal, not an exact quotient).
    writeTarget(at, clamp(sum / weights, 0.0, 1.0));
}
