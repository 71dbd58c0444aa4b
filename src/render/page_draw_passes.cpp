#include "render/page_draw_passes.h"

#include "bindings.h"
#include "pass_types.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "render/pipelines.h"
#include "vk/pipelines.h"
#include "vk/sync.h"

#include <cstring>

namespace penumbra::render {
namespace {

static_assert(sizeof(gpu::PageDrawPush) == sizeof(gpu::ShadowPush),
              "shadow_mask.frag reads the material after a ShadowPush");

constexpr VkShaderStageFlags kGraphics = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

VkVertexInputAttributeDescription attribute(uint32_t location, VkFormat format, uint32_t offset) {
    return {.location = location, .binding = 0, .format = format, .offset = offset};
}

vk::GraphicsPipelineDesc pageDesc(std::string_view vertex, bool depthClamp, bool masked) {
    vk::GraphicsPipelineDesc d{.vertexShader = vertex,
                               .depthFormat = kDepthFormat,
                               .depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL,
                               .depthClamp = depthClamp,
                               .depthBias = true};
    if (masked) {
        d.fragmentShader = "shadow_mask.frag";
        d.vertexStride = sizeof(Vertex);
        d.attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)),
                        attribute(1, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)),
                        attribute(2, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color))};
    } else {
        d.vertexStride = sizeof(glm::vec3);
        d.attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, 0)};
    }
    return d;
}

uint32_t groupsOf(uint32_t count) {
    return (count + PAGES_BLOCK - 1) / PAGES_BLOCK;
}

} // namespace

PageDrawPasses::PageDrawPasses(const vk::Context& ctx, uint32_t slots, bool readable)
    : mCtx(ctx), mReadable(readable), mSlots(std::max(slots, 1u)) {
    mSetupLayout = vk::createLayoutOf(ctx, {"page_draws.comp"}, VK_SHADER_STAGE_COMPUTE_BIT,
                                      sizeof(gpu::PageSetupPush));
    mSetup = vk::createComputePipeline(ctx, mSetupLayout, "page_draws.comp");
    mClearLayout = vk::createLayoutOf(ctx, {"page_clear.vert"}, VK_SHADER_STAGE_VERTEX_BIT,
                                      sizeof(gpu::PageDrawPush));
    mClear = vk::createGraphicsPipeline(ctx, mClearLayout,
                                        {.vertexShader = "page_clear.vert",
                                         .depthFormat = kDepthFormat,
                                         .depthCompare = VK_COMPARE_OP_ALWAYS});
    mOpaqueLayout = vk::createLayoutOf(ctx, {"page_position.vert"}, VK_SHADER_STAGE_VERTEX_BIT,
                                       sizeof(gpu::PageDrawPush));
    mMaskedLayout = vk::createLayoutOf(ctx, {"page_depth.vert", "shadow_mask.frag"}, kGraphics,
                                       sizeof(gpu::PageDrawPush) + sizeof(gpu::MaterialPush));
    // A sun's levels clamp depth (casters nearer than the light's window still cast), as the
    // host path's orthographic pipelines.
    for (uint32_t kind : {PAGE_DRAW_ORTHO, PAGE_DRAW_PERSPECTIVE}) {
        const bool clamp = kind == PAGE_DRAW_ORTHO;
        mOpaque[kind] = vk::createGraphicsPipeline(ctx, mOpaqueLayout,
                                                   pageDesc("page_position.vert", clamp, false));
        mMasked[kind] = vk::createGraphicsPipeline(ctx, mMaskedLayout,
                                                   pageDesc("page_depth.vert", clamp, true));
    }
    mListCounts = vk::createBuffer(
        ctx, 16,
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
            VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        readable ? vk::MemoryUse::Readback : vk::MemoryUse::DeviceLocal, "page draw list counts");
}

void PageDrawPasses::prepare(const std::vector<VirtualLevel>& levels, uint32_t slotIndex) {
    Slot& slot = mSlots.at(slotIndex);
    std::vector<gpu::PageViewData> views;
    for (const VirtualLevel& l : levels)
        views.push_back(
            {.viewProj = l.projection.viewProj,
             .kind = glm::uvec4(l.projection.perspective ? PAGE_DRAW_PERSPECTIVE : PAGE_DRAW_ORTHO,
                                0, 0, 0)});
    const size_t bytes = std::max<size_t>(views.size() * sizeof(gpu::PageViewData), 16);
    if (slot.views.size < bytes)
        slot.views = vk::createBuffer(mCtx, std::max<size_t>(bytes, 2 * slot.views.size),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload,
                                      "page views");
    std::memcpy(slot.views.mapped, views.data(), views.size() * sizeof(gpu::PageViewData));
}

