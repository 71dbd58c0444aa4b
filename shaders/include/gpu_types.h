// Host/shader structs, compiled both as GLSL (glslc) and as C++ (with static_asserts on the
// std140/std430 layout), so the two sides cannot drift apart.
// clang-format off
#ifndef PENUMBRA_GPU_TYPES_H
#define PENUMBRA_GPU_TYPES_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <iterator>
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
#define TECHNIQUE_PCF 1u
#define TECHNIQUE_PCSS 2u
#define TECHNIQUE_SECOND_DEPTH 3u
#define TECHNIQUE_VSM 4u
#define TECHNIQUE_ESM 5u
#define TECHNIQUE_EVSM 6u
#define TECHNIQUE_SAVSM 7u
#define TECHNIQUE_MSM 8u
#define TECHNIQUE_VSSM 9u
#define TECHNIQUE_MSM_SOFT 10u
#define TECHNIQUE_SDF 11u

// Specialization-constant ids of visibility.comp and filter_probe.comp (the pipeline key is the
// list of (id, value) pairs: src/shadows/technique.h).
#define SPEC_TECHNIQUE 0
#define SPEC_FILTER 1
#define SPEC_RECEIVER 2
#define SPEC_HORIZON 3           // 1: the visibility pass applies bias.horizon
#define SPEC_LIGHT_TYPE 4        // the visibility dispatch's light: LIGHT_*
#define SPEC_LIGHT_VIEWS 5       // ... and how many shadow views it has
#define SPEC_SCENE_LIGHTS 6      // shading.glsl: the scene's lights (0: more than
                                 // MAX_SPECIALIZED_LIGHTS, counted at run time)
#define SPEC_SCENE_LIGHT_TYPES 7 // ... their LIGHT_* kinds, two bits each
#define SPEC_FUSED_COMPOSITE 8   // 1: this visibility dispatch (the last light's) also shades
#define MAX_SPECIALIZED_LIGHTS 16u
#define SPEC_CASCADE_BLEND 9     // 1: csm.blend > 0 (the blend band evaluates two cascades)
#define SPEC_MATERIAL_TEXTURE 10 // gbuffer.frag: MaterialPush::hasTexture ...
#define SPEC_MATERIAL_ALPHA_TEST 11 // ... and alphaTest, fixed per pipeline
#define SPEC_MATERIAL_VERTEX_COLOR 12 // 0: the batch's vertex colours are all opaque white
#define SPEC_ADAPTIVE_BIAS 13    // 1: bias.mode=adaptive (the visibility pass's receiver terms)
#define SPEC_INTERMEDIATES 15    // 1: the visibility pass also writes VIS_INTERMEDIATES (viewer)

// pcf.filter, pcf.rotation and bias.receiver: indices of their choices in the registry.
#define FILTER_BILINEAR 0u
#define FILTER_HARDWARE 1u
#define FILTER_BOX 2u
#define FILTER_GAUSSIAN 3u
#define FILTER_POISSON 4u
#define ROTATION_NONE 0u
#define ROTATION_RANDOM 1u
#define ROTATION_IGN 2u
#define RECEIVER_OFF 0u
#define RECEIVER_SCREEN 1u
#define RECEIVER_LIGHT 2u
#define BIAS_FIXED 0u             // bias.mode
#define BIAS_ADAPTIVE 1u
#define HORIZON_OFF 0u            // bias.horizon
#define HORIZON_SOFT 1u
#define HORIZON_ALL 2u

// Descriptor bindings (set 0, push descriptors) of every pass: the shaders declare
// `layout(binding = X)`, src/render/pipelines.cpp builds each pass's layout from the same names,
// src/render/frame.cpp writes them.
#define BIND_FRAME 0             // FrameData, in every pass that reads it
// Lights and shadow views reach the screen-space passes as uniform buffers, not storage
// buffers: lavapipe loads a storage buffer one lane at a time even at a uniform index, a uniform
// buffer with one scalar load (uniform index) or a vector gather. The blocks are declared at
// these capacities (64 KiB each at most, NVIDIA's and lavapipe's maxUniformBufferRange) and bound
// at the size used; a device with a smaller range holds fewer (render checks, error: otherwise).
#define MAX_UNIFORM_LIGHTS 512u  // 96 bytes each
#define MAX_UNIFORM_VIEWS 448u   // 144 bytes each
#define VIS_LIGHTS 1             // visibility.comp: LightData[], uniform
#define VIS_GBUFFER_DEPTH 2
#define VIS_GBUFFER_NORMAL 3
#define VIS_SHADOW_MAP 4         // the technique's filtered map, every view (nearest)
#define VIS_SHADOW_COMPARE 5     // the depth map, every view (comparison sampler)
#define VIS_OUT 6                // R32F array, a layer per shadow-casting light
#define VIS_VIEWS 7              // ShadowViewData[], uniform
#define VIS_SHADOW_TABLE 8       // the technique's filtered map when it holds integers (a
                                 // placeholder otherwise), every view (nearest)
