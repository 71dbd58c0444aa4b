// Renderer::probeTechnique: uploads a synthetic shadow map into a D32_SFLOAT image and runs
// filter_probe.comp, which calls the visibility pass's technique code at the given receivers.
#include "penumbra/error.h"
#include "render/frame.h"
#include "render/frame_data.h"
#include "render/renderer_impl.h"
#include "vk/sync.h"

#include <cstring>

namespace penumbra {
namespace {} // namespace

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
            {{p.uv, p.depth, 0.0f},
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
    // The technique's own maps, filled from the depth map by its post passes as in a frame; a
    // technique whose passes also need another depth pass (second-depth's peel) is probed on
    // the given map as its filtered map instead.
    const bool derived = module.depthPasses.empty() && !module.postPasses.empty();
    render::FrameTargets t{.views = std::vector<render::ShadowView>(1)};
    t.shadowDepth =
        render::makeViewMaps(ctx, shadows::MapFormat::Depth32, size, 1,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    for (const shadows::MapDecl& decl : derived ? module.maps : std::vector<shadows::MapDecl>{})
        t.maps.push_back(
            render::makeViewMaps(ctx, shadows::formatOf(decl, params), size, 1,
                                 VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 shadows::mipmappedOf(decl, params)));
    t.integerPlaceholder = render::makeIntegerPlaceholder(ctx);
    const vk::Image fieldPlaceholder = render::makeFieldPlaceholder(ctx);
    const vk::Image& map = t.shadowDepth.image;
    const vk::SamplerHandle nearest = vk::createSampler(ctx, {});
    t.frame = frameBuffer.get(), t.viewData = viewBuffer.get(), t.nearest = nearest.get();
    t.params = paramsBuffer.get();
    const VkFilter compareFilter =
        ctx.info().depthLinearFilter ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    const vk::SamplerHandle compare = vk::createSampler(
        ctx, {.magFilter = compareFilter, .minFilter = compareFilter, .compare = true});

    render::FramePipelines& p = mImpl->pipelines;
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        constexpr vk::ImageState transferWrite{VK_PIPELINE_STAGE_2_COPY_BIT,
                                               VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
        vk::imageBarrier(cmd, map, vk::kUndefined, transferWrite);
        const VkBufferImageCopy region{
            .imageSubresource = {.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT, .layerCount = 1},
            .imageExtent = {size, size, 1}};
        vkCmdCopyBufferToImage(cmd, mapBuffer.get(), map.get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        vk::imageBarrier(cmd, map, transferWrite, vk::kComputeSampled);
        if (derived)
            render::recordPostPasses(cmd, p, t, module);
        vk::imageBarrier(cmd, t.integerPlaceholder, vk::kUndefined, vk::kComputeSampled);
        vk::imageBarrier(cmd, fieldPlaceholder, vk::kUndefined, vk::kComputeSampled);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                          p.probe(shadows::visibilityConstants(module, params)));
        // A technique probed on the given map (no post passes) filters the depth map itself.
        const render::FilteredBindings filtered =
            derived ? render::filteredBindings(t, module)
                    : render::FilteredBindings{map.view.get(), t.integerPlaceholder.view.get()};
        vk::PushDescriptors()
            .uniformBuffer(BIND_FRAME, frameBuffer.get())
            .storageBuffer(PROBE_RECEIVERS, probeBuffer.get())
            .sampled(TECH_MAP, filtered.floats, nearest.get())
            .sampled(TECH_TABLE, filtered.integers, nearest.get())
            .sampled(TECH_COMPARE, map.view.get(), compare.get())
            .sampled(TECH_FIELD, fieldPlaceholder.view.get(), nearest.get())
            .uniformBuffer(TECH_PARAMS, paramsBuffer.get())
            .storageBuffer(PROBE_RESULTS, results.get())
            .storageBuffer(PROBE_VIEW, viewBuffer.get())
            .push(ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.probeLayout);
        const gpu::ProbePush push{.counts = {static_cast<uint32_t>(probes.size()), size, 0, 0}};
        vkCmdPushConstants(cmd, p.probeLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push,
                           &push);
        vkCmdDispatch(cmd, static_cast<uint32_t>((probes.size() + 63) / 64), 1, 1);
        vk::bufferBarrier(cmd, results.get(), VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                          VK_ACCESS_2_HOST_READ_BIT);
    });
    const auto* out = static_cast<const glm::vec4*>(results.mapped);
    return {out, out + probes.size()};
}

} // namespace penumbra