void PageDrawPasses::recordLists(VkCommandBuffer cmd, const PageDecisionPasses& decisions,
                                 uint32_t poolPagesPerSide, uint32_t slotIndex) {
    Slot& slot = mSlots.at(slotIndex);
    const uint32_t pages = decisions.poolPages();
    if (mListPages < pages) {
        mList = vk::createBuffer(
            mCtx, 2 * size_t{pages} * sizeof(gpu::PageDrawData), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
            mReadable ? vk::MemoryUse::Readback : vk::MemoryUse::DeviceLocal, "page draw lists");
        mListPages = pages;
    }
    mListedPages = pages;
    vkCmdFillBuffer(cmd, mListCounts.get(), 0, VK_WHOLE_SIZE, 0u);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mSetup.get());
    vk::PushDescriptors()
        .storageBuffer(PAGE_DRAW_LEVELS, decisions.levels(slotIndex))
        .storageBuffer(PAGE_DRAW_VIEWS, slot.views.get())
        .storageBuffer(PAGE_DRAW_RENDER, decisions.renderList())
        .storageBuffer(PAGE_DRAW_COUNTS, decisions.countsBuffer(slotIndex))
        .storageBuffer(PAGE_DRAW_LIST, mList.get())
        .storageBuffer(PAGE_DRAW_LIST_COUNTS, mListCounts.get())
        .push(mCtx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mSetupLayout);
    const gpu::PageSetupPush setup{.pages = pages,
                                   .poolPagesPerSide = poolPagesPerSide,
                                   .levelCount = decisions.levelCount(slotIndex)};
    vkCmdPushConstants(cmd, mSetupLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof setup,
                       &setup);
    vkCmdDispatch(cmd, groupsOf(pages), 1, 1);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_HOST_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                          VK_ACCESS_2_HOST_READ_BIT);
}

std::vector<gpu::PageDrawData> PageDrawPasses::listed(uint32_t kind) const {
    PENUMBRA_CHECK(mReadable && kind < 2, "PageDrawPasses: read back from device memory");
    const uint32_t length = static_cast<const uint32_t*>(mListCounts.mapped)[kind];
    const auto* first = static_cast<const gpu::PageDrawData*>(mList.mapped) + kind * mListedPages;
    return {first, first + length};
}

