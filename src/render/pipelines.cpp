#include "render/pipelines.h"

#include "gpu_types.h"
#include "penumbra/scene.h"

#include <cstddef>

namespace penumbra::render {
namespace {

constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;

constexpr VkShaderStageFlags kGraphicsStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

VkVertexInputAttributeDescription attribute(uint32_t location, VkFormat format, uint32_t offset) {
    return {.location = location, .binding = 0, .format = format, .offset = offset};
}

vk::GraphicsPipelineDesc shadowDesc(bool depthClamp, std::string_view fragment = {}) {
    return {.vertexShader = "shadow_depth.vert",
            .fragmentShader = fragment,
            .vertexStride = sizeof(Vertex),
            .attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)),
                           attribute(1, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)),
                           attribute(2, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color))},
            .depthFormat = kDepthFormat,
            .depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL,
            .depthClamp = depthClamp,
            .depthBias = true};
}

} // namespace

FramePipelines::FramePipelines(const vk::Context& context) : ctx(context) {
    static_assert(static_cast<uint32_t>(Technique::Hard) == TECHNIQUE_HARD &&
                  static_cast<uint32_t>(Technique::Pcf) == TECHNIQUE_PCF &&
                  static_cast<uint32_t>(Technique::Pcss) == TECHNIQUE_PCSS &&
                  static_cast<uint32_t>(Technique::SecondDepth) == TECHNIQUE_SECOND_DEPTH);
    shadowLayout =
        vk::createPipelineLayout(ctx, {}, VK_SHADER_STAGE_VERTEX_BIT, sizeof(gpu::ShadowPush));
    shadowMaskLayout = vk::createPipelineLayout(
        ctx, {{0, kSampled}}, kGraphicsStages, sizeof(gpu::ShadowPush) + sizeof(gpu::MaterialPush));
    gbufferLayout = vk::createPipelineLayout(ctx, {{0, kUniform}, {1, kSampled}}, kGraphicsStages,
                                             sizeof(gpu::MaterialPush));
    // Visibility and composite read the same inputs (camera, lights, four textures, one image
    // out), so they share one layout; only visibility uses the push constants.
    screenLayout =
        vk::createPipelineLayout(ctx,
                                 {{0, kUniform},
                                  {1, kStorage},
                                  {2, kSampled},
                                  {3, kSampled},
                                  {4, kSampled},
                                  {5, kSampled},
                                  {6, kImage}},
                                 VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::VisibilityPush));
    exportLayout = vk::createPipelineLayout(
        ctx, {{0, kUniform}, {1, kSampled}, {2, kSampled}, {3, kImage}, {4, kImage}},
        VK_SHADER_STAGE_COMPUTE_BIT, 0);

    probeLayout = vk::createPipelineLayout(
        ctx,
        {{0, kUniform}, {1, kStorage}, {2, kSampled}, {3, kSampled}, {4, kStorage}, {5, kStorage}},
        VK_SHADER_STAGE_COMPUTE_BIT, sizeof(glm::uvec4));

    peelLayout = vk::createPipelineLayout(ctx, {{0, kSampled}, {1, kSampled}}, kGraphicsStages,
                                          sizeof(gpu::ShadowPush) + sizeof(gpu::MaterialPush));
    midpointLayout = vk::createPipelineLayout(ctx, {{0, kSampled}, {1, kSampled}, {2, kImage}},
                                              VK_SHADER_STAGE_COMPUTE_BIT, sizeof(glm::uvec4));
    peelOrtho = vk::createGraphicsPipeline(ctx, peelLayout, shadowDesc(true, "shadow_peel.frag"));
    peelPerspective =
        vk::createGraphicsPipeline(ctx, peelLayout, shadowDesc(false, "shadow_peel.frag"));
    midpoint = vk::createComputePipeline(ctx, midpointLayout, "second_depth_mid.comp");
    shadowOrtho = vk::createGraphicsPipeline(ctx, shadowLayout, shadowDesc(true));
    shadowPerspective = vk::createGraphicsPipeline(ctx, shadowLayout, shadowDesc(false));
    shadowMaskOrtho =
        vk::createGraphicsPipeline(ctx, shadowMaskLayout, shadowDesc(true, "shadow_mask.frag"));
    shadowMaskPerspective =
        vk::createGraphicsPipeline(ctx, shadowMaskLayout, shadowDesc(false, "shadow_mask.frag"));
    gbuffer = vk::createGraphicsPipeline(
        ctx, gbufferLayout,
        {.vertexShader = "gbuffer.vert",
         .fragmentShader = "gbuffer.frag",
         .vertexStride = sizeof(Vertex),
         .attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)),
                        attribute(1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)),
                        attribute(2, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)),
                        attribute(3, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color))},
         .colorFormats = {kNormalFormat, kAlbedoFormat},
         .depthFormat = kDepthFormat,
         .depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL, // reverse-Z
         .dynamicCullMode = true});
    composite = vk::createComputePipeline(ctx, screenLayout, "composite.comp");
    exportGBuffer = vk::createComputePipeline(ctx, exportLayout, "export.comp");
}

VkPipeline FramePipelines::specialized(std::map<Key, vk::PipelineHandle>& cache,
                                       const vk::PipelineLayout& layout, std::string_view shader,
                                       const Key& key) {
    auto it = cache.find(key);
    if (it == cache.end()) {
        const auto [technique, filter, receiver] = key;
        const vk::SpecConstant constants[] = {
            {/* TECHNIQUE= */ 0, static_cast<uint32_t>(technique)},
            {/* FILTER= */ 1, filter},
            {/* RECEIVER= */ 2, receiver}};
        it = cache.emplace(key, vk::createComputePipeline(ctx, layout, shader, constants)).first;
    }
    return it->second.get();
}

VkPipeline FramePipelines::visibility(Technique technique, uint32_t filter, uint32_t receiver) {
    return specialized(mVisibility, screenLayout, "visibility.comp", {technique, filter, receiver});
}

VkPipeline FramePipelines::probe(Technique technique, uint32_t filter) {
    return specialized(mProbe, probeLayout, "filter_probe.comp", {technique, filter, 0});
}

} // namespace penumbra::render
