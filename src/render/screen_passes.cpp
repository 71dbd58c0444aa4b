// The GBuffer and Readback phases (render/frame.h): the camera's G-buffer (reverse-Z depth,
// normals, base colour; the clusters in the camera's frustum, a pipeline per material variant),
// and the copies for the host: position and normal exported from the G-buffer, then colour,
// visibility, position and normal copied into the readback buffer at ReadbackLayout's offsets.
#include "render/frame.h"
#include "render/pass_utils.h"
#include "vk/pipelines.h"
#include "vk/sync.h"

namespace penumbra::render {

void addGBufferPass(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                    const FrameSettings& s, const FrameInputs& in, const FrameResources& r) {
    std::vector<Use> uses{{r.gbufferDepth, Access::DepthAttachment},
                          {r.gbufferNormal, Access::ColorAttachment},
                          {r.gbufferAlbedo, Access::ColorAttachment},
                          {r.frame, Access::UniformRead},
                          {r.vertices, Access::VertexRead}};
    // Where the vertices were: read by the motion vectors (bound either way, every binding a
    // shader declares must be written; the positions stand in where nothing moved).
    const ResourceId previous = r.previousPositions ? r.previousPositions : r.positions;
    uses.push_back({previous, Access::VertexStorageRead});
    if (s.motion)
        uses.push_back({r.gbufferMotion, Access::ColorAttachment});
    graph.addPass(
        {.name = "gbuffer",
         .cost = CostGroup::Frame,
         .phase = Phase::GBuffer,
         .uses = uses,
         .record = [&p, &scene, &s, &in, r, previous](PassContext& c) {
             const vk::Image& depthImage = c.image(r.gbufferDepth).get();
             // Background pixels keep no motion (w = 0 marks them).
             const VkRenderingAttachmentInfo colors[] = {
                 attachment(c.image(r.gbufferNormal).get(), {.color = {{0, 0, 0, 0}}}),
                 attachment(c.image(r.gbufferAlbedo).get(), {.color = {{0, 0, 0, 0}}}),
                 s.motion ? attachment(c.image(r.gbufferMotion).get(), {.color = {{0, 0, 0, 0}}})
                          : VkRenderingAttachmentInfo{}};
             const VkRenderingAttachmentInfo depth =
                 attachment(depthImage, {.depthStencil = {0.0f, 0}});
             const VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                                        .renderArea = {{0, 0}, {s.sizes.width, s.sizes.height}},
                                        .layerCount = 1,
                                        .colorAttachmentCount = s.motion ? 3u : 2u,
                                        .pColorAttachments = colors,
                                        .pDepthAttachment = &depth};
             VkCommandBuffer cmd = c.cmd;
             vkCmdBeginRendering(cmd, &info);
             setViewport(cmd, s.sizes.width, s.sizes.height);
             const VkDeviceSize offset = 0;
             const VkBuffer vertices = scene.vertices.get();
             vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
             vkCmdBindIndexBuffer(cmd, scene.indices.get(), 0, VK_INDEX_TYPE_UINT32);
             VkPipeline bound = VK_NULL_HANDLE;
             for (const DrawBatch& batch : scene.batches) {
                 const GpuScene::Material& material = scene.materials[batch.material];
                 const VkPipeline pipeline =
                     p.gbuffer({.texture = material.constants.hasTexture != 0u,
                                .alphaTest = material.constants.alphaTest != 0u,
                                .vertexColors = batch.vertexColors,
                                .motion = s.motion});
                 if (pipeline != bound)
                     vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound = pipeline);
                 vk::PushDescriptors()
                     .uniformBuffer(BIND_FRAME, in.frame)
                     .sampled(GBUFFER_TEXTURE, material.texture.view, material.texture.sampler)
                     .storageBuffer(GBUFFER_PREVIOUS_POSITIONS, c.buffer(previous))
                     .push(p.ctx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.gbufferLayout);
                 vkCmdPushConstants(cmd, p.gbufferLayout.get(),
                                    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                    sizeof material.constants, &material.constants);
                 vkCmdSetCullMode(cmd,
                                  material.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
                 for (const IndexRange& range :
                      visibleRanges(scene.clusters, batch.firstIndex, batch.indexCount,
                                    s.cameraViewProj, false))
                     vkCmdDrawIndexed(cmd, range.count, 1, range.first, 0, 0);
             }
             vkCmdEndRendering(cmd);
         }});
}

void addReadbackPasses(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                       const FrameInputs& in, const FrameResources& r) {
    graph.addPass({.name = "",
                   .phase = Phase::Readback,
                   .bindings = {.layout = &p.exportLayout,
                                .bound = {{BIND_FRAME, r.frame},
                                          {EXPORT_GBUFFER_DEPTH, r.gbufferDepth, in.nearest},
                                          {EXPORT_GBUFFER_NORMAL, r.gbufferNormal, in.nearest},
                                          {EXPORT_POSITION, r.position},
                                          {EXPORT_NORMAL, r.normal},
                                          {EXPORT_FACE_NORMAL, r.faceNormal}}},
                   .record = [&p, &s](PassContext& c) {
                       vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                         p.exportGBuffer.get());
                       vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(s.sizes.height), 1);
                   }});
    const ReadbackLayout layout(s.sizes.width, s.sizes.height, s.sizes.shadowLights, s.motion,
                                s.translucent != 0);
    std::vector<std::pair<ResourceId, ReadbackLayout::Part>> parts{
        {r.color, layout.color},
        {r.visibility, layout.visibility},
        {r.position, layout.position},
        {r.normal, layout.normal},
        {r.faceNormal, layout.faceNormal}};
    if (layout.motion)
        parts.emplace_back(r.gbufferMotion, *layout.motion);
    if (layout.colour)
        parts.emplace_back(r.translucentColour, *layout.colour);
    std::vector<Use> uses{{r.readback, Access::TransferWrite}};
    for (const auto& part : parts)
        uses.push_back({part.first, Access::TransferRead});
    graph.addPass(
        {.name = "", .phase = Phase::Readback, .uses = uses, .record = [parts, r](PassContext& c) {
             for (const auto& [id, part] : parts) {
                 const vk::Image& image = c.image(id).get();
                 const VkBufferImageCopy region{.bufferOffset = part.offset,
                                                .imageSubresource = {.aspectMask = image.aspect,
                                                                     .mipLevel = 0,
                                                                     .baseArrayLayer = 0,
                                                                     .layerCount = image.layers},
                                                .imageExtent = {image.width, image.height, 1}};
                 vkCmdCopyImageToBuffer(c.cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                        c.buffer(r.readback), 1, &region);
             }
         }});
    // The host reads it after the fence.
    graph.addPass({.name = "",
                   .phase = Phase::Readback,
                   .uses = {{r.readback, Access::HostRead}},
                   .record = [](PassContext&) {}});
}

} // namespace penumbra::render
