// The frame graph (src/render/frame_graph.h) on its own: the order it gives passes, the barriers
// it places, and what its pool keeps across frames; then a small graph run on the device, with
// synchronization validation watching every barrier it placed (a missing one is a validation
// message, which fails the test).
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

const vk::Context& context() {
    return sharedRenderer().context();
}

ImageDecl screenImage(std::string name, Lifetime lifetime = Lifetime::PerFrame) {
    return {.name = std::move(name),
            .size = SizeClass::Screen,
            .format = VK_FORMAT_R32_SFLOAT,
            .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
            .lifetime = lifetime};
}

PassDecl pass(std::string name, Phase phase, std::vector<Use> uses) {
    return {.name = std::move(name),
            .phase = phase,
            .uses = std::move(uses),
            .record = [](PassContext&) {}};
}

// The planned passes' names, in order.
std::vector<std::string> order(FrameGraph& graph) {
    std::vector<std::string> names;
    for (const PlannedPass& p : graph.plan())
        names.push_back(graph.passes()[p.pass].name);
    return names;
}

const FrameSizes kSizes{
    .width = 8, .height = 4, .shadowMapSize = 16, .shadowViews = 2, .shadowLights = 1};

} // namespace

TEST_F(FrameTest, PassesRunByPhaseThenInTheOrderTheyWereDeclared) {
    ResourcePool pool(context());
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(screenImage("a"));
    const ResourceId b = graph.declare(screenImage("b"));
    // Declared out of phase order: a composite, a light-space pass, per-light passes, a G-buffer.
    graph.addPass(pass("composite", Phase::Composite, {{b, Access::ComputeSampled}}));
    graph.addPass(
        pass("light", Phase::PerLight, {{a, Access::ComputeSampled}, {b, Access::ComputeWrite}}));
    graph.addPass(pass("layer", Phase::PerLight, {{b, Access::ComputeReadWrite}}));
    graph.addPass(pass("screen", Phase::ScreenSpace, {{a, Access::ComputeReadWrite}}));
    graph.addPass(pass("gbuffer", Phase::GBuffer, {{a, Access::ComputeWrite}}));
    graph.addPass(pass("shadow", Phase::LightSpace, {}));
    EXPECT_EQ(order(graph), (std::vector<std::string>{"shadow", "gbuffer", "screen", "light",
                                                      "layer", "composite"}));
}

TEST_F(FrameTest, BarriersFollowEveryHazardAndNoneBetweenReads) {
    ResourcePool pool(context());
    FrameGraph graph(pool, kSizes);
    const ResourceId image = graph.declare(screenImage("image"));
    graph.addPass(pass("write", Phase::PerLight, {{image, Access::ComputeWrite}}));
    graph.addPass(pass("read", Phase::PerLight, {{image, Access::ComputeSampled}}));
    graph.addPass(pass("read again", Phase::PerLight, {{image, Access::ComputeSampled}}));
    graph.addPass(pass("rewrite", Phase::Composite, {{image, Access::ComputeReadWrite}}));
    graph.addPass(pass("copy", Phase::Readback, {{image, Access::TransferRead}}));
    const std::vector<PlannedPass>& plan = graph.plan();
    ASSERT_EQ(plan.size(), 5u);
    // A per-frame image first written: its old contents go (from "undefined").
    ASSERT_EQ(plan[0].barriers.size(), 1u);
    EXPECT_TRUE(plan[0].barriers[0].fromUndefined);
    EXPECT_EQ(plan[0].barriers[0].to, Access::ComputeWrite);
    // Read after write.
    ASSERT_EQ(plan[1].barriers.size(), 1u);
    EXPECT_FALSE(plan[1].barriers[0].fromUndefined);
    EXPECT_EQ(plan[1].barriers[0].from, Access::ComputeWrite);
    EXPECT_EQ(plan[1].barriers[0].to, Access::ComputeSampled);
    // Two reads in the same state: nothing between them.
    EXPECT_TRUE(plan[2].barriers.empty());
    // Write after read, then read after write.
    ASSERT_EQ(plan[3].barriers.size(), 1u);
    EXPECT_EQ(plan[3].barriers[0].from, Access::ComputeSampled);
    ASSERT_EQ(plan[4].barriers.size(), 1u);
    EXPECT_EQ(plan[4].barriers[0].from, Access::ComputeReadWrite);
    EXPECT_EQ(plan[4].barriers[0].to, Access::TransferRead);
}

TEST_F(FrameTest, TwoWritesInTheSameStateStillWaitForEachOther) {
    ResourcePool pool(context());
    FrameGraph graph(pool, kSizes);
    const ResourceId image = graph.declare(screenImage("image"));
    graph.addPass(pass("write", Phase::PerLight, {{image, Access::ComputeWrite}}));
    graph.addPass(pass("layer", Phase::PerLight, {{image, Access::ComputeReadWrite}}));
    graph.addPass(pass("layer again", Phase::PerLight, {{image, Access::ComputeReadWrite}}));
    const std::vector<PlannedPass>& plan = graph.plan();
    ASSERT_EQ(plan.size(), 3u);
    // Write after write, the layout unchanged: two layers multiplying the visibility in place.
    ASSERT_EQ(plan[2].barriers.size(), 1u);
    EXPECT_EQ(plan[2].barriers[0].from, Access::ComputeReadWrite);
    EXPECT_EQ(plan[2].barriers[0].to, Access::ComputeReadWrite);
}

