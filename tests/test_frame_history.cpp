// History resources of the frame graph (src/render/frame_history.cpp): last frame's version of an
// image or buffer declared with Lifetime::History, run on the device frame after frame. Each
// frame writes its number into this frame's version and copies last frame's to the host; what
// the host reads says which frame's contents the graph handed over, and that a history that
// holds nothing (the first frame, a cut, a new key or size, a frame that did not write it) reads
// as zeros.
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

const FrameSizes kSizes{.width = 4, .height = 2};

ImageDecl historyImage(uint64_t key = 0) {
    return {.name = "accumulated",
            .size = SizeClass::Screen,
            .format = VK_FORMAT_R32_SFLOAT,
            // Written as an attachment: the graph's clear needs a usage it adds itself.
            .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
            .lifetime = Lifetime::History,
            .key = key};
}

struct Frame {
    float value = 0.0f; // what this frame writes (none when 0)
    uint64_t key = 0;   // the history's key
    FrameSizes sizes = kSizes;
};

// What one frame's reader found in last frame's version (every pixel, which must agree), and
// whether the graph said the history was valid.
struct Seen {
    float value = -1.0f;
    bool valid = false;
};

Seen runFrame(ResourcePool& pool, const Frame& f) {
    FrameGraph graph(pool, f.sizes);
    const ResourceId now = graph.declare(historyImage(f.key));
    EXPECT_EQ(graph.declare(historyImage(f.key)), now) << "declared twice, swapped once";
    const ResourceId last = graph.previous(now);
    const ResourceId host = graph.declare(BufferDecl{.name = "host",
                                                     .size = SizeClass::Screen,
                                                     .bytes = 4,
                                                     .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                     .memory = vk::MemoryUse::Readback});
    Seen seen{.valid = graph.historyValid(now)};
    graph.addPass({.name = "",
                   .phase = Phase::Readback,
                   .uses = {{last, Access::TransferRead}, {host, Access::TransferWrite}},
                   .record = [&](PassContext& c) {
                       vk::copyImageToBuffer(c.cmd, c.image(last).get(), c.buffer(host));
                   }});
    if (f.value != 0.0f)
        graph.addPass({.name = "write",
                       .cost = CostGroup::PerPixel,
                       .phase = Phase::PerLight,
                       .uses = {{now, Access::ColorAttachment}},
                       .record = [&](PassContext& c) {
                           const VkRenderingAttachmentInfo color{
                               .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                               .imageView = c.image(now).view(),
                               .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                               .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                               .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                               .clearValue = {.color = {.float32 = {f.value, 0, 0, 0}}}};
                           const VkRenderingInfo rendering{
                               .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                               .renderArea = {{0, 0}, {f.sizes.width, f.sizes.height}},
                               .layerCount = 1,
                               .colorAttachmentCount = 1,
                               .pColorAttachments = &color};
                           vkCmdBeginRendering(c.cmd, &rendering);
                           vkCmdEndRendering(c.cmd);
                       }});
    graph.plan();
    EXPECT_TRUE(graph.culled().empty()) << "a write of this frame's version is never culled";
    sharedRenderer().context().submitAndWait(
        [&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
    std::vector<float> read(size_t{f.sizes.width} * f.sizes.height);
    std::memcpy(read.data(), pool.mapped("host"), read.size() * sizeof(float));
    seen.value = read.front();
    for (float v : read)
        EXPECT_EQ(v, seen.value) << "every pixel of last frame's version alike";
    return seen;
}

} // namespace

TEST_F(FrameTest, AHistoryResourceReadsWhatLastFrameWrote) {
    ResourcePool pool(sharedRenderer().context());
    // Frame 0 has no history; frames 1 and 2 read the frame before's.
    EXPECT_FALSE(runFrame(pool, {.value = 1}).valid);
    const Seen second = runFrame(pool, {.value = 2});
    EXPECT_TRUE(second.valid);
    EXPECT_EQ(second.value, 1.0f);
    const Seen third = runFrame(pool, {.value = 3});
    EXPECT_TRUE(third.valid);
    EXPECT_EQ(third.value, 2.0f) << "last frame's, not the one before (the versions swap)";
    EXPECT_EQ(pool.creations(), 3u) << "two versions and the host buffer, made once";
}

TEST_F(FrameTest, AHistoryThatHoldsNothingIsClearedAndSaidInvalid) {
    ResourcePool pool(sharedRenderer().context());
    EXPECT_EQ(runFrame(pool, {.value = 1}).value, 0.0f) << "the first frame reads zeros";
    // A cut: the next frame's history holds nothing, the one after reads again.
    runFrame(pool, {.value = 2});
    pool.invalidateHistory();
    const Seen cut = runFrame(pool, {.value = 3});
    EXPECT_FALSE(cut.valid);
    EXPECT_EQ(cut.value, 0.0f);
    const Seen after = runFrame(pool, {.value = 4});
    EXPECT_TRUE(after.valid) << "a cut lasts one frame";
    EXPECT_EQ(after.value, 3.0f);
    // A new key.
    const Seen rekeyed = runFrame(pool, {.value = 5, .key = 1});
    EXPECT_FALSE(rekeyed.valid);
    EXPECT_EQ(rekeyed.value, 0.0f);
    EXPECT_EQ(runFrame(pool, {.value = 6, .key = 1}).value, 5.0f);
    // A frame that does not write it leaves the next one nothing.
    EXPECT_EQ(runFrame(pool, {.value = 0, .key = 1}).value, 6.0f);
    const Seen skipped = runFrame(pool, {.value = 7, .key = 1});
    EXPECT_FALSE(skipped.valid);
    EXPECT_EQ(skipped.value, 0.0f);
    // A new size.
    const Seen resized = runFrame(pool, {.value = 8, .key = 1, .sizes = {.width = 6, .height = 2}});
    EXPECT_FALSE(resized.valid);
    EXPECT_EQ(resized.value, 0.0f);
    EXPECT_EQ(runFrame(pool, {.value = 9, .key = 1, .sizes = {.width = 6, .height = 2}}).value,
              8.0f);
}

TEST_F(FrameTest, AValidHistoryIsReadAsItIsAndABufferHasOneToo) {
    ResourcePool pool(sharedRenderer().context());
    for (int frame = 0; frame < 3; ++frame) {
        FrameGraph graph(pool, kSizes);
        const ResourceId now = graph.declare(BufferDecl{.name = "counts",
                                                        .size = SizeClass::Fixed,
                                                        .bytes = 16,
                                                        .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                        .lifetime = Lifetime::History});
        const ResourceId host = graph.declare(BufferDecl{.name = "host",
                                                         .size = SizeClass::Fixed,
                                                         .bytes = 16,
                                                         .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                         .memory = vk::MemoryUse::Readback});
        const ResourceId last = graph.previous(now);
        const uint32_t word = 10u + static_cast<uint32_t>(frame);
        graph.addPass({.name = "",
                       .phase = Phase::Readback,
                       .uses = {{last, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           const VkBufferCopy all{.size = 16};
                           vkCmdCopyBuffer(c.cmd, c.buffer(last), c.buffer(host), 1, &all);
                       }});
        graph.addPass({.name = "",
                       .phase = Phase::Composite,
                       .uses = {{now, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           vkCmdFillBuffer(c.cmd, c.buffer(now), 0, 16, word);
                       }});
        // Only a history that holds nothing gets the graph's clear ahead of every pass.
        EXPECT_EQ(graph.plan().size(), frame == 0 ? 3u : 2u) << "frame " << frame;
        sharedRenderer().context().submitAndWait(
            [&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        uint32_t read[4];
        std::memcpy(read, pool.mapped("host"), sizeof(read));
        for (uint32_t w : read)
            EXPECT_EQ(w, frame == 0 ? 0u : word - 1) << "frame " << frame;
    }
}

TEST_F(FrameTest, LastFramesVersionIsOnlyRead) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            ResourcePool pool(sharedRenderer().context());
            FrameGraph graph(pool, kSizes);
            const ResourceId last = graph.previous(graph.declare(historyImage()));
            graph.addPass({.name = "",
                           .phase = Phase::PerLight,
                           .uses = {{last, Access::TransferWrite}},
                           .record = [](PassContext&) {}});
        },
        "writes accumulated \\(previous\\), last frame's version");
    EXPECT_DEATH(
        {
            ResourcePool pool(sharedRenderer().context());
            FrameGraph graph(pool, kSizes);
            ImageDecl plain = historyImage();
            plain.lifetime = Lifetime::PerFrame;
            graph.previous(graph.declare(plain));
        },
        "accumulated is not declared with history");
}
