#include "render/frame.h"

#include "bindings.h"
#include "moments.h"
#include "pass_types.h"
#include "penumbra/error.h"
#include "vk/sync.h"

#include <algorithm>
#include <span>

namespace penumbra::render {
namespace {

uint32_t groups(uint32_t n) {
    return (n + GROUP_SIZE - 1) / GROUP_SIZE;
}

void setViewport(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
    const VkViewport viewport{.x = 0,
                              .y = 0,
                              .width = static_cast<float>(width),
                              .height = static_cast<float>(height),
                              .minDepth = 0,
                              .maxDepth = 1};
    const VkRect2D scissor{.offset = {0, 0}, .extent = {width, height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

VkRenderingAttachmentInfo attachment(const vk::Image& image, VkClearValue clear,
                                     VkImageView view = VK_NULL_HANDLE) {
    return {.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
            .imageView = view ? view : image.view.get(),
            .imageLayout = image.aspect == VK_IMAGE_ASPECT_DEPTH_BIT
                               ? VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL
                               : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
            .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
            .clearValue = clear};
}

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

// One depth pass of the scene from a light into layer `layer` of `target` (cleared to the far
// plane, already in kDepthWrite), with the hardware slope bias and the constant bias of the vertex
// shader. Opaque casters go in one draw; alpha-tested ones per material with their texture.
// `reads` set: a technique's extra depth pass (a depth peel), which draws every caster with its
// pipeline, the read map's layer at binding 0.
void renderLightDepth(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene,
                      const ViewMaps& target, uint32_t layer, const ShadowView& view,
                      const FrameSettings& s, const ReadMap* reads, VkSampler nearest) {
    const vk::Image& image = target.image;
    const VkRenderingAttachmentInfo depth =
        attachment(image, {.depthStencil = {1.0f, 0}}, target.layers[layer].get());
    const VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                               .renderArea = {{0, 0}, {image.width, image.height}},
                               .layerCount = 1,
                               .pDepthAttachment = &depth};
    vkCmdBeginRendering(cmd, &info);
    setViewport(cmd, image.width, image.height);
    bindGeometry(cmd, scene);
    const bool perspective = view.projection.perspective;
    gpu::CasterPush push{
        .shadow = {.viewProj = view.projection.viewProj, .bias = {s.constantBias, 0, 0, 0}}};
    auto bind = [&](VkPipeline pipeline) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdSetDepthBias(cmd, 0.0f, 0.0f, s.slopeBias);
    };
    auto draw = [&](uint32_t first, uint32_t count) { // what the view may show of it
        for (const IndexRange& r :
             visibleRanges(scene.clusters, first, count, view.projection.viewProj, !perspective))
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
            if (batch.firstIndex >= scene.opaqueIndexCount) {
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
            if (batch.firstIndex >= scene.opaqueIndexCount) {
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

// The light's depth pass for every shadow view, then the technique's own depth passes; every
// barrier covers all the views' layers at once.
void recordShadowPasses(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene,
                        FrameTargets& t, const FrameSettings& s) {
    const shadows::TechniqueModule& technique = *s.technique;
    std::vector<const ViewMaps*> depthMaps{&t.shadowDepth};
    for (size_t m = 0; m < technique.maps.size(); ++m)
        if (technique.maps[m].format == shadows::MapFormat::Depth32)
            depthMaps.push_back(&t.maps[m]);
    vk::Barriers toDepthWrite;
    for (const ViewMaps* map : depthMaps)
        toDepthWrite.image(map->image, vk::kUndefined, vk::kDepthWrite);
    toDepthWrite.record(cmd);
    for (uint32_t v = 0; v < t.views.size(); ++v)
        renderLightDepth(cmd, p, scene, t.shadowDepth, v, t.views[v], s, nullptr, t.nearest);
    for (const shadows::DepthPassDecl& pass : technique.depthPasses) {
        const ViewMaps& read = t.named(technique, pass.reads);
        vk::imageBarrier(cmd, read.image, vk::kDepthWrite, vk::kFragmentSampled);
        for (uint32_t v = 0; v < t.views.size(); ++v) {
            const ReadMap reads{
                read.layers[v].get(),
                p.readingDepthPass(pass.fragmentShader, t.views[v].projection.perspective)};
            renderLightDepth(cmd, p, scene, t.named(technique, pass.target), v, t.views[v], s,
                             &reads, t.nearest);
        }
        vk::imageBarrier(cmd, read.image, vk::kFragmentSampled, vk::kDepthWrite);
    }
    vk::Barriers toSampled;
    for (const ViewMaps* map : depthMaps)
        toSampled.image(map->image, vk::kDepthWrite, vk::kComputeSampled);
    toSampled.record(cmd);
}

// A PostDispatch::MipChain pass: levels 1.. of `map`, each from the level above (already in
// kComputeSampled), one level at a time over every view.
void recordMipChain(VkCommandBuffer cmd, FramePipelines& p, FrameTargets& t, const ViewMaps& map,
                    const shadows::PostPassDecl& pass, vk::GpuTimer* timer) {
    const uint32_t levels = map.image.mipLevels;
    if (levels <= 1)
        return;
    if (timer)
        timer->begin(cmd, std::string(pass.shader.substr(0, pass.shader.rfind('.'))));
    const vk::PipelineLayout& layout = p.postPassLayout(1, 1);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.postPass(pass.shader, 1, 1));
    for (uint32_t level = 1; level < levels; ++level) {
        const uint32_t size = std::max(map.image.width >> level, 1u);
        vk::imageBarrier(cmd, map.image, vk::kUndefined, vk::kComputeWrite, level, 1);
        for (uint32_t v = 0; v < t.views.size(); ++v) {
            vk::PushDescriptors writes;
            writes.sampled(POST_INPUT_BINDING, map.level(v, level - 1), t.nearest)
                .storageImage(POST_OUTPUT_BINDING, map.level(v, level))
                .uniformBuffer(TECH_PARAMS, t.params)
                .uniformBuffer(POST_VIEWS_BINDING, t.viewData);
            writes.push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout);
            const gpu::PostPassPush push{.size = {size, size, v, level}};
            vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                               &push);
            vkCmdDispatch(cmd, groups(size), groups(size), 1);
        }
        vk::imageBarrier(cmd, map.image, vk::kComputeWrite, vk::kComputeSampled, level, 1);
    }
    if (timer)
        timer->end(cmd);
}

// The technique's post passes (compute), in order, each over every shadow view.
// Each pass is timed on its own, named after its shader ("vsm_blur_rows"), when `timer` is given.
void recordShadowPost(VkCommandBuffer cmd, FramePipelines& p, FrameTargets& t,
                      const FrameSettings& s, vk::GpuTimer* timer = nullptr) {
    const shadows::TechniqueModule& technique = *s.technique;
    for (const shadows::PostPassDecl& pass : technique.postPasses) {
        if (pass.dispatch == shadows::PostDispatch::MipChain) {
            recordMipChain(cmd, p, t, t.named(technique, pass.outputs.at(0)), pass, timer);
            continue;
        }
        if (timer)
            timer->begin(cmd, std::string(pass.shader.substr(0, pass.shader.rfind('.'))));
        const auto inputs = static_cast<uint32_t>(pass.inputs.size());
        const auto outputs = static_cast<uint32_t>(pass.outputs.size());
        const vk::PipelineLayout& layout = p.postPassLayout(inputs, outputs);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                          p.postPass(pass.shader, inputs, outputs));
        vk::Barriers toWrite, toSampled;
        for (std::string_view name : pass.outputs) {
            toWrite.image(t.named(technique, name).image, vk::kUndefined, vk::kComputeWrite);
            toSampled.image(t.named(technique, name).image, vk::kComputeWrite, vk::kComputeSampled);
        }
        toWrite.record(cmd);
        const vk::Image& size = t.shadowDepth.image;
        for (uint32_t v = 0; v < t.views.size(); ++v) {
            vk::PushDescriptors writes;
            for (uint32_t i = 0; i < inputs; ++i)
                writes.sampled(POST_INPUT_BINDING + i,
                               t.named(technique, pass.inputs[i]).layers[v].get(), t.nearest);
            for (uint32_t i = 0; i < outputs; ++i)
                writes.storageImage(POST_OUTPUT_BINDING + i,
                                    t.named(technique, pass.outputs[i]).layers[v].get());
            writes.uniformBuffer(TECH_PARAMS, t.params)
                .uniformBuffer(POST_VIEWS_BINDING, t.viewData);
            writes.push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout);
            const gpu::PostPassPush push{.size = {size.width, size.height, v, 0}};
            vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                               &push);
            if (pass.dispatch == shadows::PostDispatch::Lines)
                vkCmdDispatch(cmd, (size.height + LINE_GROUP_SIZE - 1) / LINE_GROUP_SIZE, 1, 1);
            else
                vkCmdDispatch(cmd, groups(size.width), groups(size.height), 1);
        }
        toSampled.record(cmd);
        if (timer)
            timer->end(cmd);
    }
}

void recordGBuffer(VkCommandBuffer cmd, FramePipelines& p, const GpuScene& scene, FrameTargets& t,
                   const glm::mat4& cameraViewProj) {
    vk::imageBarrier(cmd, t.depth, vk::kUndefined, vk::kDepthWrite);
    vk::imageBarrier(cmd, t.normal, vk::kUndefined, vk::kColorWrite);
    vk::imageBarrier(cmd, t.albedo, vk::kUndefined, vk::kColorWrite);
    const VkRenderingAttachmentInfo colors[] = {attachment(t.normal, {.color = {{0, 0, 0, 0}}}),
                                                attachment(t.albedo, {.color = {{0, 0, 0, 0}}})};
    const VkRenderingAttachmentInfo depth = attachment(t.depth, {.depthStencil = {0.0f, 0}});
    const VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                               .renderArea = {{0, 0}, {t.width, t.height}},
                               .layerCount = 1,
                               .colorAttachmentCount = 2,
                               .pColorAttachments = colors,
                               .pDepthAttachment = &depth};
    vkCmdBeginRendering(cmd, &info);
    setViewport(cmd, t.width, t.height);
    bindGeometry(cmd, scene);
    VkPipeline bound = VK_NULL_HANDLE;
    for (const DrawBatch& batch : scene.batches) {
        const GpuScene::Material& material = scene.materials[batch.material];
        const VkPipeline pipeline = p.gbuffer({.texture = material.constants.hasTexture != 0u,
                                               .alphaTest = material.constants.alphaTest != 0u,
                                               .vertexColors = batch.vertexColors});
        if (pipeline != bound)
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = pipeline);
        vk::PushDescriptors()
            .uniformBuffer(BIND_FRAME, t.frame)
            .sampled(GBUFFER_TEXTURE, material.texture.view, material.texture.sampler)
            .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.gbufferLayout);
        vkCmdPushConstants(cmd, p.gbufferLayout.get(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof material.constants, &material.constants);
        vkCmdSetCullMode(cmd, material.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
        for (const IndexRange& r : visibleRanges(scene.clusters, batch.firstIndex, batch.indexCount,
                                                 cameraViewProj, false))
            vkCmdDrawIndexed(cmd, r.count, 1, r.first, 0, 0);
    }
    vkCmdEndRendering(cmd);
    vk::imageBarrier(cmd, t.depth, vk::kDepthWrite, vk::kComputeSampled);
    vk::imageBarrier(cmd, t.normal, vk::kColorWrite, vk::kComputeSampled);
    vk::imageBarrier(cmd, t.albedo, vk::kColorWrite, vk::kComputeSampled);
}

