// The viewer's display pass (shaders/viewer_display.comp, apps/viewer/display.cpp): what the
// window shows, from the frame's targets. DISPLAY_* modes, its bindings and push constants;
// compiled as GLSL and as C++.
// clang-format off
#ifndef PENUMBRA_VIEWER_TYPES_H
#define PENUMBRA_VIEWER_TYPES_H
#include "light_geometry.h"

#define DISPLAY_SCENE 0u         // the lit image
#define DISPLAY_VISIBILITY 1u    // one light's visibility as grey
#define DISPLAY_SHADOW_MAP 2u    // one layer of the depth map, linear depth as grey, letterboxed
#define DISPLAY_CASCADES 3u      // the lit image tinted by the cascade each pixel reads
#define DISPLAY_OVERLAY 4u       // an image the host made (the error heat map)
#define DISPLAY_BLOCKER_DEPTH 5u // the average blocker's depth (PCSS, VSSM, MSM-soft) as grey
#define DISPLAY_PENUMBRA 6u      // the filter's radius in texels, as a colour ramp
#define DISPLAY_LAYER 7u         // one light's layer result (contact shadows: 0 where a surface
                                 // in the depth buffer hides the light) as grey
#define DISPLAY_COLOR 0          // rgba8 storage, the lit image (technique A)
#define DISPLAY_COLOR_B 1        // rgba8 storage, technique B's (A's when there is no B)
#define DISPLAY_VISIBILITY_MAP 2 // sampler2DArray, a layer per shadow-casting light
#define DISPLAY_DEPTH_MAP 3      // sampler2DArray, the shadow depth map
#define DISPLAY_GBUFFER_DEPTH 4  // sampler2D, reverse-Z
#define DISPLAY_OVERLAY_IMAGE 5  // rgba8 storage, the host's image
#define DISPLAY_FRAME 6          // FrameData of the frame
#define DISPLAY_OUT 7            // rgba8 storage, what is presented
#define DISPLAY_INTERMEDIATES 8  // sampler2DArray, VIS_INTERMEDIATES
#define DISPLAY_LAYER_RESULTS 9  // sampler2DArray, LAYER_RESULTS

PENUMBRA_GPU_BEGIN
struct DisplayPush {     // push constants of viewer_display.comp
    uvec4 mode;          // x DISPLAY_*, y layer (visibility or depth map), z split column (A left
                         // of it, B from it on; >= width: A only), w cascades in `splits`
    vec4 depthRange;     // x near, y far, z 1: perspective (linearise), w the largest penumbra
                         // radius in texels (DISPLAY_PENUMBRA's scale)
    vec4 forward;        // xyz: the camera's unit view axis (cascade distances)
    vec4 splits[2];      // the cascades' far distances along the view axis, 8 at most
};
PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(DisplayPush) == 80 && offsetof(DisplayPush, splits) == 48 &&
              MAX_CASCADES == 8u, "DisplayPush.splits holds MAX_CASCADES distances");
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