#define VIS_FIELD 9              // the scene's distance field (sdf; a 1x1x2 placeholder
                                 // otherwise), trilinear
#define VIS_INTERMEDIATES 10     // RGBA32F array, a layer per shadow-casting light: the
                                 // technique's intermediate results (evaluateTechnique's yzw),
                                 // written with SPEC_INTERMEDIATES (a 1x1 placeholder otherwise)
#define VIS_GBUFFER_ALBEDO 11    // read and ...
#define VIS_COLOR 12             // ... written by a dispatch with SPEC_FUSED_COMPOSITE (RGBA8)
#define COMPOSITE_LIGHTS 1       // composite.comp: LightData[], uniform
#define COMPOSITE_GBUFFER_DEPTH 2
#define COMPOSITE_GBUFFER_NORMAL 3
#define COMPOSITE_GBUFFER_ALBEDO 4
#define COMPOSITE_VISIBILITY 5
#define COMPOSITE_OUT 6
#define EXPORT_GBUFFER_DEPTH 1   // export.comp
#define EXPORT_GBUFFER_NORMAL 2
#define EXPORT_POSITION 3
#define EXPORT_NORMAL 4
#define PROBE_RECEIVERS 1        // filter_probe.comp
#define PROBE_SHADOW_MAP 2
#define PROBE_SHADOW_COMPARE 3
#define PROBE_RESULTS 4
#define PROBE_VIEW 5
#define PROBE_SHADOW_TABLE 6
#define GBUFFER_TEXTURE 1        // gbuffer.frag: the material's base colour
#define MASK_TEXTURE 0           // shadow_mask.frag: the alpha-tested caster's texture
#define READ_MAP 0               // a technique's extra depth pass (shadow_peel.frag): the map
#define READ_TEXTURE 1           // it reads, and the caster's texture
#define FIELD_TRIANGLES 0        // the distance field's build passes (sdf_seed, sdf_flood,
#define FIELD_BRICK_STARTS 1     // sdf_resolve): FieldTriangle[], each brick's first entry in
#define FIELD_BRICK_LIST 2       // the brick list (one past the last brick: its end), the list
#define FIELD_IDS_IN 3           // of triangle indices; nearest-triangle ids (R32UI, 3D) read
#define FIELD_IDS_OUT 4          // and written; the field (R32F, 3D) written
#define FIELD_OUT 5
#define FIELD_BRICK 4u           // voxels per brick side
#define FIELD_NO_TRIANGLE 0xffffffffu
#define FIELD_OPEN 1u            // FieldTriangle flags: open geometry (thickness, no sign)
#define FIELD_FLIPPED 2u         // a closed surface wound inside out: its crossings count negated
#define FIELD_OUTLINE_AB 4u      // open geometry: the edge faces a hole (an alpha-tested piece
#define FIELD_OUTLINE_BC 8u      // whose neighbour across it was cut away), so the slab ends
#define FIELD_OUTLINE_CA 16u     // there; other edges continue into the next triangle

#define POISSON_MAX_SAMPLES 64u
#define MAX_CASCADES 8u           // csm.cascades' largest value (src/core/light_space.h)
#define GROUP_SIZE 8u

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

struct LightData {       // std430 storage buffer, one per scene light
    vec4 positionType;   // xyz position (spot, point), w: LIGHT_* type
    vec4 directionRange; // xyz direction the light travels, w range (0 = unlimited)
    vec4 colorIntensity; // rgb linear colour, a intensity
    vec4 cone;           // x cos(outer), y cos(inner), w visibility layer (-1: no shadow map)
    vec4 bias;           // x constant, y slope (both applied in the shadow pass), z normal offset
                         // (texels)
    uvec4 views;         // x first shadow view (ShadowViewData), y how many (0: no shadow map;
                         // 6 for a point light's cube faces, in cubeFace() order)
};

