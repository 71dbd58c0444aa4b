#pragma once
// The frame's targets in one place: their names, what each one is (its declaration to the frame
// graph), the shadow views they hold a layer for, the readback buffer's layout (one struct that
// the pass writing it and SceneRenderer::render reading it both use) and what they all take in
// device memory (Renderer::check).
#include "core/light_space.h"
#include "render/resource_pool.h"
#include "shadows/layer.h"
#include "shadows/technique.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::render {

// Resource names of the frame graph.
namespace target {
inline constexpr std::string_view kGBufferDepth = "gbuffer.depth"; // reverse-Z, D32
inline constexpr std::string_view kGBufferNormal = "gbuffer.normal";
inline constexpr std::string_view kGBufferAlbedo = "gbuffer.albedo";
// Motion vectors (kMotionFormat), declared when something reads them (FrameSettings::motion).
inline constexpr std::string_view kGBufferMotion = "gbuffer.motion";
inline constexpr std::string_view kVisibility = "visibility";       // R32F, a layer per light
inline constexpr std::string_view kIntermediates = "intermediates"; // RGBA32F (1x1 unless asked)
inline constexpr std::string_view kScreenScratch = shadows::kScreenScratch; // R32F, as visibility
inline constexpr std::string_view kLayerResults = "layer.results"; // R32F (1x1 unless asked)
// The translucent layer's light per channel (RGBA32F, a layer per light;
// FrameSettings::translucent).
inline constexpr std::string_view kTranslucentColour = "translucent.colour";
inline constexpr std::string_view kColor = "color";                  // RGBA8, sRGB-encoded values
inline constexpr std::string_view kPosition = "export.position";     // RGBA32F, for the host
inline constexpr std::string_view kNormal = "export.normal";         // RGBA32F, for the host
inline constexpr std::string_view kFaceNormal = "export.faceNormal"; // RGBA32F, for the host
inline constexpr std::string_view kReadback = "readback";            // host-visible buffer
inline constexpr std::string_view kTraceList = "traceList"; // checkerboard.h's, for one light
inline constexpr std::string_view kIntegerPlaceholder = "placeholder.integer";
// What TECH_COMPARE holds for a technique that reads no depth map in its visibility pass.
inline constexpr std::string_view kDepthPlaceholder = "placeholder.depth";
inline constexpr std::string_view kField = "field"; // the distance field, or its placeholder
// The ring slot's uniform buffers (written by the host before the frame).
inline constexpr std::string_view kFrameBlock = "slot.frame";
inline constexpr std::string_view kLights = "slot.lights";
inline constexpr std::string_view kViews = "slot.views";
inline constexpr std::string_view kParams = "slot.params";
inline constexpr std::string_view kLayerParams = "slot.layerParams";
// Virtual maps: the physical pool (D32, persistent) and the slot's page table and requests.
inline constexpr std::string_view kVirtualPool = "virtual.pool";
// ... and with virtual.staticLayer, each page's static layer in the same place of a second pool.
inline constexpr std::string_view kStaticPool = "virtual.staticPool";
inline constexpr std::string_view kPageTable = "slot.pageTable";
inline constexpr std::string_view kPageRequests = "slot.pageRequests";
// The scene's vertex and positions buffers (GpuScene): the `skin` pass writes the skinned ones.
inline constexpr std::string_view kVertices = "scene.vertices";
inline constexpr std::string_view kPositions = "scene.positions";
// Where the vertices were in the last frame (GpuScene::previousPositions; the positions buffer in
// its place where they did not move).
inline constexpr std::string_view kPreviousPositions = "scene.previousPositions";
// A technique's map `name` of every shadow view: "shadow.depth", "shadow.moments", ...
std::string shadowMap(std::string_view name);
} // namespace target

// A shadow view as the frame draws it: the light it belongs to and its projection. Its index is
// its layer in every map (ShadowViewData::texel.z).
struct ShadowView {
    uint32_t light; // index into the scene's lights
    LightProjection projection;
};

VkFormat formatOf(shadows::MapFormat format);

// What a frame with this technique, these parameters and sizes declares of its targets: the
// depth map and the module's maps (a layer per view; with virtual.enabled, the physical pool in
// the depth map's place, one layer, its contents kept across frames), the G-buffer, visibility, the
// intermediates (full size for the viewer's `intermediates`, else 1x1), colour and the export
// images. The map declarations alone: shadowMapDecls; the maps kept with history are keyed by
// `views` (historyKeyOf).
std::vector<ImageDecl> shadowMapDecls(const shadows::TechniqueModule& module,
                                      const ParameterValues& params,
                                      std::span<const ShadowView> views);
std::vector<ImageDecl> screenDecls(bool intermediates);
// The static layers' pool (virtual.staticLayer on virtual maps), copied into the pool.
std::optional<ImageDecl> staticPoolDecl(const shadows::TechniqueModule& module,
                                        const ParameterValues& params);
// A layer's history (LayerModule::history; "layer.<name>.history"): a layer per shadow-casting
// light, kept while the technique and every parameter stay as they are (its key), whatever the
// camera does (the layer reprojects it).
ImageDecl layerHistoryDecl(const shadows::LayerModule& layer,
                           const shadows::TechniqueModule& technique,
                           const ParameterValues& params);
// The translucent layer's maps for its method (TRANSLUCENT_*, translucent.h), a layer per shadow
// view at the depth map's size: the coloured map's nearest and second nearest depths
// ("shadow.translucent.nearest", "second": D32), the nearest's transmittance and the product
// ("front", "product"); or the absorbance and the three channels' moments ("moments0" to "3").
std::vector<ImageDecl> translucentMapDecls(uint32_t method);
// Bound where the technique's filtered map holds floats (TECH_TABLE): never written, never read.
ImageDecl integerPlaceholderDecl();
// Bound at TECH_COMPARE for a technique that reads no depth map: never written, never read.
ImageDecl depthPlaceholderDecl();
// The invalidation key of the maps a technique keeps with history (MapDecl::history): the views'
// projections, so that last frame's version holds its contents only while every view projects
// as it did (a moved light or a re-fitted cascade drops it: its texels would lie elsewhere).
uint64_t historyKeyOf(std::span<const ShadowView> views);

// The readback buffer: colour, every visibility layer, position, normal, face normal and, with
// `motion`, the motion vectors, with `colour` the translucent layer's light per channel, tightly
// packed in that order.
struct ReadbackLayout {
    struct Part {
        std::string_view target;
        VkDeviceSize offset, bytes;
    };
    ReadbackLayout(uint32_t width, uint32_t height, uint32_t visibilityLayers, bool motion = false,
                   bool colour = false);
    Part color, visibility, position, normal, faceNormal;
    std::optional<Part> motion, colour;
    VkDeviceSize bytes;
    BufferDecl decl() const;
};

// Checkerboard tracing's list (checkerboard.h): its head, then room for every pixel it fills
// (traceListEntries: the odd pixels of the image).
uint32_t traceListEntries(uint32_t width, uint32_t height);
BufferDecl traceListDecl(uint32_t width, uint32_t height, bool checkerboard);

// Device memory the frame's targets take for these sizes (declared images, the readback buffer
// and the trace list): what Renderer::check compares with the device's.
struct TargetBytes {
    uint64_t shadowMaps, screen;
};
// `motion`: the frame makes motion vectors (FrameSettings::motion); the translucent layer's light
// per channel counts where the layer is on.
TargetBytes targetBytes(const shadows::TechniqueModule& module, const ParameterValues& params,
                        const FrameSizes& sizes, bool motion = false);

} // namespace penumbra::render
