// The frame block (std140 uniform, BIND_FRAME): the camera, the image, the composite's knobs and
// the settings every technique reads. Compiled as GLSL and as C++ with static_asserts on the
// layout.
// clang-format off
#ifndef PENUMBRA_FRAME_BLOCK_H
#define PENUMBRA_FRAME_BLOCK_H
#include "kernels.h"

PENUMBRA_GPU_BEGIN
struct FrameData {       // std140 uniform block: the camera and every technique setting
    mat4 viewProj;       // world -> clip (reverse-Z, y flipped)
    mat4 invViewProj;    // clip -> world
    vec4 position;       // xyz: camera position
    uvec4 imageSize;     // x width, y height, z light count
    vec4 composite;      // x ambient, y shadow intensity, z exposure scale 2^EV
    vec4 background;     // rgb: colour of pixels with no geometry
    uvec4 filterMode;    // x pcf.filter, y pcf.size, z pcf.samples, w pcf.rotation
    vec4 filterParams;   // x pcf.radius (texels), y Gaussian sigma (texels), z pcf.adaptive
    uvec4 biasMode;      // x bias.receiver, y 1: hardware linear depth compare, z sub-texel bits,
                         // w bias.mode
    vec4 biasParams;     // xy: range of a tap's receiver-plane depth correction (light depth),
                         // z bias.adaptive (texels), w bias.curvature
    uvec4 pcssMode;      // x pcss.blockerSamples, y pcss.filterSamples, z pcss.rotation
    vec4 pcssParams;     // x pcss.maxRadius (texels)
    vec4 cameraForward;  // xyz: the camera's unit view axis (cascades are picked by distance
                         // along it)
    vec4 vsmParams;      // x vsm.minVariance, y vsm.bleedReduction, z vsm.size (taps), w
                         // vsm.anisotropy with vsm.filter=mip (0: vsm.filter=blur)
    vec4 esmParams;      // x esm.c, y esm.size (taps)
    vec4 evsmParams;     // x evsm.positive, y evsm.negative, z evsm.minVariance,
                         // w evsm.bleedReduction
    uvec4 evsmMode;      // x evsm.components (2 or 4), y evsm.size (taps)
    vec4 savsmParams;    // x savsm.size (texels, box width), y savsm.minVariance,
                         // z savsm.bleedReduction
    vec4 msmParams;      // x msm.bias (moment bias), y msm.size (taps), z msm.precision (16, 32)
    vec4 vssmParams;     // x vssm.maxRadius (texels), y vssm.minVariance, z vssm.bleedReduction
    vec4 msmSoftParams;  // x msm-soft.maxRadius (texels), y msm-soft.bias
    uvec4 softMode;      // x vssm.subdivision (sub-kernels per axis), y vssm.refine (1: on),
                         // z msm-soft.subdivision, w msm-soft.refine
    vec4 tableScales;    // fixed-point steps per unit of the summed-area tables' moments:
                         // x savsm, y vssm, z msm-soft (src/shadows/technique.h, fixedPointScale)
    vec4 sdfParams;      // x sdf.steps, y sdf.startOffset (voxels), z sdf.k (0: from the light's
                         // size), w the smallest step (voxels)
    vec4 fieldOrigin;    // the distance field's box: xyz its lowest corner, w a voxel's side
    uvec4 fieldSize;     // xyz its voxels per axis (zero: no field)
    vec4 poisson[POISSON_MAX_SAMPLES / 2u]; // Poisson disk in the unit disk, two points a vec4
};
PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(FrameData) == 1024 && offsetof(FrameData, position) == 128 &&
              offsetof(FrameData, imageSize) == 144 && offsetof(FrameData, background) == 176 &&
              offsetof(FrameData, filterMode) == 192 && offsetof(FrameData, biasParams) == 240 &&
              offsetof(FrameData, pcssMode) == 256 && offsetof(FrameData, cameraForward) == 288 &&
              offsetof(FrameData, vsmParams) == 304 && offsetof(FrameData, evsmMode) == 352 &&
              offsetof(FrameData, savsmParams) == 368 && offsetof(FrameData, msmParams) == 384 &&
              offsetof(FrameData, vssmParams) == 400 &&
              offsetof(FrameData, msmSoftParams) == 416 &&
              offsetof(FrameData, softMode) == 432 &&
              offsetof(FrameData, tableScales) == 448 && offsetof(FrameData, sdfParams) == 464 &&
              offsetof(FrameData, fieldSize) == 496 && offsetof(FrameData, poisson) == 512);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
