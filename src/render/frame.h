#pragma once
// One frame as a render graph (render/frame_graph.h; docs/architecture.md): buildFrame declares its
// targets and adds its passes phase by phase; each pass lives in the file of its phase:
//   LightSpace   shadow_passes.cpp   the light's depth per shadow view, the technique's own
//                                    depth passes and its post passes
//   GBuffer      screen_passes.cpp   the camera's G-buffer
//   PerLight     light_passes.cpp    per shadow-casting light: the base technique (visibility),
//                                    then each enabled layer (contact shadows)
//   Composite    light_passes.cpp    shading from every light's visibility, fused into the last
//                                    light's visibility dispatch when it has no layers
//   Readback     screen_passes.cpp   position and normal exported, everything copied for the
//                                    host (the last frame of a render only)
#include "render/frame_graph.h"
#include "render/frame_targets.h"
#include "render/pipelines.h"
#include "render/scene_upload.h"
#include "shadows/layer.h"

#include <glm/glm.hpp>

#include <vector>

namespace penumbra::render {

// One shadow-casting light's evaluation: its kind and view count specialise the visibility
// pipeline (SPEC_LIGHT_TYPE, SPEC_LIGHT_VIEWS).
struct LightDispatch {
    gpu::VisibilityPush push;
    uint32_t type;  // LIGHT_*
    uint32_t views; // how many, from push.light.w
    bool sized;     // the light has a size (Light::hasSize)
};

class PageDecisionPasses;
class PageDrawPasses;
// Virtual maps' pages decided on the device: the passes, the frame's slot of their host-written
// inputs, and the pool's pages a side.
struct DevicePages {
    PageDecisionPasses* decisions;
    PageDrawPasses* draws;
    uint32_t slot;
    uint32_t poolPagesPerSide;
};

// Virtual maps: a page to render this frame, its projection (pageViewProj) and its texels'
// first corner in the pool (and in the static pool); with virtual.staticLayer, whether the
// static pool holds its static layer already (else it is drawn first).
struct PageDraw {
    glm::mat4 viewProj;
    bool perspective;
    glm::uvec2 origin;
    bool staticHeld = false;
};
// Everything the frame's passes need to know but the host-filled buffers hold.
struct FrameSettings {
    const shadows::TechniqueModule* technique;
    const ParameterValues* params;
    std::vector<shadows::SpecConstant> constants; // of the visibility pass, but the light's
    std::vector<LightDispatch> shadowLights;
    std::vector<const shadows::LayerModule*> layers; // run after the base technique, in order
    // The translucent layer's method (TRANSLUCENT_*) where it runs: its maps are drawn and the
    // depth map leaves the translucent casters out (0: it does not run; the scene has none).
    uint32_t translucent = 0;
    std::vector<shadows::SpecConstant> sceneLights; // shading.glsl's: the scene's lights
    bool fuseComposite;       // composite.fused: the last light's base dispatch shades (no layers)
    bool intermediates;       // the viewer's: the technique's and layers' intermediate results
    bool readback;            // the frame ends with the readback passes
    bool present = false;     // ... or hands its outputs to the caller's passes (FrameOutputs)
    bool motion = false;      // the G-buffer writes motion vectors (read back with `readback`)
    glm::mat4 cameraViewProj; // the G-buffer's, for culling
    float slopeBias, constantBias;
    FrameSizes sizes;
    std::vector<ShadowView> views; // every shadow view, in layer order
    // Virtual maps (virtual.enabled): the views are levels of virtual maps, the depth map the
    // pool; the pages the host decided to render this frame (filled after the graph is planned,
    // before it records), a page's side.
    bool virtualMaps = false;
    uint32_t pageSize = 0;
    const std::vector<PageDraw>* pages = nullptr;
    // Pages decided on the device (virtual.deviceDecides): the decisions and the page draws run
    // in the ScreenSpace phase after the marking, in this frame's commands; `pages` is unused.
    const DevicePages* devicePages = nullptr;
};

// What the frame reads but does not declare: this frame's ring slot (written by the host), the
// distance field (or its stand-in) and the renderer's samplers.
struct FrameInputs {
    VkBuffer frame, lights, views, params, layerParams;
    VkBuffer pageTable, pageRequests;         // virtual maps' (a small stand-in table otherwise)
    VkBuffer pageRenderList = VK_NULL_HANDLE; // pages decided on the device: what to render
    const vk::Image* field;
    VkSampler nearest, compare, fieldSampler;
};

// The maps a pass that evaluates the technique binds (shadows::visibilitySlots): TECH_MAP's
// slots and TECH_TABLE's.
struct FilteredBindings {
    std::array<ResourceId, TECH_MAX_MAPS> floats{}, integers{};
    ResourceId compare = 0; // TECH_COMPARE: the depth map, or its placeholder where none is read
    // What unused slots hold: integer slots, and TECH_COMPARE for a technique that reads no
    // depth map (shadows::VisibilitySlots::readsDepthMap).
    struct Placeholders {
        ResourceId integers, depth;
    };
    // `named`: the resource of a map by its name (kDepthMap too); null: the depth map alone,
    // in every float slot and at TECH_COMPARE (virtual maps' page pool, the probe of a map
    // given whole).
    static FilteredBindings of(const shadows::TechniqueModule& module,
                               const ParameterValues& params, ResourceId depthMap,
                               Placeholders placeholders,
                               const std::function<ResourceId(std::string_view)>& named);
    // Every slot written, at TECH_MAP, TECH_TABLE and TECH_COMPARE (`compareSampler`).
    void write(vk::PushDescriptors& descriptors, const PassContext& c, VkSampler nearest,
               VkSampler compareSampler) const;
    // Every slot, sampled by compute.
    void addUses(std::vector<Use>& uses) const;
};

// What a frame that presents leaves for the caller's own passes (the viewer's display pass):
// colour in storage (general) layout, written by compute; the others sampled by compute.
struct FrameOutputs {
    const vk::Image *color, *visibility, *depthMap, *gbufferDepth, *intermediates, *layerResults;
    VkBuffer frame; // the frame block
};

// The frame's resources, by role, as declared in one graph.
struct FrameResources {
    ResourceId depthMap = 0;
    ResourceId staticPool = 0;    // virtual.staticLayer's (0: none)
    std::vector<ResourceId> maps; // the technique's own, in its module's order
    // Last frame's version of each of its own maps declared with history (MapDecl::history).
    std::vector<std::optional<ResourceId>> previousMaps;
    ResourceId gbufferDepth = 0, gbufferNormal = 0, gbufferAlbedo = 0;
    ResourceId gbufferMotion = 0; // FrameSettings::motion's (0: none)
    // Per entry of FrameSettings::layers: its history, this frame's and last frame's (0: none).
    std::vector<ResourceId> layerHistory, layerHistoryPrevious;
    ResourceId visibility = 0, intermediates = 0, layerResults = 0, color = 0;
    ResourceId screenScratch = 0; // shadows::kScreenScratch (0: no screen pass binds it)
    ResourceId position = 0, normal = 0, faceNormal = 0, readback = 0;
    ResourceId integerPlaceholder = 0, depthPlaceholder = 0, field = 0;
    FilteredBindings filtered{};
    ResourceId frame = 0, lights = 0, views = 0, params = 0, layerParams = 0;
    ResourceId pageTable = 0, pageRequests = 0, pageRenderList = 0;
    ResourceId traceList = 0; // checkerboard tracing's (a head alone when it does not run)
    ResourceId vertices = 0, positions = 0; // the scene's, which every draw reads (VertexRead)
    ResourceId previousPositions = 0;       // what the G-buffer's motion vectors read
    // The translucent layer's maps (translucentMapDecls; FrameSettings::translucent), empty when
    // it does not run.
    std::vector<ResourceId> translucentMaps;
    ResourceId translucentColour = 0; // its light per channel, a layer per light (0: none)
    // The map a module calls `name` (shadows::kDepthMap or one of its own).
    // `<name> (previous)`: last frame's version of a map declared with history.
    ResourceId named(const shadows::TechniqueModule& module, std::string_view name) const;
    // The map whose last frame's version `id` is (one of previousMaps); nullopt for any other.
    std::optional<ResourceId> currentOf(ResourceId id) const;
    // Declares the technique's own maps (shadowMapDecls past the depth map's), with last
    // frame's versions of those with history.
    void declareOwnMaps(FrameGraph& graph, const shadows::TechniqueModule& module,
                        std::span<const ImageDecl> decls);
};

// What a pass that draws the casters into the light's depth map declares: the map as its depth
// attachment, the vertices and positions it reads (the light's depth pass, the pages' draws).
inline std::vector<Use> casterDrawUses(const FrameResources& r) {
    return {{r.depthMap, Access::DepthAttachment},
            {r.vertices, Access::VertexRead},
            {r.positions, Access::VertexRead}};
}

// The screen passes the technique adds under these settings (shadows::ScreenPassDecl): a
// checkerboard's fill left out with the viewer's intermediates, which want every pixel traced.
std::vector<shadows::ScreenPassDecl> screenPassesOf(const FrameSettings& s);

// Declares every target and input of a frame with these settings.
FrameResources declareFrame(FrameGraph& graph, const FrameSettings& s, const FrameInputs& in);

// The whole frame, phase by phase.
FrameResources buildFrame(FrameGraph& graph, FramePipelines& pipelines, const GpuScene& scene,
                          const FrameSettings& settings, const FrameInputs& inputs);

// The phases' passes (each file's own).
// The `skin` pass (GpuScene::Skin): the skinned vertices placed for this pose.
void addSkinPass(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                 const FrameResources& r);
void addShadowPasses(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                     const FrameSettings& s, const FrameInputs& in, const FrameResources& r);
void addPostPasses(FrameGraph& graph, FramePipelines& p, const shadows::TechniqueModule& module,
                   const ParameterValues& params, uint32_t views, const FrameInputs& in,
                   const FrameResources& r);
void addGBufferPass(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                    const FrameSettings& s, const FrameInputs& in, const FrameResources& r);
// One page of a virtual map rendered into its place in the pool (shadow_passes.cpp): `set`'s
// casters; CasterSet::Dynamic's over what the page holds.
void renderPageDepth(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene,
                     const PooledImage& pool, const PageDraw& page, uint32_t pageSize,
                     const FrameSettings& s, VkSampler nearest, CasterSet set = CasterSet::All);
// Virtual maps: each page the host decided on rendered into the pool (LightSpace), and each
// light's page marking after the G-buffer (ScreenSpace), both timed as "shadow".
void addVirtualPagePasses(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                          const FrameSettings& s, const FrameInputs& in, const FrameResources& r);
void addLightPasses(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                    const FrameInputs& in, const FrameResources& r);
// The translucent layer (translucent_passes.cpp): its casters drawn into its maps from every
// view (LightSpace, timed as "translucent_maps" with the shadow maps), and its pass for every light
// (PerLight, timed under the layer's name).
void addTranslucentCasterPass(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                              const FrameSettings& s, const FrameInputs& in,
                              const FrameResources& r);
void addTranslucentLayerPass(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                             const FrameInputs& in, const FrameResources& r,
                             const shadows::LayerModule& layer);
// Whether the light's depth map draws this batch: every one, but the translucent casters' when
// the translucent layer runs.
bool drawnInDepthMap(const GpuScene& scene, const FrameSettings& s, const DrawBatch& batch);
void addReadbackPasses(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                       const FrameInputs& in, const FrameResources& r);
// The hand-off of a frame that presents: its outputs in FrameOutputs' states.
void addPresentPass(FrameGraph& graph, const FrameResources& r);

// A 1x1x2 R32F 3D image: what a pass that may trace the distance field binds at TECH_FIELD when
// no field is built.
vk::Image makeFieldPlaceholder(const vk::Context& ctx);

} // namespace penumbra::render