// One shadow view: a projection of a light into one layer of the technique's maps (a light may
// own several: cascades, cube faces).
struct ShadowViewData {  // std430 storage buffer, one per shadow view
    mat4 shadowMatrix;   // world -> (u, v, depth) * w: T x the view's view-projection
    vec4 frustum;        // x near, y far (view distance), zw world size of one uv unit
                         // (orthographic) or of one uv unit at unit distance (perspective)
    vec4 texel;          // x world size of a texel (perspective: at unit distance), y 1 if
                         // perspective, z the view's layer in the maps, w the light's size as
                         // this view sees it: radius (perspective) or tan(half angular diameter)
    vec4 cascade;        // x the camera view distance where this view's slice ends, y where it
                         // starts blending into the next view (both huge: not a cascade), z the
                         // kernel scale (the first cascade's texel size over this view's)
    vec4 moments;        // the part of the view's depth range the moment techniques spread
                         // their [0, 1] over (momentDepth), in the range's linear [0, 1]: from
                         // x to 1 - y (zero: the whole range)
    vec4 fromFirst;      // this view's (u, v) = xy * (u, v) of its light's first view + zw, the
                         // depth the same: a sun's cascades share one orientation and depth
                         // range (src/core/cascades.cpp), so the visibility pass maps the first
                         // cascade's receiver plane and footprint by xy (cascadeReceiver; it
                         // projects (u, v) itself, which rounds as the shadow pass does).
                         // (1, 1, 0, 0) for a light's first view.
};

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

// A shadow-map post pass samples its inputs at bindings POST_INPUT_BINDING + i and writes its
// outputs at POST_OUTPUT_BINDING + i (src/shadows/technique.h, PostPassDecl).
#define POST_INPUT_BINDING 0
#define POST_OUTPUT_BINDING 8
#define POST_MAX_MAPS 8
#define POST_FRAME_BINDING 16   // FrameData (the technique's parameters)
#define LINE_GROUP_SIZE 64u     // post passes dispatched one invocation per row or column
#define POST_VIEWS_BINDING 17   // ShadowViewData[], uniform; PostPassPush.size.z: the view

// A triangle of the distance field's build (src/shadows/sdf_input.h): its corners, and in a.w
// its FIELD_* flags (as float bits).
struct FieldTriangle {   // std430
    vec4 a, b, c;
};

struct FieldPush {       // push constants of the distance field's build passes
    vec4 origin;         // xyz the box's lowest corner, w a voxel's side
    uvec4 size;          // xyz voxels per axis, w the flood's step (sdf_flood)
    vec4 thickness;      // x: open geometry's half-thickness (world units)
};

struct PostPassPush {    // push constants of every shadow-map post pass
    uvec4 size;          // xy: the shadow map's size in texels, z: the view (ShadowViewData)
};

struct CasterPush {      // push constants of shadow_mask.frag and shadow_peel.frag
    ShadowPush shadow;
    MaterialPush material;
};