// The visibility dispatch of one light with shadow views, into its layer of the visibility
// image; `fused`: it also shades every pixel into t.color (the last light's).
void dispatchVisibility(VkCommandBuffer cmd, FramePipelines& p, FrameTargets& t,
                        const FrameSettings& s, const LightDispatch& light, bool fused) {
    std::vector<shadows::SpecConstant> constants = s.constants;
    constants.push_back({SPEC_LIGHT_TYPE, light.type});
    constants.push_back({SPEC_LIGHT_VIEWS, light.views});
    if (fused) {
        constants.insert(constants.end(), s.sceneLights.begin(), s.sceneLights.end());
        constants.push_back({SPEC_FUSED_COMPOSITE, 1u});
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.visibility(constants));
    const FilteredBindings filtered = filteredBindings(t, *s.technique);
    vk::PushDescriptors()
        .uniformBuffer(BIND_FRAME, t.frame)
        .uniformBuffer(VIS_LIGHTS, t.lights)
        .sampled(VIS_GBUFFER_DEPTH, t.depth.view.get(), t.nearest)
        .sampled(VIS_GBUFFER_NORMAL, t.normal.view.get(), t.nearest)
        .sampled(TECH_MAP, filtered.floats, t.nearest)
        .sampled(TECH_TABLE, filtered.integers, t.nearest)
        .sampled(TECH_COMPARE, t.shadowDepth.image.view.get(), t.compare)
        .uniformBuffer(TECH_PARAMS, t.params)
        .storageImage(VIS_OUT, t.visibility.view.get())
        .uniformBuffer(VIS_VIEWS, t.viewData)
        .sampled(TECH_FIELD, t.field, t.fieldSampler)
        .storageImage(VIS_INTERMEDIATES, t.intermediates.view.get())
        .sampled(VIS_GBUFFER_ALBEDO, t.albedo.view.get(), t.nearest)
        .storageImage(VIS_COLOR, t.color.view.get())
        .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.visibilityLayout);
    vkCmdPushConstants(cmd, p.visibilityLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       sizeof light.push, &light.push);
    vkCmdDispatch(cmd, groups(t.width), groups(t.height), 1);
}

