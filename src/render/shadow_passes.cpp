// The LightSpace phase (render/frame.h): the light's depth per shadow view, the technique's own
// depth passes (a peel), and its post passes over every view. Each is a graph pass that declares
// the maps it reads and writes; the graph places the barriers, over all the views' layers at
// once.
#include "pass_types.h"
#include "render/frame.h"
#include "render/pass_utils.h"
#include "vk/pipelines.h"
#include "vk/sync.h"

#include <algorithm>

namespace penumbra::render {
namespace {

void bindGeometry(VkCommandBuffer cmd, const GpuScene& scene) {
    const VkDeviceSize offset = 0;
    const VkBuffer vertices = scene.vertices.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
    vkCmdBindIndexBuffer(cmd, scene.indices.get(), 0, VK_INDEX_TYPE_UINT32);
}

// The layer of a map that a technique's extra depth pass reads, and the pipeline that reads it.
struct ReadMap {
    VkImageView layer;
    VkPipeline pipeline;
};

// One depth pass of the scene from a light (world -> clip `viewProj`) into layer `layer` of
// `target`, over `area` (the whole layer when null), cleared to the far plane first, with the
// hardware slope bias and the constant bias of the vertex shader. Opaque casters go in one draw;
// alpha-tested ones per material with their texture, and so do translucent ones, unless the
// translucent layer draws them into maps of their own (drawnInDepthMap). `reads` set: a technique's
// extra depth pass (a depth peel), which draws every caster with its pipeline, the read map's layer
// at binding 0. `set`: the clusters drawn; CasterSet::Dynamic draws over what the area holds,
// uncleared.
void renderLightDepth(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene,
                      const PooledImage& target, uint32_t layer, const glm::mat4& viewProj,
                      bool perspective, const FrameSettings& s, const ReadMap* reads,
                      VkSampler nearest, const VkRect2D* area = nullptr,
                      CasterSet set = CasterSet::All) {
    const vk::Image& image = target.get();
    VkRenderingAttachmentInfo depth =
        attachment(image, {.depthStencil = {1.0f, 0}}, target.layer(layer));
    if (set == CasterSet::Dynamic)
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    const VkRect2D rect = area ? *area : VkRect2D{{0, 0}, {image.width, image.height}};
    const VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                               .renderArea = rect,
                               .layerCount = 1,
                               .pDepthAttachment = &depth};
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport{.x = static_cast<float>(rect.offset.x),
                              .y = static_cast<float>(rect.offset.y),
                              .width = static_cast<float>(rect.extent.width),
                              .height = static_cast<float>(rect.extent.height),
                              .minDepth = 0.0f,
                              .maxDepth = 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &rect);
    bindGeometry(cmd, scene);
    gpu::CasterPush push{.shadow = {.viewProj = viewProj, .bias = {s.constantBias, 0, 0, 0}}};
    auto bind = [&](VkPipeline pipeline) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdSetDepthBias(cmd, 0.0f, 0.0f, s.slopeBias);
    };
    auto draw = [&](uint32_t first, uint32_t count) { // what the view may show of it
        for (const IndexRange& r :
             visibleRanges(scene.clusters, first, count, viewProj, !perspective, set))
            vkCmdDrawIndexed(cmd, r.count, 1, r.first, 0, 0);
    };
    constexpr VkShaderStageFlags kStages =
        VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    if (reads) {
        bind(reads->pipeline);
        auto pushFor = [&](const GpuTextures::Binding& texture) {
            vk::PushDescriptors()
                .sampled(READ_MAP, reads->layer, nearest)
                .sampled(READ_TEXTURE, texture.view, texture.sampler)
                .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.readingDepthLayout);
            vkCmdPushConstants(cmd, p.readingDepthLayout.get(), kStages, 0, sizeof push, &push);
        };
        if (scene.opaqueIndexCount > 0) {
            pushFor(scene.textures.white());
            draw(0, scene.opaqueIndexCount);
        }
        for (const DrawBatch& batch : scene.batches)
            if (batch.firstIndex >= scene.opaqueIndexCount && drawnInDepthMap(scene, s, batch)) {
                const GpuScene::Material& material = scene.materials[batch.material];
                push.material = material.constants;
                pushFor(material.texture);
                draw(batch.firstIndex, batch.indexCount);
            }
    } else {
        if (scene.opaqueIndexCount > 0) {
            bind(perspective ? p.shadowPerspective.get() : p.shadowOrtho.get());
            const VkDeviceSize offset = 0;
            const VkBuffer positions = scene.positions.get();
            vkCmdBindVertexBuffers(cmd, 0, 1, &positions, &offset);
            vkCmdPushConstants(cmd, p.shadowLayout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0,
                               sizeof push.shadow, &push.shadow);
            draw(0, scene.opaqueIndexCount);
            bindGeometry(cmd, scene); // the masked casters read whole vertices
        }
        if (scene.indexCount > scene.opaqueIndexCount)
            bind(perspective ? p.shadowMaskPerspective.get() : p.shadowMaskOrtho.get());
        for (const DrawBatch& batch : scene.batches)
            if (batch.firstIndex >= scene.opaqueIndexCount && drawnInDepthMap(scene, s, batch)) {
                const GpuScene::Material& material = scene.materials[batch.material];
                vk::PushDescriptors()
                    .sampled(MASK_TEXTURE, material.texture.view, material.texture.sampler)
                    .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.shadowMaskLayout);
                push.material = material.constants;
                vkCmdPushConstants(cmd, p.shadowMaskLayout.get(), kStages, 0, sizeof push, &push);
                draw(batch.firstIndex, batch.indexCount);
            }
    }
    vkCmdEndRendering(cmd);
}

