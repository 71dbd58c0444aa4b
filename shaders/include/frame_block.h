// The frame block (std140 uniform, BIND_FRAME): the camera, the image, the composite's knobs and
// the settings every technique reads; each technique's own are in its parameter block
// (technique_block.h). Compiled as GLSL and as C++ with static_asserts on the
// layout.
// clang-format off
#ifndef PENUMBRA_FRAME_BLOCK_H
#define PENUMBRA_FRAME_BLOCK_H
#include "kernels.h"

PENUMBRA_GPU_BEGIN
struct FrameData {       // std140 uniform block: the camera, the image and the shared settings
    mat4 viewProj;       // world -> clip (reverse-Z, y flipped)
    mat4 invViewProj;    // clip -> world
    vec4 position;       // xyz: camera position
    uvec4 imageSize;     // x width, y height, z light count
    vec4 composite;      // x ambient, y shadow intensity, z exposure scale 2^EV
    vec4 background;     // rgb: colour of pixels with no geometry
    vec4 cameraForward;  // xyz: the camera's unit view axis (cascades are picked by distance
                         // along it)
    uvec4 biasMode;      // x bias.receiver, y 1: hardware linear depth compare, z sub-texel bits,
                         // w bias.mode
    vec4 biasParams;     // xy: range of a tap's receiver-plane depth correction (light depth),
                         // z bias.adaptive (texels), w bias.curvature
    vec4 filterLimits;   // x: the widest blocker search and filter, texels of the view sampled
                         // (TechniqueModule::searchCap; SPEC_BLOCKER_SEARCH's cascade choice),
                         // y: bias.crease, the steepest plane the crease rule takes (0: off)
    vec4 fieldOrigin;    // the scene's distance field when one is built: xyz its lowest corner,
                         // w a voxel's side
    uvec4 fieldSize;     // xyz its voxels per axis (zero: no field)
    uvec4 virtualPages;  // virtual maps (virtual.enabled; virtual_pages.h): x a page's side in
                         // texels, y the pool's pages a side, z a spot's or cube face's levels,
                         // w 1: on
    vec4 virtualLod;     // x virtual.lodBias, y the technique's reach around a receiver in texels
                         // (the pages its filter reads are requested)
    vec4 poisson[POISSON_MAX_SAMPLES / 2u]; // Poisson disk in the unit disk, two points a vec4
                                            // (the PCF family's kernels)
    mat4 previousViewProj; // the last frame's viewProj (this frame's on a first frame or a cut):
                           // the G-buffer's motion vectors (gbuffer.vert)
    uvec4 motion;          // x 1: the vertices moved since the last frame and the previous
                           // positions buffer holds where they were (GBUFFER_PREVIOUS_POSITIONS);
                           // y the frame's index while a layer keeps a history (0 otherwise): the
                           // techniques turn their per-pixel rotations by it (turnedByFrame)
};
PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(FrameData) == 912 && offsetof(FrameData, position) == 128 &&
              offsetof(FrameData, imageSize) == 144 && offsetof(FrameData, background) == 176 &&
              offsetof(FrameData, cameraForward) == 192 && offsetof(FrameData, biasMode) == 208 &&
              offsetof(FrameData, biasParams) == 224 && offsetof(FrameData, filterLimits) == 240 &&
              offsetof(FrameData, fieldOrigin) == 256 && offsetof(FrameData, fieldSize) == 272 &&
              offsetof(FrameData, virtualPages) == 288 &&
              offsetof(FrameData, virtualLod) == 304 && offsetof(FrameData, poisson) == 320 &&
              offsetof(FrameData, previousViewProj) == 832 &&
              offsetof(FrameData, motion) == 896);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