// The visibility dispatches of every light with shadow views but, when the composite is fused,
// the last (recordComposite runs it).
void recordVisibility(VkCommandBuffer cmd, FramePipelines& p, FrameTargets& t,
                      const FrameSettings& s) {
    vk::Barriers()
        .image(t.visibility, vk::kUndefined, vk::kComputeWrite)
        .image(t.intermediates, vk::kUndefined, vk::kComputeWrite)
        .image(t.integerPlaceholder, vk::kUndefined, vk::kComputeSampled)
        .image(t.color, vk::kUndefined, vk::kComputeWrite) // bound by every dispatch
        .record(cmd);
    const size_t separate = s.fuseComposite && !s.shadowLights.empty() ? s.shadowLights.size() - 1
                                                                       : s.shadowLights.size();
    for (size_t i = 0; i < separate; ++i)
        dispatchVisibility(cmd, p, t, s, s.shadowLights[i], false);
}

void recordComposite(VkCommandBuffer cmd, FramePipelines& p, FrameTargets& t,
                     const FrameSettings& s) {
    if (s.fuseComposite && !s.shadowLights.empty()) {
        // The last light reads the earlier lights' layers as it writes its own.
        vk::imageBarrier(cmd, t.visibility, vk::kComputeWrite, vk::kComputeReadWrite);
        dispatchVisibility(cmd, p, t, s, s.shadowLights.back(), true);
        vk::Barriers()
            .image(t.visibility, vk::kComputeReadWrite, vk::kComputeSampled)
            .image(t.intermediates, vk::kComputeWrite, vk::kComputeSampled)
            .record(cmd);
        return;
    }
    vk::Barriers()
        .image(t.visibility, vk::kComputeWrite, vk::kComputeSampled)
        .image(t.intermediates, vk::kComputeWrite, vk::kComputeSampled)
        .record(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.composite(s.sceneLights));
    vk::PushDescriptors()
        .uniformBuffer(BIND_FRAME, t.frame)
        .uniformBuffer(COMPOSITE_LIGHTS, t.lights)
        .sampled(COMPOSITE_GBUFFER_DEPTH, t.depth.view.get(), t.nearest)
        .sampled(COMPOSITE_GBUFFER_NORMAL, t.normal.view.get(), t.nearest)
        .sampled(COMPOSITE_GBUFFER_ALBEDO, t.albedo.view.get(), t.nearest)
        .sampled(COMPOSITE_VISIBILITY, t.visibility.view.get(), t.nearest)
        .storageImage(COMPOSITE_OUT, t.color.view.get())
        .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.compositeLayout);
    vkCmdDispatch(cmd, groups(t.width), groups(t.height), 1);
}

} // namespace