std::string timestampOf(std::string_view shader) {
    return std::string(shader.substr(0, shader.rfind('.')));
}

// A PostDispatch::MipChain pass: levels 1.. of `map`, each from the level above, one level at a
// time over every view. The graph leaves the whole chain sampled before it; each level goes to
// storage for its dispatch and back.
void recordMipChain(VkCommandBuffer cmd, FramePipelines& p, const PooledImage& map,
                    const shadows::PostPassDecl& pass, uint32_t views, const FrameInputs& in) {
    const vk::Image& image = map.get();
    const vk::PipelineLayout& layout = p.postPassLayout(1, 1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                      p.postPass(pass.shader, 1, std::array{image.format}));
    for (uint32_t level = 1; level < image.mipLevels; ++level) {
        const uint32_t size = std::max(image.width >> level, 1u);
        vk::imageBarrier(cmd, image, vk::kComputeSampled, vk::kComputeWrite, level, 1);
        for (uint32_t v = 0; v < views; ++v) {
            vk::PushDescriptors writes;
            writes.sampled(POST_INPUT_BINDING, map.level(v, level - 1), in.nearest)
                .storageImage(POST_OUTPUT_BINDING, map.level(v, level))
                .uniformBuffer(TECH_PARAMS, in.params)
                .uniformBuffer(POST_VIEWS_BINDING, in.views);
            writes.push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout);
            const gpu::PostPassPush push{.size = {size, size, v, level}};
            vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                               &push);
            vkCmdDispatch(cmd, groups(size), groups(size), 1);
        }
        vk::imageBarrier(cmd, image, vk::kComputeWrite, vk::kComputeSampled, level, 1);
    }
}

// A Texels or Lines post pass over every view: inputs sampled, outputs written.
void recordPostPass(VkCommandBuffer cmd, FramePipelines& p, const shadows::PostPassDecl& pass,
                    const std::vector<const PooledImage*>& inputs,
                    const std::vector<const PooledImage*>& outputs, uint32_t heldHistory,
                    uint32_t views, const FrameInputs& in) {
    const auto inputCount = static_cast<uint32_t>(inputs.size());
    const auto outputCount = static_cast<uint32_t>(outputs.size());
    const vk::PipelineLayout& layout = p.postPassLayout(inputCount, outputCount);
    std::vector<VkFormat> formats;
    for (const PooledImage* output : outputs)
        formats.push_back(output->get().format);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                      p.postPass(pass.shader, inputCount, formats));
    const vk::Image& size = outputs.front()->get();
    for (uint32_t v = 0; v < views; ++v) {
        vk::PushDescriptors writes;
        for (uint32_t i = 0; i < inputCount; ++i)
            writes.sampled(POST_INPUT_BINDING + i, inputs[i]->layer(v), in.nearest);
        for (uint32_t i = 0; i < outputCount; ++i)
            writes.storageImage(POST_OUTPUT_BINDING + i, outputs[i]->layer(v));
        writes.uniformBuffer(TECH_PARAMS, in.params).uniformBuffer(POST_VIEWS_BINDING, in.views);
        writes.push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout);
        const gpu::PostPassPush push{.size = {size.width, size.height, v, heldHistory}};
        vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        if (pass.dispatch == shadows::PostDispatch::Lines)
            vkCmdDispatch(cmd, (size.height + LINE_GROUP_SIZE - 1) / LINE_GROUP_SIZE, 1, 1);
        else
            vkCmdDispatch(cmd, groups(size.width), groups(size.height), 1);
    }
}

} // namespace

void renderPageDepth(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene,
                     const PooledImage& pool, const PageDraw& page, uint32_t pageSize,
                     const FrameSettings& s, VkSampler nearest, CasterSet set) {
    const VkRect2D area{{static_cast<int32_t>(page.origin.x), static_cast<int32_t>(page.origin.y)},
                        {pageSize, pageSize}};
    renderLightDepth(cmd, p, scene, pool, 0, page.viewProj, page.perspective, s, nullptr, nearest,
                     &area, set);
}

