#version 460
// The `contact` layer (src/shadows/contact.cpp): screen-space contact shadows for one light. From
// each pixel, contact.steps samples march towards the light over contact.length (world units);
// the first that a G-buffer surface hides (contactOccludes, shaders/include/contact_march.h) puts the
// pixel in shadow, which multiplies the light's visibility from its base technique. Pixels whose
// triangle faces away from the light, and background pixels, are left as they are.
#include "frame_block.h"
#include "light_geometry.h"
#include "bindings.h"
#include "pass_types.h"
#include "kernels.h"
#include "contact_march.h"
layout(set = 0, binding = BIND_FRAME, std140) uniform FrameBlock { FrameData frame; };
layout(constant_id = SPEC_LIGHT_TYPE) const uint LIGHT_TYPE = LIGHT_DIRECTIONAL;
layout(constant_id = SPEC_INTERMEDIATES) const bool WRITE_RESULTS = false;
#define LIGHT_TYPE_OF(light) LIGHT_TYPE
#include "gbuffer.glsl"
#include "shadow_common.glsl"

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;
layout(set = 0, binding = LAYER_LIGHTS, std140) uniform Lights { LightData lights[MAX_UNIFORM_LIGHTS]; };
layout(set = 0, binding = LAYER_GBUFFER_DEPTH) uniform sampler2D gDepth;
layout(set = 0, binding = LAYER_GBUFFER_NORMAL) uniform sampler2D gNormal;
layout(set = 0, binding = LAYER_VISIBILITY, r32f) uniform image2DArray visibility;
layout(set = 0, binding = LAYER_RESULTS, r32f) uniform writeonly image2DArray results;
layout(push_constant) uniform Push { VisibilityPush push; };

// 1 lit, 0 a surface within the march hides the light (src/shadows/contact.cpp mirrors it).
float contactVisibility(ivec2 p, vec3 world, vec3 face, LightData light) {
    vec3 toLight = directionToLight(light, world);
    float nDotL = dot(face, toLight);
    if (nDotL <= 0.0) return 1.0; // the surface hides the light itself
    float reach = contact.marchLength;
    if (LIGHT_TYPE != LIGHT_DIRECTIONAL)
        reach = min(reach, length(light.positionType.xyz - world));
    float jitter = turnedByFrame(rotationTurns(ROTATION_IGN, uvec2(p)), frame.motion.y);
    vec2 size = vec2(frame.imageSize.xy);
    for (uint i = 0u; i < contact.steps; ++i) {
        float t = contactSampleDistance(i, contact.steps, reach, jitter);
        vec3 q = world + toLight * t;
        vec3 ndc;
        vec2 pixel;
        if (!contactProject(frame.viewProj, q, size, ndc, pixel)) break; // off the image
        float tolerance =
            contactTolerance(frame.invViewProj, ndc, size.x, reach / float(contact.steps));
        vec3 near = unprojectNdc(frame.invViewProj, vec3(ndc.xy, 1.0));
        // Hidden where the pixels around q that hide it hold most of its bilinear weight: just
        // past an object's edge, those beyond it show what lies behind.
        ivec2 base = contactTexels(pixel, frame.imageSize.xy);
        float hidden = 0.0;
        for (int k = 0; k < 4; ++k) {
            ivec2 s = base + ivec2(k & 1, k >> 1);
            float depth = texelFetch(gDepth, s, 0).r;
            if (!isBackground(depth) &&
                contactOccludes(q, near,
                                worldPosition(frame.invViewProj, s, frame.imageSize.xy, depth),
                                faceNormal(texelFetch(gNormal, s, 0)), tolerance,
                                contact.thickness))
                hidden += contactTexelWeight(pixel, base, k);
        }
        if (hidden >= 0.75) return 0.0;
    }
    return 1.0;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = frame.imageSize.xy;
    if (any(greaterThanEqual(uvec2(p), size))) return;
    float depth = texelFetch(gDepth, p, 0).r;
    if (isBackground(depth)) return; // NaN stays
    ivec3 at = ivec3(p, int(push.light.y));
    vec3 world = worldPosition(frame.invViewProj, p, size, depth);
    float c = contactVisibility(p, world, faceNormal(texelFetch(gNormal, p, 0)),
                                lights[push.light.x]);
    imageStore(visibility, at, vec4(imageLoad(visibility, at).r * c));
    if (WRITE_RESULTS) imageStore(results, at, vec4(c));
}
