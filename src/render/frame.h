#pragma once
// The images one render needs, sized for its options, and the recording of one frame:
// shadow passes -> G-buffer -> visibility (compute) -> composite (compute), design.md §2.
#include "core/light_space.h"
#include "pass_types.h"
#include "render/culling.h"
#include "render/pipelines.h"
#include "render/textures.h"
#include "shadows/technique.h"
#include "vk/resources.h"
#include "vk/timestamps.h"

#include <string_view>
#include <vector>

namespace penumbra::render {

// The triangles of one material, contiguous in the index buffer.
struct DrawBatch {
    uint32_t material;
    uint32_t firstIndex, indexCount;
    bool vertexColors; // some vertex's colour is not opaque white (else the G-buffer skips them)
};

// Indices are grouped by material, the alpha-tested materials last, so that the shadow pass
// draws every opaque caster in one call and only the alpha-tested ones per material.
struct GpuScene {
    vk::Buffer vertices, indices;
    vk::Buffer positions;          // the vertices' positions alone: the opaque casters' shadow pass
    std::vector<Cluster> clusters; // of the index buffer, for culling (render/culling.h)
    uint32_t indexCount = 0;
    uint32_t opaqueIndexCount = 0; // indices [0, opaqueIndexCount) have no alpha test
    std::vector<DrawBatch> batches;
    GpuTextures textures;
    struct Material {
        gpu::MaterialPush constants;
        GpuTextures::Binding texture; // the 1x1 white texture when it has none
        bool doubleSided;
    };
    std::vector<Material> materials; // per Scene::materials
};
GpuScene uploadScene(const vk::Context& ctx, const Scene& scene);

// A shadow view as the frame draws it: the light it belongs to and its projection. Its index is
// its layer in every map (ShadowViewData::texel.z).
struct ShadowView {
    uint32_t light; // index into the scene's lights
    LightProjection projection;
};

// One map of every shadow view: an array image with a layer per view (its array view is what the
// visibility pass reads), and a 2D view of each layer to render into or write in a post pass.
struct ViewMaps {
    vk::Image image;
    std::vector<vk::ImageViewHandle> layers;
    shadows::MapFormat format = shadows::MapFormat::Depth32;
    // A mipmapped map's level views, layer-major (levels[layer * mipLevels + level]); empty
    // when it has one level.
    std::vector<vk::ImageViewHandle> levels;
    VkImageView level(uint32_t layer, uint32_t mip) const {
        return levels[size_t{layer} * image.mipLevels + mip].get();
    }
};

struct FrameTargets {
    uint32_t width = 0, height = 0;
    vk::Image depth, normal, albedo; // G-buffer; depth is reverse-Z
    vk::Image visibility;            // R32F array, one layer per shadow-casting light
    vk::Image intermediates;         // RGBA32F array like visibility when the viewer asks for the
                             // technique's intermediate results (SPEC_INTERMEDIATES); else 1x1
    vk::Image color;                  // RGBA8, sRGB-encoded values
    vk::Image position, exportNormal; // RGBA32F, filled for readback only
    std::vector<ShadowView> views;
    ViewMaps shadowDepth;       // shadows::kDepthMap: D32_SFLOAT, the seeds' depth (near 0, far 1)
    std::vector<ViewMaps> maps; // the technique's own, as its module declares them
    vk::Image integerPlaceholder; // makeIntegerPlaceholder: TECH_TABLE when the filtered
                                  // map holds floats
    // Not owned: this frame's ring slot (FrameData, LightData[], ShadowViewData[], the
    // technique's parameter block) and the renderer's samplers.
    VkBuffer frame = VK_NULL_HANDLE, lights = VK_NULL_HANDLE, viewData = VK_NULL_HANDLE;
    VkBuffer params = VK_NULL_HANDLE;
    VkSampler nearest = VK_NULL_HANDLE, compare = VK_NULL_HANDLE;
    // Not owned: the scene's distance field (sdf; a placeholder otherwise) and its sampler.
    VkImageView field = VK_NULL_HANDLE;
    VkSampler fieldSampler = VK_NULL_HANDLE;

    // The map called `name` (kDepthMap or one of the module's).
    const ViewMaps& named(const shadows::TechniqueModule& module, std::string_view name) const;
};

// One visibility dispatch: a light with shadow views. Its kind and view count specialise the
// pipeline (SPEC_LIGHT_TYPE, SPEC_LIGHT_VIEWS).
struct LightDispatch {
    gpu::VisibilityPush push;
    uint32_t type;  // LIGHT_*
    uint32_t views; // how many, from push.light.w
};

struct FrameSettings {
    const shadows::TechniqueModule* technique;
    std::vector<shadows::SpecConstant> constants; // of the visibility pass, but the light's
    std::vector<LightDispatch> shadowLights;
    std::vector<shadows::SpecConstant> sceneLights; // shading.glsl's: sceneLightConstants
    bool fuseComposite;                             // the last visibility dispatch shades
    glm::mat4 cameraViewProj;                       // the G-buffer's, for culling
    float slopeBias;
    float constantBias;
    uint32_t shadowMapSize;
};

// The Vulkan format of a technique's map.
VkFormat formatOf(shadows::MapFormat format);
// A 1x1 RGBA32UI array image: what the visibility and probe passes bind at their integer-map
// binding when the technique filters a float map (every binding a shader uses must be written).
vk::Image makeIntegerPlaceholder(const vk::Context& ctx);
// A 1x1x2 R32F 3D image: what a pass that may trace the distance field binds at TECH_FIELD when
// no field is built.
vk::Image makeFieldPlaceholder(const vk::Context& ctx);
// What a pass that filters the technique's map binds: the float map (the depth map when the
// filtered map holds integers) and the integer one (the placeholder when it holds floats).
struct FilteredBindings {
    VkImageView floats, integers;
};
FilteredBindings filteredBindings(const FrameTargets& t, const shadows::TechniqueModule& module);

// An array image, one layer per shadow view, and a 2D view of each layer (of each level too
// when `mipmapped`: a full chain).
ViewMaps makeViewMaps(const vk::Context& ctx, shadows::MapFormat format, uint32_t size,
                      uint32_t views, VkImageUsageFlags usage, bool mipmapped = false);

// The technique's post passes over every view of `targets` (their inputs already filled, in
// kComputeSampled): what recordFrame runs after the shadow passes, for Renderer::probeTechnique.
void recordPostPasses(VkCommandBuffer cmd, FramePipelines& pipelines, FrameTargets& targets,
                      const shadows::TechniqueModule& technique);

void recordFrame(VkCommandBuffer cmd, FramePipelines& pipelines, const GpuScene& scene,
                 FrameTargets& targets, const FrameSettings& settings, vk::GpuTimer& timer);

// Fills position/exportNormal and copies colour, visibility, position and normal into
// `readback` (one host-visible buffer, in that order, tightly packed).
void recordReadback(VkCommandBuffer cmd, FramePipelines& pipelines, FrameTargets& targets,
                    VkBuffer readback);

} // namespace penumbra::render