TEST_F(FrameTest, ThePoolKeepsWhatIsDeclaredAlikeAndPersistentContentsUnderTheirKey) {
    ResourcePool pool(context());
    const vk::Image* first = nullptr;
    for (int frame = 0; frame < 3; ++frame) {
        FrameGraph graph(pool, kSizes);
        ImageDecl cache = screenImage("cache", Lifetime::Persistent);
        cache.key = frame < 2 ? 7 : 8; // the third frame's key differs: contents invalid
        const ResourceId id = graph.declare(cache);
        graph.declare(screenImage("scratch"));
        // A producer writes the cache only when it does not hold its contents.
        const bool holds = graph.holdsContents(id);
        EXPECT_EQ(holds, frame == 1) << "frame " << frame;
        graph.addPass(pass("produce", Phase::ScreenSpace,
                           {{id, holds ? Access::ComputeSampled : Access::ComputeWrite}}));
        const std::vector<PlannedPass>& plan = graph.plan();
        // A persistent resource's contents are never dropped: from "undefined" only when it
        // has never been used.
        ASSERT_EQ(plan[0].barriers.size(), 1u);
        EXPECT_EQ(plan[0].barriers[0].fromUndefined, frame == 0) << "frame " << frame;
        context().submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        if (frame == 0)
            first = &graph.image(id).get();
        else // kept, even under a new key: only its contents lapse
            EXPECT_EQ(&graph.image(id).get(), first) << "frame " << frame;
    }
    EXPECT_EQ(pool.creations(), 2u); // "cache" and "scratch", once each
    // A declaration that changes (another size) remakes the resource; one no frame declares
    // any more is freed.
    FrameGraph bigger(pool, {.width = 16, .height = 4});
    bigger.declare(screenImage("cache", Lifetime::Persistent));
    bigger.plan();
    EXPECT_EQ(pool.creations(), 3u);
    EXPECT_EQ(pool.findImage("scratch"), nullptr);
    EXPECT_EQ(pool.findImage("cache")->get().width, 16u);
}

TEST_F(FrameTest, ReadingWhatNothingWroteIsAProgrammerError) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            ResourcePool pool(context());
            FrameGraph graph(pool, kSizes);
            const ResourceId image = graph.declare(screenImage("never written"));
            graph.addPass(pass("read", Phase::PerLight, {{image, Access::ComputeSampled}}));
            graph.plan();
        },
        "reads never written, which no earlier pass writes");
}

// A graph of transfers on the device: an image cleared, copied into a buffer, that buffer
// copied into a second one and read by the host. The values arrive only if each barrier the
// graph placed is there; synchronization validation reports any it missed.
TEST_F(FrameTest, AGraphOfImagesAndBuffersRunsWithoutAHazard) {
    ResourcePool pool(context());
    for (int frame = 0; frame < 2; ++frame) { // the second starts from the first's states
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image"));
        const ResourceId staging = graph.declare(BufferDecl{
            .name = "staging",
            .size = SizeClass::Screen,
            .bytes = 4,
            .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT});
        const ResourceId host = graph.declare(BufferDecl{.name = "host",
                                                         .size = SizeClass::Screen,
                                                         .bytes = 4,
                                                         .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                         .memory = vk::MemoryUse::Readback});
        const float value = 0.25f + static_cast<float>(frame);
        // Declared in reverse: the phases put them in order.
        graph.addPass({.name = "",
                       .phase = Phase::Readback,
                       .uses = {{host, Access::HostRead}},
                       .record = [](PassContext&) {}});
        graph.addPass({.name = "copy buffer",
                       .phase = Phase::Composite,
                       .uses = {{staging, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           const VkBufferCopy region{.size = 4 * 8 * 4};
                           vkCmdCopyBuffer(c.cmd, c.buffer(staging), c.buffer(host), 1, &region);
                       }});
        graph.addPass({.name = "copy image",
                       .phase = Phase::PerLight,
                       .uses = {{image, Access::TransferRead}, {staging, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           vk::copyImageToBuffer(c.cmd, c.image(image).get(), c.buffer(staging));
                       }});
        graph.addPass(
            {.name = "clear",
             .phase = Phase::GBuffer,
             .uses = {{image, Access::TransferWrite}},
             .record = [&](PassContext& c) {
                 const VkClearColorValue clear{.float32 = {value, 0, 0, 0}};
                 const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                 vkCmdClearColorImage(c.cmd, c.image(image).get().get(),
                                      VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
             }});
        EXPECT_EQ(order(graph),
                  (std::vector<std::string>{"clear", "copy image", "copy buffer", ""}));
        context().submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        std::vector<float> read(8 * 4);
        std::memcpy(read.data(), pool.mapped("host"), read.size() * sizeof(float));
        for (float v : read)
            ASSERT_EQ(v, value) << "frame " << frame;
    }
}

// What Renderer::check counts for a buffer of each size class: per view times the views (at
// least one), per pixel times the pixels, the declared bytes otherwise.
TEST_F(FrameTest, BufferBytesFollowTheirSizeClass) {
    const FrameSizes sizes{.width = 30, .height = 20, .shadowMapSize = 64, .shadowViews = 6};
    const auto bytes = [&](SizeClass size, const FrameSizes& s) {
        return ResourcePool::bytesOf(BufferDecl{.name = "b", .size = size, .bytes = 12, .usage = 0},
                                     s);
    };
    EXPECT_EQ(bytes(SizeClass::ShadowView, sizes), 12u * 6u);
    EXPECT_EQ(bytes(SizeClass::ShadowView, FrameSizes{}), 12u) << "no view: room for one";
    EXPECT_EQ(bytes(SizeClass::Screen, sizes), 12u * 30u * 20u);
    EXPECT_EQ(bytes(SizeClass::Scene, sizes), 12u);
    EXPECT_EQ(bytes(SizeClass::Fixed, sizes), 12u);
}
