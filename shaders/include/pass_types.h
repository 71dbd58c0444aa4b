// Push constants and storage records of the frame's passes (shadow, G-buffer, post passes,
// visibility, the filter probe, the distance field's build), compiled as GLSL and as C++ with
// static_asserts on their layout.
// clang-format off
#ifndef PENUMBRA_PASS_TYPES_H
#define PENUMBRA_PASS_TYPES_H
#include "shared_prelude.h"

#define FIELD_BRICK 4u           // voxels per brick side
#define FIELD_NO_TRIANGLE 0xffffffffu
#define FIELD_OPEN 1u            // FieldTriangle flags: open geometry (thickness, no sign)
#define FIELD_FLIPPED 2u         // a closed surface wound inside out: its crossings count negated
#define FIELD_OUTLINE_AB 4u      // open geometry: the edge faces a hole (an alpha-tested piece
#define FIELD_OUTLINE_BC 8u      // whose neighbour across it was cut away), so the slab ends
#define FIELD_OUTLINE_CA 16u     // there; other edges continue into the next triangle

PENUMBRA_GPU_BEGIN
struct ShadowPush {      // push constants of shadow_depth.vert
    mat4 viewProj;
    vec4 bias;           // x: constant depth offset
};

// A material as one draw sees it: push constants of gbuffer.frag and, after ShadowPush (see
// CasterPush), of the alpha-tested shadow passes and of a technique's extra depth passes.
struct MaterialPush {
    vec4 baseColor;      // linear RGBA factor
    float alphaCutoff;
    uint alphaTest;      // 1: coverage below alphaCutoff is a hole
    uint hasTexture;     // 0: the material has no texture (a 1x1 white one is bound)
    uint pad;
};

// A triangle of the distance field's build (src/shadows/sdf_input.h): its corners, and in a.w
// its FIELD_* flags (as float bits).
struct FieldTriangle {   // std430
    vec4 a, b, c;
};

struct FieldPush {       // push constants of the distance field's build passes
    vec4 origin;         // xyz the box's lowest corner, w a voxel's side
    uvec4 size;          // xyz voxels per axis, w the first z of this dispatch's slab
    vec4 thickness;      // x: open geometry's half-thickness (world units)
};

struct PostPassPush {    // push constants of every shadow-map post pass
    uvec4 size;          // xy: the shadow map's size in texels, z: the view (ShadowViewData),
                         // w: a mip chain's level; else bit i set where input i is last
                         // frame's version of a map and holds last frame's contents (clear:
                         // zeros; docs/architecture.md, "History")
};

struct CasterPush {      // push constants of shadow_mask.frag and shadow_peel.frag
    ShadowPush shadow;
    MaterialPush material;
};

struct ProbeReceiver {   // std430, filter_probe.comp's input (Renderer::probeTechnique)
    vec4 uvDepth;        // u, v, receiver depth, Receiver::creaseLimit
    vec4 gradientPixel;  // d depth / du, d depth / dv, pixel x, pixel y (rotations use it)
    vec4 footprint;      // xy: d uv / d pixel x, zw: d uv / d pixel y (vsm.filter=mip)
    vec4 adaptive;       // bias.mode=adaptive's per-tap terms: xy Receiver::curve, zw
                         // Receiver::planeRange (zeros with zw = (-1e30, 1e30): none)
};

struct ProbePush {       // push constants of filter_probe.comp
    uvec4 counts;        // x receivers, y shadow-map size
};

struct VisibilityPush {  // push constants of visibility.comp
    uvec4 light;         // x light index, y its visibility layer, z shadow-map size, w its first
                         // view (the shader picks the view of each pixel: lightViewOf)
};

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(ShadowPush) == 80 && sizeof(VisibilityPush) == 16 &&
              sizeof(PostPassPush) == 16 && sizeof(ProbePush) == 16);
static_assert(sizeof(ProbeReceiver) == 64 && offsetof(ProbeReceiver, gradientPixel) == 16 &&
              offsetof(ProbeReceiver, footprint) == 32 && offsetof(ProbeReceiver, adaptive) == 48);
static_assert(sizeof(MaterialPush) == 32 && offsetof(MaterialPush, alphaCutoff) == 16);
static_assert(sizeof(FieldTriangle) == 48 && sizeof(FieldPush) == 48);
static_assert(sizeof(CasterPush) == 112 && offsetof(CasterPush, material) == 80);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
