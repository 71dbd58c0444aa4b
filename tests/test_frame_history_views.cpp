// History resources beyond one plain colour image (src/render/frame_history.cpp and the pool's
// swap): an image written through its layer and level views, a depth image, a buffer the host
// maps, and a history whose only reader is culled. Each frame writes values that name the frame,
// the layer and the level; what last frame's version holds says whether every handle swapped.
#include "frame_clears.h"
#include "gpu_fixture.h"
#include "render/frame_graph.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/sync.h"

#include <cstring>

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

namespace {

const FrameSizes kSizes{.width = 2, .height = 2};
constexpr uint32_t kLayers = 2;

// What frame `frame` writes into layer `layer` at mip level `level`.
float written(int frame, uint32_t layer, uint32_t level) {
    return static_cast<float>(100 * frame + 10 * static_cast<int>(level) + static_cast<int>(layer));
}

ResourceId readbackOf(FrameGraph& graph, VkDeviceSize bytes) {
    return graph.declare(BufferDecl{.name = "host",
                                    .size = SizeClass::Fixed,
                                    .bytes = bytes,
                                    .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    .memory = vk::MemoryUse::Readback});
}

} // namespace

// Written through a view per layer and per level, read back whole: a swap that left the views
// behind would write last frame's image (or read this frame's). Its reader runs in the first
// phase, beside the graph's own clear.
TEST_F(FrameTest, AHistoryWrittenThroughItsLayerAndLevelViewsSwapsThemToo) {
    ResourcePool pool(sharedRenderer().context());
    const ImageDecl decl{.name = "pyramid",
                         .size = SizeClass::Fixed,
                         .format = VK_FORMAT_R32_SFLOAT,
                         .usage =
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                         .width = 2,
                         .height = 2,
                         .layers = kLayers,
                         .mipmapped = true, // 2x2 and 1x1
                         .layerViews = true,
                         .lifetime = Lifetime::History};
    constexpr uint32_t kTexels = kLayers * (4 + 1);
    for (int frame = 1; frame <= 3; ++frame) {
        FrameGraph graph(pool, kSizes);
        const ResourceId now = graph.declare(decl);
        const ResourceId last = graph.previous(now);
        const ResourceId host = readbackOf(graph, kTexels * sizeof(float));
        graph.addPass({.name = "",
                       .phase = Phase::LightSpace,
                       .uses = {{last, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           const vk::Image& image = c.image(last).get();
                           const VkBufferImageCopy levels[] = {
                               {.bufferOffset = 0,
                                .imageSubresource = {image.aspect, 0, 0, kLayers},
                                .imageExtent = {2, 2, 1}},
                               {.bufferOffset = kLayers * 4 * sizeof(float),
                                .imageSubresource = {image.aspect, 1, 0, kLayers},
                                .imageExtent = {1, 1, 1}}};
                           vkCmdCopyImageToBuffer(c.cmd, image.get(),
                                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                  c.buffer(host), 2, levels);
                       }});
        graph.addPass({.name = "write",
                       .cost = CostGroup::PerPixel,
                       .phase = Phase::PerLight,
                       .uses = {{now, Access::ColorAttachment}},
                       .record = [&](PassContext& c) {
                           for (uint32_t l = 0; l < kLayers; ++l) {
                               clearThrough(c.cmd, c.image(now).layer(l), {2, 2}, false,
                                            written(frame, l, 0));
                               clearThrough(c.cmd, c.image(now).level(l, 1), {1, 1}, false,
                                            written(frame, l, 1));
                           }
                       }});
        graph.plan();
        sharedRenderer().context().submitAndWait(
            [&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        float read[kTexels];
        std::memcpy(read, pool.mapped("host"), sizeof(read));
        for (uint32_t l = 0; l < kLayers; ++l) {
            const float level0 = frame == 1 ? 0.0f : written(frame - 1, l, 0);
            const float level1 = frame == 1 ? 0.0f : written(frame - 1, l, 1);
            for (uint32_t t = 0; t < 4; ++t)
                EXPECT_EQ(read[l * 4 + t], level0) << "frame " << frame << " layer " << l;
            EXPECT_EQ(read[kLayers * 4 + l], level1) << "frame " << frame << " layer " << l;
        }
    }
}

// A depth history takes the graph's depth clear (to zero) and hands last frame's depth over.
TEST_F(FrameTest, ADepthHistoryIsClearedAsDepthAndHandedOver) {
    ResourcePool pool(sharedRenderer().context());
    const ImageDecl decl{.name = "depth kept",
                         .size = SizeClass::Screen,
                         .format = VK_FORMAT_D32_SFLOAT,
                         .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                         .lifetime = Lifetime::History};
    for (int frame = 1; frame <= 2; ++frame) {
        FrameGraph graph(pool, kSizes);
        const ResourceId now = graph.declare(decl);
        const ResourceId last = graph.previous(now);
        const ResourceId host = readbackOf(graph, 4 * sizeof(float));
        graph.addPass({.name = "",
                       .phase = Phase::GBuffer,
                       .uses = {{last, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           vk::copyImageToBuffer(c.cmd, c.image(last).get(), c.buffer(host));
                       }});
        graph.addPass({.name = "",
                       .phase = Phase::PerLight,
                       .uses = {{now, Access::DepthAttachment}},
                       .record = [&](PassContext& c) {
                           clearThrough(c.cmd, c.image(now).view(), {2, 2}, true,
                                        0.25f * static_cast<float>(frame));
                       }});
        graph.plan();
        sharedRenderer().context().submitAndWait(
            [&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        float read[4];
        std::memcpy(read, pool.mapped("host"), sizeof(read));
        for (float d : read)
            EXPECT_EQ(d, frame == 1 ? 0.0f : 0.25f) << "frame " << frame;
    }
}

// A history buffer the host maps: the host reads each version where the graph says it is.
TEST_F(FrameTest, AMappedHistoryBufferIsMappedWhereItsVersionIs) {
    ResourcePool pool(sharedRenderer().context());
    const BufferDecl decl{.name = "tally",
                          .size = SizeClass::Fixed,
                          .bytes = 16,
                          .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          .memory = vk::MemoryUse::Readback,
                          .lifetime = Lifetime::History};
    for (uint32_t frame = 1; frame <= 3; ++frame) {
        FrameGraph graph(pool, kSizes);
        const ResourceId now = graph.declare(decl);
        graph.addPass({.name = "",
                       .phase = Phase::Composite,
                       .uses = {{now, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           vkCmdFillBuffer(c.cmd, c.buffer(now), 0, 16, 7 * frame);
                       }});
        graph.plan();
        sharedRenderer().context().submitAndWait(
            [&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        uint32_t current = 0;
        std::memcpy(&current, pool.mapped("tally"), sizeof(current));
        EXPECT_EQ(current, 7 * frame);
        if (frame > 1) {
            uint32_t previous = 0;
            std::memcpy(&previous, pool.mapped("tally (previous)"), sizeof(previous));
            EXPECT_EQ(previous, 7 * (frame - 1));
        }
    }
}

// Last frame's version only matters to its readers: when they are culled, so is its clear.
TEST_F(FrameTest, AHistoryWhoseReaderIsCulledIsNotCleared) {
    ResourcePool pool(sharedRenderer().context());
    FrameGraph graph(pool, kSizes);
    const ResourceId now = graph.declare(BufferDecl{.name = "kept",
                                                    .size = SizeClass::Fixed,
                                                    .bytes = 16,
                                                    .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                    .lifetime = Lifetime::History});
    const ResourceId unread = graph.declare(BufferDecl{.name = "unread",
                                                       .size = SizeClass::Fixed,
                                                       .bytes = 16,
                                                       .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT});
    graph.addPass(
        {.name = "",
         .phase = Phase::PerLight,
         .uses = {{graph.previous(now), Access::TransferRead}, {unread, Access::TransferWrite}},
         .record = [](PassContext&) {}});
    graph.addPass({.name = "",
                   .phase = Phase::PerLight,
                   .uses = {{now, Access::TransferWrite}},
                   .record = [](PassContext&) {}});
    EXPECT_EQ(graph.plan().size(), 1u) << "this frame's write alone";
    EXPECT_EQ(graph.culled().size(), 2u) << "the reader and the clear of what it read";
}