ViewMaps makeViewMaps(const vk::Context& ctx, shadows::MapFormat format, uint32_t size,
                      uint32_t views, VkImageUsageFlags usage, bool mipmapped) {
    ViewMaps maps{
        .image = vk::createImage(ctx, {.name = "--shadow-map-size",
                                       .format = formatOf(format),
                                       .width = size,
                                       .height = size,
                                       .layers = std::max(views, 1u),
                                       .usage = usage,
                                       .arrayView = true,
                                       .mipLevels = mipmapped ? gpu::mipLevelCount(size) : 1u}),
        .format = format};
    for (uint32_t layer = 0; layer < maps.image.layers; ++layer)
        maps.layers.push_back(vk::createLayerView(ctx, maps.image, layer));
    if (maps.image.mipLevels > 1)
        for (uint32_t layer = 0; layer < maps.image.layers; ++layer)
            for (uint32_t level = 0; level < maps.image.mipLevels; ++level)
                maps.levels.push_back(vk::createLayerView(ctx, maps.image, layer, level));
    return maps;
}

void recordPostPasses(VkCommandBuffer cmd, FramePipelines& pipelines, FrameTargets& targets,
                      const shadows::TechniqueModule& technique) {
    recordShadowPost(cmd, pipelines, targets, FrameSettings{.technique = &technique});
}