struct ProbeReceiver {   // std430, filter_probe.comp's input (Renderer::probeTechnique)
    vec4 uvDepth;        // u, v, receiver depth
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

// The viewer's display pass (shaders/viewer_display.comp, apps/viewer/display.cpp): what the
// window shows, from the frame's targets. DISPLAY_* modes, then bindings.
#define DISPLAY_SCENE 0u         // the lit image
#define DISPLAY_VISIBILITY 1u    // one light's visibility as grey
#define DISPLAY_SHADOW_MAP 2u    // one layer of the depth map, linear depth as grey, letterboxed
#define DISPLAY_CASCADES 3u      // the lit image tinted by the cascade each pixel reads
#define DISPLAY_OVERLAY 4u       // an image the host made (the error heat map)
#define DISPLAY_BLOCKER_DEPTH 5u // the average blocker's depth (PCSS, VSSM, MSM-soft) as grey
#define DISPLAY_PENUMBRA 6u      // the filter's radius in texels, as a colour ramp
#define DISPLAY_COLOR 0          // rgba8 storage, the lit image (technique A)
#define DISPLAY_COLOR_B 1        // rgba8 storage, technique B's (A's when there is no B)
#define DISPLAY_VISIBILITY_MAP 2 // sampler2DArray, a layer per shadow-casting light
#define DISPLAY_DEPTH_MAP 3      // sampler2DArray, the shadow depth map
#define DISPLAY_GBUFFER_DEPTH 4  // sampler2D, reverse-Z
#define DISPLAY_OVERLAY_IMAGE 5  // rgba8 storage, the host's image
#define DISPLAY_FRAME 6          // FrameData of the frame
#define DISPLAY_OUT 7            // rgba8 storage, what is presented
#define DISPLAY_INTERMEDIATES 8  // sampler2DArray, VIS_INTERMEDIATES

struct DisplayPush {     // push constants of viewer_display.comp
    uvec4 mode;          // x DISPLAY_*, y layer (visibility or depth map), z split column (A left
                         // of it, B from it on; >= width: A only), w cascades in `splits`
    vec4 depthRange;     // x near, y far, z 1: perspective (linearise), w the largest penumbra
                         // radius in texels (DISPLAY_PENUMBRA's scale)
    vec4 forward;        // xyz: the camera's unit view axis (cascade distances)
    vec4 splits[2];      // the cascades' far distances along the view axis, 8 at most
};

#ifdef __cplusplus
// The names of pcf.filter, pcf.rotation / pcss.rotation and bias.receiver, in the order of the
// values above: the registry's choice lists are these arrays, so a name's index is the value the
// shaders compare with.
inline constexpr const char* kFilterChoices[] = {"bilinear", "hardware", "box", "gaussian",
                                                 "poisson"};
inline constexpr const char* kRotationChoices[] = {"none", "random", "ign"};
inline constexpr const char* kReceiverChoices[] = {"off", "screen", "light"};
inline constexpr const char* kHorizonChoices[] = {"off", "soft", "all"};
inline constexpr const char* kBiasModeChoices[] = {"fixed", "adaptive"};
static_assert(BIAS_FIXED == 0 && BIAS_ADAPTIVE == 1 && std::size(kBiasModeChoices) == 2);
static_assert(FILTER_BILINEAR == 0 && FILTER_HARDWARE == 1 && FILTER_BOX == 2 &&
              FILTER_GAUSSIAN == 3 && FILTER_POISSON == 4 && std::size(kFilterChoices) == 5);
static_assert(ROTATION_NONE == 0 && ROTATION_RANDOM == 1 && ROTATION_IGN == 2 &&
              std::size(kRotationChoices) == 3);
static_assert(RECEIVER_OFF == 0 && RECEIVER_SCREEN == 1 && RECEIVER_LIGHT == 2 &&
              std::size(kReceiverChoices) == 3);
static_assert(HORIZON_OFF == 0 && HORIZON_SOFT == 1 && HORIZON_ALL == 2 &&
              std::size(kHorizonChoices) == 3);

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
static_assert(sizeof(LightData) == 96 && offsetof(LightData, cone) == 48 &&
              offsetof(LightData, bias) == 64 && offsetof(LightData, views) == 80);
static_assert(sizeof(ShadowViewData) == 144 && offsetof(ShadowViewData, frustum) == 64 &&
              offsetof(ShadowViewData, texel) == 80 && offsetof(ShadowViewData, cascade) == 96 &&
              offsetof(ShadowViewData, moments) == 112 &&
              offsetof(ShadowViewData, fromFirst) == 128);
static_assert(MAX_UNIFORM_VIEWS * sizeof(ShadowViewData) <= 65536 &&
              MAX_UNIFORM_LIGHTS * sizeof(LightData) <= 65536);
static_assert(sizeof(ShadowPush) == 80 && sizeof(VisibilityPush) == 16 &&
              sizeof(PostPassPush) == 16 && sizeof(ProbePush) == 16);
static_assert(sizeof(ProbeReceiver) == 64 && offsetof(ProbeReceiver, gradientPixel) == 16 &&
              offsetof(ProbeReceiver, footprint) == 32 && offsetof(ProbeReceiver, adaptive) == 48);
static_assert(sizeof(MaterialPush) == 32 && offsetof(MaterialPush, alphaCutoff) == 16);
static_assert(sizeof(FieldTriangle) == 48 && sizeof(FieldPush) == 48);
static_assert(sizeof(DisplayPush) == 80 && offsetof(DisplayPush, splits) == 48 &&
              MAX_CASCADES == 8u, "DisplayPush.splits holds MAX_CASCADES distances");
static_assert(sizeof(CasterPush) == 112 && offsetof(CasterPush, material) == 80);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
