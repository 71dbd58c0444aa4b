// The translucent layer's passes (src/shadows/translucent.cpp, docs/translucency.md). In the
// LightSpace phase, after the light's depth map: every translucent caster drawn from each shadow
// view into the layer's maps, each fragment behind the depth map dropped (its shader reads the
// map). The coloured map takes three draws a view: the nearest surface's depth and transmittance
// (a depth test), the product of the transmittances (multiplicative blending, no depth test:
// every surface counts), then, in a pass of its own, the second nearest depth (a peel past the
// nearest); the moments one (additive blending into four maps). In the PerLight phase, one
// dispatch a light multiplies its visibility by what the maps let through at each pixel.
#include "render/frame.h"
#include "render/pass_utils.h"
#include "translucent.h"
#include "vk/pipelines.h"

#include <algorithm>
#include <array>

namespace penumbra::render {
namespace {

// Every translucent caster drawn from view `v` with `pipeline` into the attachments `info` names.
// `nearestDepth`: what TRANSLUCENT_NEAREST_DEPTH holds (the coloured map's nearest depths for its
// peel, else the light's depth map, unread).
void drawCasters(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene,
                 const FrameSettings& s, const FrameInputs& in, VkImageView opaqueDepth,
                 VkImageView nearestDepth, uint32_t v, VkPipeline pipeline,
                 const VkRenderingInfo& info) {
    vkCmdBeginRendering(cmd, &info);
    setViewport(cmd, info.renderArea.extent.width, info.renderArea.extent.height);
    const VkDeviceSize offset = 0;
    const VkBuffer vertices = scene.vertices.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, scene.indices.get(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    const vk::PipelineLayout& layout = p.translucentCasterLayout();
    const LightProjection& projection = s.views[v].projection;
    for (const DrawBatch& batch : scene.batches) {
        if (batch.firstIndex < scene.translucentFirstIndex)
            continue;
        const GpuScene::Material& material = scene.materials[batch.material];
        gpu::TranslucentCasterPush push = material.translucent;
        push.viewProj = projection.viewProj;
        push.bias.x = s.constantBias;
        push.flags.y = v;
        vk::PushDescriptors()
            .sampled(TRANSLUCENT_TEXTURE_BINDING, material.texture.view, material.texture.sampler)
            .sampled(TRANSLUCENT_TRANSMISSION_TEXTURE, material.transmissionTexture.view,
                     material.transmissionTexture.sampler)
            .sampled(TRANSLUCENT_OPAQUE_DEPTH, opaqueDepth, in.nearest)
            .sampled(TRANSLUCENT_NEAREST_DEPTH, nearestDepth, in.nearest)
            .uniformBuffer(TRANSLUCENT_VIEWS, in.views)
            .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout);
        vkCmdPushConstants(cmd, layout.get(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof push, &push);
        for (const IndexRange& r :
             visibleRanges(scene.clusters, batch.firstIndex, batch.casterIndexCount,
                           projection.viewProj, !projection.perspective, CasterSet::All))
            vkCmdDrawIndexed(cmd, r.count, 1, r.first, 0, 0);
    }
    vkCmdEndRendering(cmd);
}

VkRenderingInfo renderingInfo(const vk::Image& image, const VkRenderingAttachmentInfo* colors,
                              uint32_t colorCount, const VkRenderingAttachmentInfo* depth) {
    return {.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
            .renderArea = {{0, 0}, {image.width, image.height}},
            .layerCount = 1,
            .colorAttachmentCount = colorCount,
            .pColorAttachments = colors,
            .pDepthAttachment = depth};
}

} // namespace

bool drawnInDepthMap(const GpuScene& scene, const FrameSettings& s, const DrawBatch& batch) {
    return s.translucent == 0 || batch.firstIndex < scene.translucentFirstIndex;
}

void addTranslucentCasterPass(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                              const FrameSettings& s, const FrameInputs& in,
                              const FrameResources& r) {
    const std::vector<Use> common{{r.depthMap, Access::FragmentSampled},
                                  {r.views, Access::UniformRead},
                                  {r.vertices, Access::VertexRead}};
    const std::vector<ResourceId>& maps = r.translucentMaps;
    auto depthOf = [&](const PooledImage& image, uint32_t v) {
        return attachment(image.get(), {.depthStencil = {1.0f, 0}}, image.layer(v));
    };
    if (s.translucent == TRANSLUCENT_MOMENTS) {
        std::vector<Use> uses = common;
        for (ResourceId id : maps)
            uses.push_back({id, Access::ColorAttachment});
        graph.addPass(
            {.name = "translucent_maps",
             .cost = CostGroup::ShadowMaps,
             .phase = Phase::LightSpace,
             .uses = std::move(uses),
             .record = [&p, &scene, &s, &in, depthMap = r.depthMap, maps](PassContext& c) {
                 const VkImageView opaque = c.image(depthMap).view();
                 for (uint32_t v = 0; v < s.views.size(); ++v) {
                     std::array<VkRenderingAttachmentInfo, TRANSLUCENT_MAPS> colors{};
                     for (size_t i = 0; i < colors.size(); ++i)
                         colors[i] = attachment(c.image(maps[i]).get(),
                                                {.color = {{0.0f, 0.0f, 0.0f, 0.0f}}},
                                                c.image(maps[i]).layer(v));
                     drawCasters(c.cmd, p, scene, s, in, opaque, opaque, v,
                                 p.translucentCaster(TRANSLUCENT_DRAW_MOMENTS,
                                                     s.views[v].projection.perspective),
                                 renderingInfo(c.image(maps[0]).get(), colors.data(),
                                               TRANSLUCENT_MAPS, nullptr));
                 }
             }});
        return;
    }
    // The coloured map: the nearest depth with its transmittance, and the product; then the
    // second nearest depth, a peel that reads the nearest.
    const ResourceId nearest = maps.at(0), second = maps.at(1), front = maps.at(2),
                     product = maps.at(3);
    std::vector<Use> uses = common;
    uses.push_back({nearest, Access::DepthAttachment});
    uses.push_back({front, Access::ColorAttachment});
    uses.push_back({product, Access::ColorAttachment});
    graph.addPass({.name = "translucent_maps",
                   .cost = CostGroup::ShadowMaps,
                   .phase = Phase::LightSpace,
                   .uses = std::move(uses),
                   .record = [&p, &scene, &s, &in, depthMap = r.depthMap, nearest, front, product,
                              depthOf](PassContext& c) {
                       const VkImageView opaque = c.image(depthMap).view();
                       const PooledImage &nearestMap = c.image(nearest), &frontMap = c.image(front),
                                         &productMap = c.image(product);
                       const VkClearValue clear{.color = {{1.0f, 1.0f, 1.0f, 1.0f}}};
                       for (uint32_t v = 0; v < s.views.size(); ++v) {
                           const bool perspective = s.views[v].projection.perspective;
                           const VkRenderingAttachmentInfo depth = depthOf(nearestMap, v),
                                                           first = attachment(frontMap.get(), clear,
                                                                              frontMap.layer(v));
                           drawCasters(c.cmd, p, scene, s, in, opaque, opaque, v,
                                       p.translucentCaster(TRANSLUCENT_DRAW_NEAREST, perspective),
                                       renderingInfo(nearestMap.get(), &first, 1, &depth));
                           const VkRenderingAttachmentInfo all =
                               attachment(productMap.get(), clear, productMap.layer(v));
                           drawCasters(c.cmd, p, scene, s, in, opaque, opaque, v,
                                       p.translucentCaster(TRANSLUCENT_DRAW_PRODUCT, perspective),
                                       renderingInfo(productMap.get(), &all, 1, nullptr));
                       }
                   }});
    uses = common;
    uses.push_back({nearest, Access::FragmentSampled});
    uses.push_back({second, Access::DepthAttachment});
    graph.addPass({.name = "translucent_maps",
                   .cost = CostGroup::ShadowMaps,
                   .phase = Phase::LightSpace,
                   .uses = std::move(uses),
                   .record = [&p, &scene, &s, &in, depthMap = r.depthMap, nearest, second,
                              depthOf](PassContext& c) {
                       const VkImageView opaque = c.image(depthMap).view();
                       const VkImageView nearestView = c.image(nearest).view();
                       const PooledImage& secondMap = c.image(second);
                       for (uint32_t v = 0; v < s.views.size(); ++v) {
                           const VkRenderingAttachmentInfo depth = depthOf(secondMap, v);
                           drawCasters(c.cmd, p, scene, s, in, opaque, nearestView, v,
                                       p.translucentCaster(TRANSLUCENT_DRAW_SECOND,
                                                           s.views[v].projection.perspective),
                                       renderingInfo(secondMap.get(), nullptr, 0, &depth));
                       }
                   }});
}

void addTranslucentLayerPass(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                             const FrameInputs& in, const FrameResources& r,
                             const shadows::LayerModule& layer) {
    const size_t index = shadows::layerIndex(layer);
    // The coloured map: its two depths, the nearest's transmittance and the product (again in the
    // last two slots); the moments: the absorbance in the depths' places (unread).
    const bool coloured = s.translucent == TRANSLUCENT_COLOURED;
    const std::vector<ResourceId>& own = r.translucentMaps;
    const ResourceId nearest = own.at(0), second = coloured ? own.at(1) : own.at(0);
    std::array<ResourceId, TRANSLUCENT_MAPS> maps{};
    for (size_t i = 0; i < maps.size(); ++i)
        maps[i] = coloured ? own.at(std::min<size_t>(2 + i, 3)) : own.at(i);
    std::vector<Use> uses{{r.frame, Access::UniformRead},
                          {r.lights, Access::UniformRead},
                          {r.views, Access::UniformRead},
                          {r.layerParams, Access::UniformRead},
                          {r.gbufferDepth, Access::ComputeSampled},
                          {r.visibility, Access::ComputeReadWrite},
                          {r.translucentColour, Access::ComputeWrite}};
    for (ResourceId id : r.translucentMaps)
        uses.push_back({id, Access::ComputeSampled});
    graph.addPass(
        {.name = std::string(layer.name),
         .cost = CostGroup::PerPixel,
         .phase = Phase::PerLight,
         .uses = std::move(uses),
         .record = [&p, &s, &in, r, nearest, second, maps, index](PassContext& c) {
             std::array<VkImageView, TRANSLUCENT_MAPS> views{};
             for (size_t i = 0; i < maps.size(); ++i)
                 views[i] = c.image(maps[i]).view();
             const vk::PipelineLayout& layout = p.translucentLayerLayout();
             vk::PushDescriptors()
                 .uniformBuffer(BIND_FRAME, in.frame)
                 .uniformBuffer(LAYER_LIGHTS, in.lights)
                 .sampled(LAYER_GBUFFER_DEPTH, c.image(r.gbufferDepth).view(), in.nearest)
                 .storageImage(LAYER_VISIBILITY, c.image(r.visibility).view())
                 .storageImage(TRANSLUCENT_LAYER_COLOUR, c.image(r.translucentColour).view())
                 .uniformBuffer(LAYER_PARAMS, in.layerParams, TECHNIQUE_BLOCK_BYTES * index,
                                TECHNIQUE_BLOCK_BYTES)
                 .uniformBuffer(TRANSLUCENT_LAYER_VIEWS, in.views)
                 .sampled(TRANSLUCENT_LAYER_NEAREST, c.image(nearest).view(), in.nearest)
                 .sampled(TRANSLUCENT_LAYER_SECOND, c.image(second).view(), in.nearest)
                 .sampled(TRANSLUCENT_LAYER_MAPS, views, in.nearest)
                 .push(p.ctx, c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout);
             for (const LightDispatch& light : s.shadowLights) {
                 vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                   p.translucentLayer({{SPEC_LIGHT_TYPE, light.type},
                                                       {SPEC_LIGHT_VIEWS, light.views},
                                                       {SPEC_TRANSLUCENT_METHOD, s.translucent}}));
                 vkCmdPushConstants(c.cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                    sizeof light.push, &light.push);
                 vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(s.sizes.height), 1);
             }
         }});
}

} // namespace penumbra::render
