#pragma once
// Renderer: owns a Vulkan device and renders a Scene with one shadow technique, returning the lit
// image, per-light visibility and the G-buffer's world position and normal, plus GPU time per
// pass. Headless; the same frame (docs/architecture.md) serves the CLI, the tests and the viewer.
#include "penumbra/scene.h"
#include "penumbra/settings.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

// Vulkan's own handle types, for a window system's presentation test and a caller that records
// frames into its own command buffers (no vulkan.h here).
struct VkInstance_T;
struct VkPhysicalDevice_T;
struct VkCommandBuffer_T;

namespace penumbra {

namespace vk {
class Context;  // src/vk/context.h
class GpuTimer; // src/vk/timestamps.h
} // namespace vk
namespace render {
struct FrameOutputs; // src/render/frame.h
} // namespace render

struct DeviceOptions {
    int deviceIndex = -1;    // -1: a GPU when there is one, else the software rasterizer
    bool validation = false; // Khronos validation layer + debug messenger that counts errors
    // A window to present to (the viewer): the instance extensions its window system needs, and
    // whether a queue family of a device can present to it. A device whose queue cannot, or that
    // lacks VK_KHR_swapchain, is unsuitable. Unset: headless.
    std::vector<std::string> instanceExtensions;
    std::function<bool(VkInstance_T*, VkPhysicalDevice_T*, uint32_t queueFamily)> canPresent;
};

struct DeviceInfo {
    uint32_t index = 0;
    std::string name, type, driverName, driverInfo, apiVersion;
    uint32_t maxImageDimension2D = 0;
    uint32_t maxComputeWorkGroupInvocations = 0;
    uint32_t maxStorageBufferRange = 0; // bytes a storage buffer binding may hold
    uint64_t deviceLocalBytes = 0;
    float timestampPeriodNs = 0.0f;
    bool depthLinearFilter = false;     // D32_SFLOAT linear (and hardware 2x2 PCF) filtering
    uint32_t subTexelPrecisionBits = 0; // bits a filter keeps of a texel's sub-position
    float maxSamplerAnisotropy = 0;     // 0: no anisotropic filtering (the feature is missing)
    bool imageCubeArray = false;        // cube-map arrays (point lights' shadow views)
    bool suitable = false;              // has everything Penumbra needs
    std::string unsuitableReason;
};

struct DeviceMemoryUse {
    uint64_t allocations = 0;
    uint64_t bytes = 0;
};

// What a pass's time counts towards, as its pass declares it (docs/cli.md, "GPU time"): the
// shadow maps (the depth passes, what is filtered from them, virtual pages), the technique's
// per-pixel work (its visibility dispatch, its visibility filter, the layers, the composite it
// may be fused into), or the frame around the technique (the G-buffer: the same for every one).
enum class CostGroup { ShadowMaps, PerPixel, Frame };
// Its key in metrics.json's and stats.json's "gpu_ms_by_cost".
constexpr std::string_view costGroupName(CostGroup group) {
    return group == CostGroup::ShadowMaps ? "shadow_maps"
           : group == CostGroup::PerPixel ? "per_pixel"
                                          : "frame";
}

struct PassTime {
    std::string pass; // "shadow", "gbuffer", "visibility", "composite"
    CostGroup cost = CostGroup::ShadowMaps;
    double medianMs = 0.0;
    std::vector<double> frameMs; // every timed frame
};

// One shadow view of a light (a layer of the shadow maps): its projection.
struct ShadowViewInfo {
    std::string name;       // "" for a light's only view; "+x", "-x", ... for cube faces;
                            // "cascade" for a sun's cascades
    uint32_t layer = 0;     // its layer in the shadow maps
    std::string projection; // "orthographic" / "perspective"
    float nearPlane = 0.0f, farPlane = 0.0f;
    float texelWorldSize = 0.0f; // at unit distance for perspective
    float fovDegrees = 0.0f;     // perspective: the full field of view (cube faces: 90 + guard)
    // A sun's cascade: the slice of the camera's view distance it serves (from splitNear, with
    // the previous cascade's blend, to splitFar), where it starts blending into the next, and
    // its kernel scale (the first cascade's texel size over its own).
    bool cascade = false;
    float splitNear = 0.0f, splitFar = 0.0f, blendStart = 0.0f, kernelScale = 1.0f;
    glm::mat4 worldToShadow{1.0f}; // T x view-projection: world -> (u, v, depth) * w
};

struct LightShadow {
    uint32_t sceneLight = 0;           // index into Scene::lights
    int visibilityIndex = -1;          // index into RenderResult::visibility; -1: casts no shadow
    std::string projection;            // "orthographic" / "perspective" / "cube" / "none"
    std::vector<ShadowViewInfo> views; // empty when it casts no shadow
    uint32_t guardTexels = 0;          // cube faces: texels beyond 90 degrees on each side
};

// The distance field a render traced (sdf): its grid, memory and what building it cost. A
// SceneRenderer builds it once per scene and field setting; `built` says whether this render did.
struct DistanceFieldInfo {
    glm::uvec3 voxels{0u};
    float voxelSize = 0.0f;            // world units
    glm::vec3 origin{0.0f};            // the box's lowest corner
    uint64_t bytes = 0;                // the field (R32F)
    uint32_t triangles = 0;            // the scene's
    uint32_t fieldTriangles = 0;       // what the field was built from: alpha-tested ones cut
    uint32_t openTriangles = 0;        // of those, unsigned, with sdf.thickness
    uint32_t alphaTriangles = 0;       // the scene's alpha-tested triangles
    uint32_t alphaPieces = 0;          // the covered pieces they were cut into
    double buildGpuMs = 0.0;           // its three compute passes
    std::vector<PassTime> buildPasses; // each: sdf_seed, sdf_flood, sdf_resolve
    double buildCpuMs = 0.0;           // the triangle lists
    bool built = false;
};

// Virtual shadow maps (virtual.enabled): the page cache over a render's frames. The counts are
// the last frame's: its requests are those of the frame before it (the host reads them back
// after each frame), the pages it rendered those that were not resident.
struct VirtualMapInfo {
    uint32_t requested = 0; // distinct pages asked for
    uint32_t resident = 0;  // in the pool after the frame's allocation
    uint32_t rendered = 0;  // rendered in the last frame
    uint32_t cached = 0;    // of the requested, resident already
    // Of the rendered, those whose static layer the static pool held (virtual.staticLayer): only
    // the dynamic casters were drawn into them.
    uint32_t staticHeld = 0;
    uint32_t dropped = 0;   // asked for but the pool was full (pixels read coarser pages)
    uint32_t evicted = 0;   // resident pages given to others, least recently used first
    uint32_t poolPages = 0; // the pool's capacity
    uint64_t poolBytes = 0, tableBytes = 0;
    uint32_t pageSize = 0, virtualSize = 0;
    float levelBias = 0.0f; // the level bias the image read with (VirtualSettings::levelBias)
    std::vector<uint32_t> renderedPerFrame; // every frame's, the warm-up first
    uint32_t droppedFrames = 0;             // frames whose pool was too small for their view
};

// A virtual page as the debug views show it (SceneRenderer::virtualPages).
enum class PageState : uint8_t {
    Absent,   // not in the pool
    Kept,     // in the pool, not asked for by the last frame
    Cached,   // asked for, and in the pool before the frame
    Rendered, // asked for, and rendered by the frame
    Dropped,  // asked for, but the pool was full: its pixels read a coarser page
};

// The last frame's virtual pages: every level's page table and what the pool holds.
struct VirtualPages {
    struct Level {
        uint32_t light = 0, face = 0, level = 0; // scene light, cube face, 0 the finest
        uint32_t pagesPerSide = 0;
        std::vector<PageState> pages; // row by row, the window's page (0, 0) first
    };
    std::vector<Level> levels;
    // Per physical page, row by row: the index in `levels` of the level it holds a page of; -1
    // free, -2 a page of no level this frame shows (a sun's window has moved past it).
    std::vector<int32_t> poolOwner;
    std::vector<uint8_t> poolRendered; // 1: rendered by the last frame
    uint32_t poolPagesPerSide = 0;
    VirtualMapInfo info;
};

// The frame's transient images (per-frame, never handed out of the frame): what they would take
// each in memory of its own, and what they take placed to share memory where the passes that
// use them do not overlap (docs/architecture.md, "Transient memory").
struct TransientMemory {
    uint64_t separateBytes = 0, sharedBytes = 0;
};

struct RenderResult {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> image;                 // RGBA8, sRGB-encoded, rows top to bottom
    std::vector<std::vector<float>> visibility; // per shadow-casting light; NaN = background
    std::vector<float> position;                // xyz per pixel, world space; NaN = background
    std::vector<float> normal;                  // xyz per pixel, unit; NaN = background
    std::vector<float> faceNormal; // xyz per pixel: the triangle's own unit normal; NaN as above
    // With RenderOptions::motion: xyz per pixel, x and y where the surface is minus where it was
    // in the last frame this renderer drew (pixels, x right, y down), z its depth then (NDC,
    // reverse-Z); NaN as above. Zero motion on a first frame, after a cut, and for a frame of
    // the same pose and camera as the one before.
    std::vector<float> motion;
    // With the translucent layer on a scene with translucent casters, per shadow-casting light:
    // the light that arrives per channel (linear RGB, 3 floats a pixel; NaN = background), of which
    // `visibility` is the luminance (Rec. 709), as ReferenceResult::transmittance. Empty otherwise.
    std::vector<std::vector<float>> transmittance;
    std::vector<PassTime> passes;
    std::vector<LightShadow> lights;
    std::optional<DistanceFieldInfo> field;    // sdf only
    std::optional<VirtualMapInfo> virtualMaps; // virtual.enabled only
    float exposure = 0.0f; // EV the image was shaded with: composite.exposure, else automatic
    TransientMemory transientMemory;
};

using ProgressFn = std::function<void(const std::string& stage)>;

// A receiver for Renderer::probeTechnique: where it reads the shadow map, its light depth, its
// receiver-plane gradient (d depth / d uv; zero for none), its pixel (rotations use it) and its
// pixel's footprint in the map (the uv's change across one pixel along x and y; vsm.filter=mip).
struct FilterProbe {
    glm::vec2 uv{0.0f};
    float depth = 0.0f;
    glm::vec2 gradient{0.0f};
    glm::uvec2 pixel{0u};
    glm::vec2 uvDx{0.0f}, uvDy{0.0f};
    // bias.mode=adaptive's per-tap terms (bias.h, tapDepth): the curvature lift and the
    // receiver's own range for the plane's correction.
    glm::vec2 curve{0.0f};
    glm::vec2 planeRange{-1e30f, 1e30f};
    float creaseLimit = 0.0f; // the crease rule's steepest plane, d depth / d uv (0: off)
};

// The light behind a probed shadow map, for techniques that need its geometry (PCSS).
struct ProbeLight {
    bool perspective = false;
    float size = 0.0f;                       // radius (perspective) or tan(half angular diameter)
    float nearPlane = 0.0f, farPlane = 1.0f; // light view distances of depth 0 and 1
    glm::vec2 worldPerUv{1.0f}; // world size of one uv unit (at unit distance if perspective)
    bool cubeFace = false;      // a point light's cube face (perspective): the soft members'
                                // kernels take their cubeRadius cap
    // Tests of what the visibility pass binds: 1 returns, instead of the technique, the texel
    // under each receiver of the four float map slots (TECH_MAP), 2 of the four integer ones
    // (TECH_TABLE, their bits as floats), 3 the four channels of the first integer one (a
    // summed-area table's sums, as float bits).
    uint32_t readSlots = 0;
};

class SceneRenderer;

class Renderer {
public:
    // Throws InputError("--device", ...) for a bad index or a device lacking what we need.
    explicit Renderer(const DeviceOptions& options);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const DeviceInfo& device() const;
    // Throws InputError on options this device cannot honour (sizes past its limits, memory)
    // or a scene it cannot draw. render() calls it first; callers may call it earlier.
    void check(const Scene& scene, const RenderOptions& options) const;
    RenderResult render(const Scene& scene, const RenderOptions& options,
                        const ProgressFn& progress = {});
    // Evaluates `technique` with `parameters` at each probe on the square shadow map `depths`
    // (size x size, rows top to bottom) with the visibility pass's own shader code: how the
    // CPU references in src/reference are checked against the GPU. x: visibility; yzw: the
    // technique's intermediate results (PCSS: average blocker depth, blocking texels, filter
    // radius in texels; VSM: the filtered moments, the receiver's moment depth); a technique with
    // post passes (VSM's moments and blur) runs them on the map first.
    std::vector<glm::vec4> probeTechnique(Technique technique, const ParameterValues& parameters,
                                          std::span<const float> depths, uint32_t size,
                                          std::span<const FilterProbe> probes,
                                          const ProbeLight& light = {});
    // Validation-layer messages of severity error so far (0 when validation is off).
    uint32_t validationErrors() const;
    // Device memory Penumbra holds right now in this process (every Renderer together): its
    // allocations and their bytes. Flat over a long run once every size has been seen.
    DeviceMemoryUse deviceMemoryInUse() const;
    // Every validation-layer message so far, warnings and performance warnings included.
    uint32_t validationMessages() const;
    // The Vulkan context (src/vk/context.h): for a caller that records its own passes around
    // the frame and submits them (the viewer's swapchain and display pass).
    const vk::Context& context() const;

private:
    friend class SceneRenderer;
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// A scene uploaded once to a Renderer's device. It renders any number of frames with any
// technique, parameters, light sizes, camera and image or shadow-map size without uploading the
// scene again; its targets are kept while the sizes and the technique's shadow maps stay the
// same. Per-frame data (camera, lights, settings) lives in a ring of buffers, so a frame can be
// recorded while the previous one is still in flight. Renderer::render is one SceneRenderer
// rendering once; `compare` renders every row with one.
class SceneRenderer {
public:
    // Drops invalid triangles (the rule the ground truth applies) and uploads the rest; throws
    // InputError when none are left. `renderer` must outlive this.
    SceneRenderer(Renderer& renderer, const Scene& scene);
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // The scene as uploaded (invalid triangles dropped).
    const Scene& scene() const;
    // Throws InputError on options this device cannot honour for this scene.
    void check(const RenderOptions& options) const;
    RenderResult render(const RenderOptions& options, const ProgressFn& progress = {});
    // One frame of a path (compare --camera-path): the camera, and the lights' directions and
    // sizes, changed from the scene's; the lights keep their count, order and positions.
    // `shadowCamera`: the camera the shadow views (cascades) are fitted to, when it is not the
    // one that draws the frame (shimmer: this frame's pixels under the previous frame's views).
    struct FrameState {
        std::optional<Camera> camera;
        std::optional<std::vector<Light>> lights;
        std::optional<Camera> shadowCamera;
        // The view jumped (a camera cut): last frame's versions of every history resource hold
        // nothing from this frame on (a temporal pass starts again rather than blend across it).
        bool cut = false;
        // This frame follows the last one render() drew, in the same ring slot and with no
        // warm-up frames, so that what the technique kept from it shows (a virtual map's pages
        // asked for a frame ago): a scene in motion, frame by frame, after repose().
        bool continues = false;
    };
    RenderResult render(const RenderOptions& options, const FrameState& state,
                        const ProgressFn& progress = {});
    // The same scene at another time (issue 59): its vertices, lights and cameras moved, its
    // materials and textures the same. Where only skinned vertices moved, only this pose's joint
    // matrices go up and the next frame's `skin` pass places them; else the geometry is
    // uploaded again (textures are kept); the
    // targets, history and the last frame's page requests are kept, as an engine keeps them
    // while things move; every cached virtual page is dropped, since nothing yet says which
    // pages a moved caster touched. Throws InputError when no valid triangle is left, or when
    // `posed` has other materials, textures or lights than the scene uploaded.
    void repose(const Scene& posed);
    // Frees the device memory of what no later frame reads: the per-frame targets and maps,
    // which the next frame makes again (on a device where first use costs, lavapipe, that frame's
    // GPU time shows it). What the technique keeps across frames stays: history, a virtual map's
    // page pool and cache. For a caller holding many renderers between frames (compare
    // --timeline's rows in motion, when together they pass the device's local memory).
    void trim();
    // The vertex and positions buffers as the device holds them now, in Scene::vertices' order:
    // skinned vertices where the last frame's `skin` pass placed them (in bind space before the
    // first frame). For tests and debugging; waits for the device.
    struct DeviceGeometry {
        std::vector<Vertex> vertices;
        std::vector<glm::vec3> positions; // what the opaque casters' shadow pass draws
        // Where the vertices were in the frame before the last pose moved them (the motion
        // vectors' source); empty until a pose moves something.
        std::vector<glm::vec3> previousPositions;
    };
    DeviceGeometry deviceGeometry() const;
    // The pages of the last frame that read virtual maps (empty levels before one).
    VirtualPages virtualPages() const;
    // The distance field the last sdf render traced, x fastest, then y, then z (empty before
    // one); `info` gets its grid.
    std::vector<float> distanceField(DistanceFieldInfo& info) const;

    // One frame recorded into the caller's command buffer, for a caller that submits frames
    // itself (the viewer: frames in flight, presentation). `slot`: a ring slot the caller knows
    // the frame that used it last has completed; `timer` is read after the frame's fence;
    // `intermediates`: the technique's and the layers' intermediate results too. The frame hands
    // its outputs over for the caller's own passes (render::FrameOutputs: colour in storage
    // layout, the rest sampled), valid until the next frame is recorded. Remaking targets or the
    // distance field waits for the device to go idle.
    struct RecordedFrame {
        RenderResult result; // lights, views and distance field; no pixels, no times
        const render::FrameOutputs* outputs;
    };
    RecordedFrame record(VkCommandBuffer_T* commandBuffer, const RenderOptions& options,
                         const FrameState& state, size_t slot, vk::GpuTimer& timer,
                         bool intermediates, const ProgressFn& progress = {});

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// Every physical device the Vulkan loader reports, with the reason any one is unsuitable.
std::vector<DeviceInfo> listDevices();

} // namespace penumbra
