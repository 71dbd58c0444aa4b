// Renderer::probeTechnique: uploads a synthetic shadow map into a D32_SFLOAT image and runs, as a
// small frame graph, the technique's post passes over it (as a frame does) and filter_probe.comp,
// which calls the visibility pass's technique code at the given receivers.
#include "penumbra/error.h"
#include "render/frame.h"
#include "render/frame_data.h"
#include "render/renderer_impl.h"
#include "vk/sync.h"

#include <cstring>

namespace penumbra {
namespace {

// The visibility pass's constants but SPEC_VIRTUAL: the probe hands the technique a map's layer
// (its texels written from the host), never a virtual map. SPEC_LIGHT_TYPE: the kind of light
// whose view it is.
std::vector<shadows::SpecConstant> probeConstants(const shadows::TechniqueModule& module,
                                                  const ParameterValues& params,
                                                  const ProbeLight& light) {
    std::vector<shadows::SpecConstant> constants = shadows::visibilityConstants(module, params);
    for (shadows::SpecConstant& c : constants)
        if (c.id == SPEC_VIRTUAL)
            c.value = 0u;
    constants.push_back({SPEC_LIGHT_TYPE, light.cubeFace      ? uint32_t{LIGHT_POINT}
                                          : light.perspective ? uint32_t{LIGHT_SPOT}
                                                              : uint32_t{LIGHT_DIRECTIONAL}});
    if (light.readSlots != 0)
        constants.push_back({SPEC_PROBE_SLOTS, light.readSlots});
    return constants;
}

} // namespace

std::vector<glm::vec4> Renderer::probeTechnique(Technique technique, const ParameterValues& params,
                                                std::span<const float> depths, uint32_t size,
                                                std::span<const FilterProbe> probes,
                                                const ProbeLight& probeLight) {
    const vk::Context& ctx = mImpl->ctx;
    PENUMBRA_CHECK(depths.size() == size_t{size} * size && !probes.empty(), "probe input sizes");
    const shadows::TechniqueModule& module = shadows::moduleOf(technique);
    const shadows::FilterSettings settings = shadows::filterSettings(
        module, params, ctx.info().depthLinearFilter, ctx.limits().subTexelPrecisionBits);
    std::vector<gpu::ProbeReceiver> gpuProbes;
    for (const FilterProbe& p : probes)
        gpuProbes.push_back(
            {{p.uv, p.depth, p.creaseLimit},
             {p.gradient, static_cast<float>(p.pixel.x), static_cast<float>(p.pixel.y)},
             {p.uvDx, p.uvDy},
             {p.curve, p.planeRange}});

    auto upload = [&](std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                      const char* name) {
        vk::Buffer b = vk::createBuffer(ctx, bytes.size(), usage, vk::MemoryUse::Upload, name);
        std::memcpy(b.mapped, bytes.data(), bytes.size());
        return b;
    };
    const vk::Buffer frameBuffer = upload(std::as_bytes(std::span(&settings.frame, 1)),
                                          VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "probe frame");
    const vk::Buffer paramsBuffer =
        upload(settings.params.bytes(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "probe parameters");
    const vk::Buffer probeBuffer =
        upload(std::as_bytes(std::span(gpuProbes)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "probes");
    const vk::Buffer mapBuffer =
        upload(std::as_bytes(depths), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "probe shadow map");
    const gpu::ShadowViewData view = render::probeViewData(probeLight);
    // The probe reads it as storage, the technique's post passes as their uniform view records.
    const vk::Buffer viewBuffer = upload(
        std::as_bytes(std::span(&view, 1)),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "probe view");
    const vk::Buffer results =
        vk::createBuffer(ctx, probes.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         vk::MemoryUse::Readback, "probe results");
    const vk::Image fieldPlaceholder = render::makeFieldPlaceholder(ctx);
    const vk::SamplerHandle nearest = vk::createSampler(ctx, {});
    const VkFilter compareFilter =
        ctx.info().depthLinearFilter ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    const vk::SamplerHandle compare = vk::createSampler(
        ctx, {.magFilter = compareFilter, .minFilter = compareFilter, .compare = true});
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, fieldPlaceholder, vk::kUndefined, vk::kComputeSampled);
    });

