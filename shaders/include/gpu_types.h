// Host/shader structs, compiled both as GLSL (glslc) and as C++ (with static_asserts on the
// std140/std430 layout), so the two sides cannot drift apart.
#ifndef PENUMBRA_GPU_TYPES_H
#define PENUMBRA_GPU_TYPES_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
namespace penumbra::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
#endif

#define LIGHT_DIRECTIONAL 0u
#define LIGHT_SPOT 1u
#define LIGHT_POINT 2u

// Specialization constant TECHNIQUE of visibility.comp; equals penumbra::Technique.
#define TECHNIQUE_HARD 0u

#define GROUP_SIZE 8u

struct CameraData {   // std140 uniform block
    mat4 viewProj;    // world -> clip (reverse-Z, y flipped)
    mat4 invViewProj; // clip -> world
    vec4 position;    // xyz: camera position
    uvec4 imageSize;  // x width, y height, z light count
    vec4 composite;   // x ambient, y shadow intensity
    vec4 background;  // rgb: colour of pixels with no geometry
};

struct LightData {       // std430 storage buffer, one per scene light
    mat4 shadowMatrix;   // world -> (u, v, depth) * w: T x light view-projection
    vec4 positionType;   // xyz position (spot, point), w: LIGHT_* type
    vec4 directionRange; // xyz direction the light travels, w range (0 = unlimited)
    vec4 colorIntensity; // rgb linear colour, a intensity
    vec4 cone;           // x cos(outer), y cos(inner), z texel world size, w shadow layer (-1 none)
    vec4 bias;           // x constant, y slope, z normal offset (texels), w 1 if perspective
};

struct ShadowPush { // push constants of shadow_depth.vert
    mat4 viewProj;
    vec4 bias; // x: constant depth offset
};

struct VisibilityPush { // push constants of visibility.comp
    uvec4 light;        // x light index, y shadow layer, z shadow-map size
};

#ifdef __cplusplus
static_assert(sizeof(CameraData) == 192 && offsetof(CameraData, position) == 128 &&
              offsetof(CameraData, imageSize) == 144 && offsetof(CameraData, background) == 176);
static_assert(sizeof(LightData) == 144 && offsetof(LightData, positionType) == 64 &&
              offsetof(LightData, cone) == 112 && offsetof(LightData, bias) == 128);
static_assert(sizeof(ShadowPush) == 80 && sizeof(VisibilityPush) == 16);
} // namespace penumbra::gpu
#endif

#endif