const ViewMaps& FrameTargets::named(const shadows::TechniqueModule& module,
                                    std::string_view name) const {
    if (name == shadows::kDepthMap)
        return shadowDepth;
    for (size_t m = 0; m < module.maps.size(); ++m)
        if (module.maps[m].name == name)
            return maps[m];
    fatal(__FILE__, __LINE__, "FrameTargets::named: the technique declares no such map");
}

VkFormat formatOf(shadows::MapFormat format) {
    switch (format) {
    case shadows::MapFormat::Depth32:
        return kDepthFormat;
    case shadows::MapFormat::R32F:
        return VK_FORMAT_R32_SFLOAT;
    case shadows::MapFormat::RG32F:
        return VK_FORMAT_R32G32_SFLOAT;
    case shadows::MapFormat::RG32UI:
        return VK_FORMAT_R32G32_UINT;
    case shadows::MapFormat::RGBA32UI:
        return VK_FORMAT_R32G32B32A32_UINT;
    case shadows::MapFormat::RGBA16:
        return VK_FORMAT_R16G16B16A16_UNORM;
    case shadows::MapFormat::RGBA32F:
        break;
    }
    return VK_FORMAT_R32G32B32A32_SFLOAT;
}

vk::Image makeIntegerPlaceholder(const vk::Context& ctx) {
    return vk::createImage(ctx, {.name = "integer-map placeholder",
                                 .format = VK_FORMAT_R32G32B32A32_UINT,
                                 .width = 1,
                                 .height = 1,
                                 .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
                                 .arrayView = true});
}

vk::Image makeFieldPlaceholder(const vk::Context& ctx) {
    return vk::createImage(ctx, {.name = "distance field placeholder",
                                 .format = VK_FORMAT_R32_SFLOAT,
                                 .width = 1,
                                 .height = 1,
                                 .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
                                 .depth = 2});
}

FilteredBindings filteredBindings(const FrameTargets& t, const shadows::TechniqueModule& module) {
    const ViewMaps& filtered = t.named(module, module.visibilityMap);
    const VkImageView map = filtered.image.view.get();
    if (shadows::holdsIntegers(filtered.format))
        return {.floats = t.shadowDepth.image.view.get(), .integers = map};
    return {.floats = map, .integers = t.integerPlaceholder.view.get()};
}

void recordFrame(VkCommandBuffer cmd, FramePipelines& pipelines, const GpuScene& scene,
                 FrameTargets& targets, const FrameSettings& settings, vk::GpuTimer& timer) {
    timer.reset(cmd);
    if (settings.technique->tracesField) {
        // No shadow map: the depth map (1x1) is only bound, never drawn.
        vk::imageBarrier(cmd, targets.shadowDepth.image, vk::kUndefined, vk::kComputeSampled);
    } else {
        timer.begin(cmd, "shadow");
        recordShadowPasses(cmd, pipelines, scene, targets, settings);
        timer.end(cmd);
        if (!targets.views.empty())
            recordShadowPost(cmd, pipelines, targets, settings, &timer);
    }
    timer.begin(cmd, "gbuffer");
    recordGBuffer(cmd, pipelines, scene, targets, settings.cameraViewProj);
    timer.end(cmd);
    timer.begin(cmd, "visibility");
    recordVisibility(cmd, pipelines, targets, settings);
    timer.end(cmd);
    timer.begin(cmd, "composite");
    recordComposite(cmd, pipelines, targets, settings);
    timer.end(cmd);
}