void addShadowPasses(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                     const FrameSettings& s, const FrameInputs& in, const FrameResources& r) {
    const shadows::TechniqueModule& technique = *s.technique;
    // The light's own depth pass, every view; the technique's depth passes count as "shadow" too.
    graph.addPass({.name = "shadow",
                   .cost = CostGroup::ShadowMaps,
                   .phase = Phase::LightSpace,
                   .uses = casterDrawUses(r),
                   .record = [&p, &scene, &s, &in, map = r.depthMap](PassContext& c) {
                       for (uint32_t v = 0; v < s.views.size(); ++v)
                           renderLightDepth(
                               c.cmd, p, scene, c.image(map), v, s.views[v].projection.viewProj,
                               s.views[v].projection.perspective, s, nullptr, in.nearest);
                   }});
    for (const shadows::DepthPassDecl& pass : technique.depthPasses) {
        const ResourceId read = r.named(technique, pass.reads);
        const ResourceId target = r.named(technique, pass.target);
        graph.addPass({.name = "shadow",
                       .cost = CostGroup::ShadowMaps,
                       .phase = Phase::LightSpace,
                       .uses = {{read, Access::FragmentSampled},
                                {target, Access::DepthAttachment},
                                {r.vertices, Access::VertexRead}},
                       .record = [&p, &scene, &s, &in, pass, read, target](PassContext& c) {
                           for (uint32_t v = 0; v < s.views.size(); ++v) {
                               const bool perspective = s.views[v].projection.perspective;
                               const ReadMap reads{
                                   c.image(read).layer(v),
                                   p.readingDepthPass(pass.fragmentShader, perspective)};
                               renderLightDepth(c.cmd, p, scene, c.image(target), v,
                                                s.views[v].projection.viewProj, perspective, s,
                                                &reads, in.nearest);
                           }
                       }});
    }
    if (!s.views.empty())
        addPostPasses(graph, p, technique, *s.params, static_cast<uint32_t>(s.views.size()), in, r);
}

void addPostPasses(FrameGraph& graph, FramePipelines& p, const shadows::TechniqueModule& module,
                   const ParameterValues& params, uint32_t views, const FrameInputs& in,
                   const FrameResources& r) {
    const ResourceId block = r.params, viewRecords = r.views;
    for (const shadows::PostPassDecl& pass : module.postPasses) {
        if (pass.dispatch == shadows::PostDispatch::MipChain) {
            const ResourceId map = r.named(module, pass.outputs.at(0));
            bool chain = false; // the parameters may keep one level: nothing to fill
            for (const shadows::MapDecl& decl : module.maps)
                chain = chain ||
                        (decl.name == pass.outputs.at(0) && shadows::mipmappedOf(decl, params));
            if (!chain || graph.sizes().shadowMapSize < 2)
                continue;
            graph.addPass({.name = timestampOf(pass.shader),
                           .cost = CostGroup::ShadowMaps,
                           .phase = Phase::LightSpace,
                           .uses = {{map, Access::ComputeSampled},
                                    {block, Access::UniformRead},
                                    {viewRecords, Access::UniformRead}},
                           .record = [&p, &in, pass, map, views](PassContext& c) {
                               recordMipChain(c.cmd, p, c.image(map), pass, views, in);
                           }});
            continue;
        }
        std::vector<Use> uses{{block, Access::UniformRead}, {viewRecords, Access::UniformRead}};
        std::vector<ResourceId> inputs, outputs;
        std::vector<std::pair<uint32_t, ResourceId>> histories; // input i: last frame's of id
        for (std::string_view name : pass.inputs) {
            const ResourceId id = r.named(module, name);
            if (const std::optional<ResourceId> current = r.currentOf(id))
                histories.emplace_back(static_cast<uint32_t>(inputs.size()), *current);
            uses.push_back({inputs.emplace_back(id), Access::ComputeSampled});
        }
        for (std::string_view name : pass.outputs)
            uses.push_back({outputs.emplace_back(r.named(module, name)), Access::ComputeWrite});
        graph.addPass(
            {.name = timestampOf(pass.shader),
             .cost = CostGroup::ShadowMaps,
             .phase = Phase::LightSpace,
             .uses = std::move(uses),
             .record = [&p, &in, pass, inputs, outputs, histories, views](PassContext& c) {
                 uint32_t held = 0; // PostPassPush::size.w
                 for (const auto& [input, current] : histories)
                     if (c.graph.historyValid(current))
                         held |= 1u << input;
                 std::vector<const PooledImage*> in_, out;
                 for (ResourceId id : inputs)
                     in_.push_back(&c.image(id));
                 for (ResourceId id : outputs)
                     out.push_back(&c.image(id));
                 recordPostPass(c.cmd, p, pass, in_, out, held, views, in);
             }});
    }
}

} // namespace penumbra::render
