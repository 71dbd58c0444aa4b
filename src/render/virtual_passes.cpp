// Virtual shadow maps' passes (virtual.enabled; render/frame.h, docs/techniques.md "Virtual shadow
// maps"). Decided on the host: the pages the host decided to render this frame (SceneRenderer,
// from the requests the previous frame's marking left and the page cache,
// src/core/virtual_maps.h), each cleared and drawn into its place in the pool, before the
// G-buffer; after it, every visible pixel's page requests, which the host reads back once the
// frame is done. Decided on the device (virtual.deviceDecides): after the marking, this frame's
// requests decided (PageDecisionPasses) and the pages drawn (PageDrawPasses), before the
// PerLight passes read the pool. All are timed as "shadow": all the shadow-map work of a frame
// whose pages are all cached is the marking (and, on the device, the decisions).
#include "render/frame.h"
#include "render/page_draw_passes.h"
#include "render/pass_utils.h"
#include "vk/pipelines.h"

namespace penumbra::render {
namespace {

// The host's pages for this frame drawn into their places in `target` (the pool, or the static
// pool): `set`'s clusters; CasterSet::Static's only into the pages whose static layer is not
// held, CasterSet::Dynamic's over what the pages hold.
void addPageDraws(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                  const FrameSettings& s, const FrameInputs& in, const FrameResources& r,
                  ResourceId target, CasterSet set) {
    graph.addPass({.name = "shadow",
                   .cost = CostGroup::ShadowMaps,
                   .phase = Phase::LightSpace,
                   .uses = {{target, Access::DepthAttachment},
                            {r.vertices, Access::VertexRead},
                            {r.positions, Access::VertexRead}},
                   .record = [&p, &scene, &s, &in, target, set](PassContext& c) {
                       if (s.pages)
                           for (const PageDraw& page : *s.pages)
                               if (set != CasterSet::Static || !page.staticHeld)
                                   renderPageDepth(c.cmd, p, scene, c.image(target), page,
                                                   s.pageSize, s, in.nearest, set);
                   }});
}

// virtual.staticLayer: the static layers of the pages that lack one drawn into the static pool
// (the casters no pose has moved), every page's copied into its place in the pool, and the
// dynamic casters drawn over it. A page only dynamic casters moved over skips the first.
void addStaticLayerPasses(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                          const FrameSettings& s, const FrameInputs& in, const FrameResources& r) {
    addPageDraws(graph, p, scene, s, in, r, r.staticPool, CasterSet::Static);
    graph.addPass(
        {.name = "shadow",
         .cost = CostGroup::ShadowMaps,
         .phase = Phase::LightSpace,
         .uses = {{r.staticPool, Access::TransferRead}, {r.depthMap, Access::TransferWrite}},
         .record = [&s, from = r.staticPool, to = r.depthMap](PassContext& c) {
             std::vector<VkImageCopy> regions;
             for (const PageDraw& page : s.pages ? *s.pages : std::vector<PageDraw>{}) {
                 const VkImageSubresourceLayers depth{.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT,
                                                      .layerCount = 1};
                 const VkOffset3D corner{static_cast<int32_t>(page.origin.x),
                                         static_cast<int32_t>(page.origin.y), 0};
                 regions.push_back({.srcSubresource = depth,
                                    .srcOffset = corner,
                                    .dstSubresource = depth,
                                    .dstOffset = corner,
                                    .extent = {s.pageSize, s.pageSize, 1}});
             }
             if (!regions.empty())
                 vkCmdCopyImage(c.cmd, c.image(from).get().get(),
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, c.image(to).get().get(),
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                static_cast<uint32_t>(regions.size()), regions.data());
         }});
    addPageDraws(graph, p, scene, s, in, r, r.depthMap, CasterSet::Dynamic);
}

} // namespace

void addVirtualPagePasses(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                          const FrameSettings& s, const FrameInputs& in, const FrameResources& r) {
    if (!s.devicePages && r.staticPool)
        addStaticLayerPasses(graph, p, scene, s, in, r);
    else if (!s.devicePages)
        addPageDraws(graph, p, scene, s, in, r, r.depthMap, CasterSet::All);
    // The requests start empty every frame.
    graph.addPass({.name = "",
                   .phase = Phase::ScreenSpace,
                   .uses = {{r.pageRequests, Access::TransferWrite}},
                   .record = [requests = r.pageRequests](PassContext& c) {
                       vkCmdFillBuffer(c.cmd, c.buffer(requests), 0, VK_WHOLE_SIZE, 0u);
                   }});
    graph.addPass(
        {.name = "shadow",
         .cost = CostGroup::ShadowMaps,
         .phase = Phase::ScreenSpace,
         .bindings = {.layout = &p.markingLayout,
                      .bound = {{BIND_FRAME, r.frame},
                                {MARK_LIGHTS, r.lights},
                                {MARK_GBUFFER_DEPTH, r.gbufferDepth, in.nearest},
                                {MARK_GBUFFER_NORMAL, r.gbufferNormal, in.nearest},
                                {MARK_VIEWS, r.views},
                                {MARK_REQUESTS, r.pageRequests}}},
         .record = [&p, &s](PassContext& c) {
             for (const LightDispatch& light : s.shadowLights) {
                 vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                   p.marking({{SPEC_LIGHT_TYPE, light.type}}));
                 vkCmdPushConstants(c.cmd, p.markingLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                    sizeof light.push, &light.push);
                 vkCmdDispatch(c.cmd, groups((s.sizes.width + MARK_BLOCK - 1) / MARK_BLOCK),
                               groups((s.sizes.height + MARK_BLOCK - 1) / MARK_BLOCK), 1);
             }
         }});
    if (const DevicePages* device = s.devicePages) {
        std::vector<Use> drawUses = casterDrawUses(r);
        drawUses.push_back({r.pageRenderList, Access::ComputeRead});
        graph.addPass({.name = "shadow",
                       .cost = CostGroup::ShadowMaps,
                       .phase = Phase::ScreenSpace,
                       .uses = {{r.pageRequests, Access::ComputeRead},
                                {r.pageTable, Access::ComputeWrite},
                                {r.pageRenderList, Access::ComputeWrite}},
                       .record = [device = *device, requests = r.pageRequests](PassContext& c) {
                           device.decisions->record(c.cmd, c.buffer(requests), nullptr,
                                                    device.slot);
                       }});
        graph.addPass({.name = "shadow",
                       .cost = CostGroup::ShadowMaps,
                       .phase = Phase::ScreenSpace,
                       .uses = std::move(drawUses),
                       .record = [device = *device, &scene, &s, pool = r.depthMap](PassContext& c) {
                           device.draws->record(c.cmd, *device.decisions, scene, c.image(pool),
                                                device.poolPagesPerSide, s.constantBias,
                                                s.slopeBias, device.slot);
                       }});
        return;
    }
    // The host reads them after the frame's fence.
    graph.addPass({.name = "",
                   .phase = Phase::Readback,
                   .uses = {{r.pageRequests, Access::HostRead}},
                   .record = [](PassContext&) {}});
}

} // namespace penumbra::render