void recordReadback(VkCommandBuffer cmd, FramePipelines& p, FrameTargets& t, VkBuffer readback) {
    vk::imageBarrier(cmd, t.position, vk::kUndefined, vk::kComputeWrite);
    vk::imageBarrier(cmd, t.exportNormal, vk::kUndefined, vk::kComputeWrite);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.exportGBuffer.get());
    vk::PushDescriptors()
        .uniformBuffer(BIND_FRAME, t.frame)
        .sampled(EXPORT_GBUFFER_DEPTH, t.depth.view.get(), t.nearest)
        .sampled(EXPORT_GBUFFER_NORMAL, t.normal.view.get(), t.nearest)
        .storageImage(EXPORT_POSITION, t.position.view.get())
        .storageImage(EXPORT_NORMAL, t.exportNormal.view.get())
        .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.exportLayout);
    vkCmdDispatch(cmd, groups(t.width), groups(t.height), 1);

    VkDeviceSize offset = 0;
    const std::pair<vk::Image*, vk::ImageState> sources[] = {{&t.color, vk::kComputeWrite},
                                                             {&t.visibility, vk::kComputeSampled},
                                                             {&t.position, vk::kComputeWrite},
                                                             {&t.exportNormal, vk::kComputeWrite}};
    for (const auto& [image, state] : sources) {
        vk::imageBarrier(cmd, *image, state, vk::kTransferRead);
        const VkBufferImageCopy region{.bufferOffset = offset,
                                       .imageSubresource = {.aspectMask = image->aspect,
                                                            .mipLevel = 0,
                                                            .baseArrayLayer = 0,
                                                            .layerCount = image->layers},
                                       .imageExtent = {image->width, image->height, 1}};
        vkCmdCopyImageToBuffer(cmd, image->get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1,
                               &region);
        offset += VkDeviceSize{image->width} * image->height * image->layers *
                  vk::formatBytes(image->format);
    }
}

GpuScene uploadScene(const vk::Context& ctx, const Scene& scene) {
    GpuScene out;
    const size_t materialCount = std::max<size_t>(scene.materials.size(), 1);
    std::vector<std::vector<uint32_t>> byMaterial(materialCount);
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const uint32_t m = scene.vertices[scene.indices[3 * t]].material;
        auto& list = byMaterial[m < materialCount ? m : 0];
        list.insert(list.end(), scene.indices.begin() + static_cast<long>(3 * t),
                    scene.indices.begin() + static_cast<long>(3 * t + 3));
    }
    auto alphaTested = [&](size_t m) {
        return m < scene.materials.size() && scene.materials[m].alphaTested();
    };
    std::vector<uint32_t> indices;
    indices.reserve(scene.indices.size());
    for (const bool tested : {false, true})
        for (size_t m = 0; m < materialCount; ++m) {
            if (alphaTested(m) != tested || byMaterial[m].empty())
                continue;
            const bool coloured =
                std::any_of(byMaterial[m].begin(), byMaterial[m].end(),
                            [&](uint32_t i) { return scene.vertices[i].color != glm::vec4(1.0f); });
            out.batches.push_back({.material = static_cast<uint32_t>(m),
                                   .firstIndex = static_cast<uint32_t>(indices.size()),
                                   .indexCount = static_cast<uint32_t>(byMaterial[m].size()),
                                   .vertexColors = coloured});
            indices.insert(indices.end(), byMaterial[m].begin(), byMaterial[m].end());
            if (!tested)
                out.opaqueIndexCount = static_cast<uint32_t>(indices.size());
        }
    out.textures = uploadTextures(ctx, scene);
    for (size_t m = 0; m < materialCount; ++m) {
        const Material material = m < scene.materials.size() ? scene.materials[m] : Material{};
        out.materials.push_back(
            {.constants = {.baseColor = material.baseColor,
                           .alphaCutoff = material.alphaCutoff,
                           .alphaTest = material.alphaTested() ? 1u : 0u,
                           .hasTexture = material.baseColorTexture >= 0 ? 1u : 0u},
             .texture = out.textures.of(scene, material),
             .doubleSided = material.doubleSided});
    }
    out.vertices = vk::uploadBuffer(ctx, std::as_bytes(std::span(scene.vertices)),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertex buffer");
    std::vector<glm::vec3> positions;
    positions.reserve(scene.vertices.size());
    for (const Vertex& v : scene.vertices)
        positions.push_back(v.position);
    out.positions = vk::uploadBuffer(ctx, std::as_bytes(std::span(positions)),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "position buffer");
    std::vector<uint32_t> batchStarts;
    for (const DrawBatch& batch : out.batches)
        batchStarts.push_back(batch.firstIndex);
    out.clusters = makeClusters(positions, indices, batchStarts);
    out.indices = vk::uploadBuffer(ctx, std::as_bytes(std::span(indices)),
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "index buffer");
    out.indexCount = static_cast<uint32_t>(indices.size());
    return out;
}

} // namespace penumbra::render