void PageDrawPasses::record(VkCommandBuffer cmd, const PageDecisionPasses& decisions,
                            const GpuScene& scene, const PooledImage& pool,
                            uint32_t poolPagesPerSide, float constantBias, float slopeBias,
                            uint32_t slotIndex) {
    Slot& slot = mSlots.at(slotIndex);
    const uint32_t pages = decisions.poolPages();
    // The indirect draws: the clear (6 vertices a page), then per list the opaque casters and
    // each alpha-tested batch. Instance counts come from the device below.
    std::vector<uint32_t> masked;
    for (uint32_t b = 0; b < scene.batches.size(); ++b)
        if (scene.batches[b].firstIndex >= scene.opaqueIndexCount)
            masked.push_back(b);
    const bool opaque = scene.opaqueIndexCount > 0;
    std::vector<VkDrawIndexedIndirectCommand> draws;
    for (uint32_t kind = 0; kind < 2; ++kind) {
        if (opaque)
            draws.push_back({.indexCount = scene.opaqueIndexCount, .firstIndex = 0});
        for (uint32_t b : masked)
            draws.push_back({.indexCount = scene.batches[b].indexCount,
                             .firstIndex = scene.batches[b].firstIndex});
    }
    const size_t perList = draws.size() / 2;
    constexpr VkDeviceSize kDrawsAt = sizeof(VkDrawIndirectCommand);
    const size_t bytes = kDrawsAt + draws.size() * sizeof(VkDrawIndexedIndirectCommand);
    if (slot.commands.size < bytes)
        slot.commands = vk::createBuffer(
            mCtx, bytes, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
            vk::MemoryUse::Upload, "page draw commands");
    const VkDrawIndirectCommand clear{.vertexCount = 6};
    std::memcpy(slot.commands.mapped, &clear, sizeof clear);
    std::memcpy(static_cast<std::byte*>(slot.commands.mapped) + kDrawsAt, draws.data(),
                draws.size() * sizeof(VkDrawIndexedIndirectCommand));

    recordLists(cmd, decisions, poolPagesPerSide, slotIndex);
    // The instance counts: the clear's from the pages rendered, each list's draws from its length.
    const VkBufferCopy rendered{.srcOffset = offsetof(gpu::PageCounts, rendered),
                                .dstOffset = offsetof(VkDrawIndirectCommand, instanceCount),
                                .size = sizeof(uint32_t)};
    vkCmdCopyBuffer(cmd, decisions.countsBuffer(slotIndex), slot.commands.get(), 1, &rendered);
    std::vector<VkBufferCopy> lengths;
    for (size_t d = 0; d < draws.size(); ++d)
        lengths.push_back({.srcOffset = (d / perList) * sizeof(uint32_t),
                           .dstOffset = kDrawsAt + d * sizeof(VkDrawIndexedIndirectCommand) +
                                        offsetof(VkDrawIndexedIndirectCommand, instanceCount),
                           .size = sizeof(uint32_t)});
    if (!lengths.empty())
        vkCmdCopyBuffer(cmd, mListCounts.get(), slot.commands.get(),
                        static_cast<uint32_t>(lengths.size()), lengths.data());
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);

    // The pool, one viewport; what it holds elsewhere is kept.
    const vk::Image& image = pool.get();
    const VkRenderingAttachmentInfo depth{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                          .imageView = pool.layer(0),
                                          .imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                          .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
                                          .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
    const VkRect2D area{{0, 0}, {image.width, image.height}};
    const VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                               .renderArea = area,
                               .layerCount = 1,
                               .pDepthAttachment = &depth};
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport{.width = static_cast<float>(image.width),
                              .height = static_cast<float>(image.height),
                              .maxDepth = 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    gpu::PageDrawPush push{.bias = {constantBias, 0, 0, 0},
                           .list = {0, pages, poolPagesPerSide, 0}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mClear.get());
    vk::PushDescriptors()
        .storageBuffer(PAGE_DRAW_RENDER, decisions.renderList())
        .push(mCtx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mClearLayout);
    vkCmdPushConstants(cmd, mClearLayout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push, &push);
    vkCmdDrawIndirect(cmd, slot.commands.get(), 0, 1, sizeof(VkDrawIndirectCommand));

    vkCmdBindIndexBuffer(cmd, scene.indices.get(), 0, VK_INDEX_TYPE_UINT32);
    const VkDeviceSize noOffset = 0;
    for (uint32_t kind = 0; kind < 2; ++kind) {
        push.list.x = kind;
        VkDeviceSize at = kDrawsAt + kind * perList * sizeof(VkDrawIndexedIndirectCommand);
        if (opaque) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mOpaque[kind].get());
            vkCmdSetDepthBias(cmd, 0.0f, 0.0f, slopeBias);
            const VkBuffer positions = scene.positions.get();
            vkCmdBindVertexBuffers(cmd, 0, 1, &positions, &noOffset);
            vk::PushDescriptors()
                .storageBuffer(PAGE_DRAW_LIST, mList.get())
                .push(mCtx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mOpaqueLayout);
            vkCmdPushConstants(cmd, mOpaqueLayout.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push,
                               &push);
            vkCmdDrawIndexedIndirect(cmd, slot.commands.get(), at, 1,
                                     sizeof(VkDrawIndexedIndirectCommand));
            at += sizeof(VkDrawIndexedIndirectCommand);
        }
        if (masked.empty())
            continue;
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mMasked[kind].get());
        vkCmdSetDepthBias(cmd, 0.0f, 0.0f, slopeBias);
        const VkBuffer vertices = scene.vertices.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &noOffset);
        for (uint32_t b : masked) {
            const GpuScene::Material& material = scene.materials[scene.batches[b].material];
            vk::PushDescriptors()
                .storageBuffer(PAGE_DRAW_LIST, mList.get())
                .sampled(MASK_TEXTURE, material.texture.view, material.texture.sampler)
                .push(mCtx, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mMaskedLayout);
            struct {
                gpu::PageDrawPush page;
                gpu::MaterialPush material;
            } both{push, material.constants};
            vkCmdPushConstants(cmd, mMaskedLayout.get(), kGraphics, 0, sizeof both, &both);
            vkCmdDrawIndexedIndirect(cmd, slot.commands.get(), at, 1,
                                     sizeof(VkDrawIndexedIndirectCommand));
            at += sizeof(VkDrawIndexedIndirectCommand);
        }
    }
    vkCmdEndRendering(cmd);
}

} // namespace penumbra::render