    // The technique's own maps, filled from the depth map by its post passes as in a frame; a
    // technique whose passes also need another depth pass (second-depth's peel) is probed on
    // the given map as its filtered map instead.
    const bool derived = module.depthPasses.empty() && !module.postPasses.empty();
    render::ResourcePool pool(ctx);
    render::FrameGraph graph(pool, {.shadowMapSize = size, .shadowViews = 1});
    render::FrameResources r;
    std::vector<render::ImageDecl> maps =
        render::shadowMapDecls(module, params, {});        // one frame: no history
    maps.front().usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT; // the given depths go in by a copy
    r.depthMap = graph.declare(maps.front());
    if (derived)
        r.declareOwnMaps(graph, module, std::span(maps).subspan(1));
    r.integerPlaceholder = graph.declare(render::integerPlaceholderDecl());
    r.depthPlaceholder = graph.declare(render::depthPlaceholderDecl());
    graph.markBoundOnly(r.integerPlaceholder);
    graph.markBoundOnly(r.depthPlaceholder);
    r.field = graph.importImage("probe.field", fieldPlaceholder, render::Access::ComputeSampled);
    r.params = graph.importBuffer("probe.params", paramsBuffer.get());
    r.views = graph.importBuffer("probe.views", viewBuffer.get());
    // The depth map itself is filtered unless the post passes derive the technique's maps.
    const render::FilteredBindings filtered = render::FilteredBindings::of(
        module, params, r.depthMap, {r.integerPlaceholder, r.depthPlaceholder},
        derived ? std::function([&](std::string_view name) { return r.named(module, name); })
                : nullptr);
    std::vector<render::Use> probeUses{{r.depthMap, render::Access::ComputeSampled},
                                       {r.field, render::Access::ComputeSampled},
                                       {r.params, render::Access::UniformRead},
                                       {r.views, render::Access::ComputeRead}};
    filtered.addUses(probeUses);
    const render::FrameInputs inputs{
        .views = viewBuffer.get(), .params = paramsBuffer.get(), .nearest = nearest.get()};
    render::FramePipelines& p = mImpl->pipelines;
    graph.addPass(
        {.name = "",
         .phase = render::Phase::LightSpace,
         .uses = {{r.depthMap, render::Access::TransferWrite}},
         .record = [&](render::PassContext& c) {
             const VkBufferImageCopy region{
                 .imageSubresource = {.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT, .layerCount = 1},
                 .imageExtent = {size, size, 1}};
             vkCmdCopyBufferToImage(c.cmd, mapBuffer.get(), c.image(r.depthMap).get().get(),
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
         }});
    if (derived)
        render::addPostPasses(graph, p, module, params, 1, inputs, r);
    graph.addPass({.name = "",
                   .phase = render::Phase::PerLight,
                   .uses = probeUses,
                   .record = [&](render::PassContext& c) {
                       vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                         p.probe(probeConstants(module, params, probeLight)));
                       vk::PushDescriptors descriptors;
                       filtered.write(descriptors, c, nearest.get(), compare.get());
                       descriptors.uniformBuffer(BIND_FRAME, frameBuffer.get())
                           .storageBuffer(PROBE_RECEIVERS, probeBuffer.get())
                           .sampled(TECH_FIELD, fieldPlaceholder.view.get(), nearest.get())
                           .uniformBuffer(TECH_PARAMS, paramsBuffer.get())
                           .storageBuffer(PROBE_RESULTS, results.get())
                           .storageBuffer(PROBE_VIEW, viewBuffer.get())
                           // never read: the probe's map is no virtual map (probeConstants)
                           .storageBuffer(TECH_PAGE_TABLE, viewBuffer.get())
                           .push(ctx, c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.probeLayout);
                       const gpu::ProbePush push{
                           .counts = {static_cast<uint32_t>(probes.size()), size, 0, 0}};
                       vkCmdPushConstants(c.cmd, p.probeLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT,
                                          0, sizeof push, &push);
                       vkCmdDispatch(c.cmd, static_cast<uint32_t>((probes.size() + 63) / 64), 1, 1);
                       vk::bufferBarrier(c.cmd, results.get(),
                                         VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                         VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                         VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
                   }});
    ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
    const auto* out = static_cast<const glm::vec4*>(results.mapped);
    return {out, out + probes.size()};
}

} // namespace penumbra
