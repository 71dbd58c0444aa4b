// The frame graph (src/render/frame_graph.h) on its own: the order it gives passes, the barriers
// it places, and what its pool keeps across frames; then a small graph run on the device, with
// synchronization validation watching every barrier it placed (a missing one is a validation
// message, which fails the test). What the graph refuses: test_frame_graph_checks.cpp.
#include "frame_graph_passes.h"
#include "vk/resources.h"
#include "vk/sync.h"

#include <algorithm>
#include <cstring>
#include <optional>

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

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

// b takes a's memory after a's last read: b's first write waits for that read (the barrier's
// `after`), and b's second read, after b's first, waits for nothing: the memory it shares was
// handed over once, at b's first use.
TEST_F(FrameTest, MemoryHandedOverWaitsOnceAtItsFirstUse) {
    ResourcePool pool(context());
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(screenImage("a"));
    const ResourceId b = graph.declare(screenImage("b"));
    graph.addPass(pass("write a", Phase::PerLight, {{a, Access::ComputeWrite}}));
    graph.addPass(pass("read a", Phase::PerLight, {{a, Access::ComputeSampled}}));
    graph.addPass(pass("write b", Phase::Composite, {{b, Access::ComputeWrite}}));
    graph.addPass(pass("read b", Phase::Composite, {{b, Access::ComputeSampled}}));
    graph.addPass(pass("read b again", Phase::Composite, {{b, Access::ComputeSampled}}));
    const std::vector<PlannedPass>& plan = graph.plan();
    ASSERT_EQ(plan.size(), 5u);
    const std::vector<ResourceId> shared = pool.sharesMemoryWith(b);
    ASSERT_NE(std::find(shared.begin(), shared.end(), a), shared.end()) << "disjoint: shared";
    ASSERT_EQ(plan[2].barriers.size(), 1u);
    EXPECT_TRUE(plan[2].barriers[0].fromUndefined);
    EXPECT_EQ(plan[2].barriers[0].after, std::vector<Access>{Access::ComputeSampled});
    ASSERT_EQ(plan[3].barriers.size(), 1u);
    EXPECT_TRUE(plan[3].barriers[0].after.empty());
    EXPECT_TRUE(plan[4].barriers.empty()) << "two reads of b, its memory already handed over";
}

TEST_F(FrameTest, TwoWritesInTheSameStateStillWaitForEachOther) {
    ResourcePool pool(context());
    FrameGraph graph(pool, kSizes);
    const ResourceId image = graph.declare(screenImage("image"));
    graph.addPass(pass("write", Phase::PerLight, {{image, Access::ComputeWrite}}));
    graph.addPass(pass("layer", Phase::PerLight, {{image, Access::ComputeReadWrite}}));
    graph.addPass(pass("layer again", Phase::PerLight, {{image, Access::ComputeReadWrite}}));
    graph.addPass(pass("composite", Phase::Composite, {{image, Access::ComputeSampled}}));
    const std::vector<PlannedPass>& plan = graph.plan();
    ASSERT_EQ(plan.size(), 4u);
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

// Imports are the caller's for one frame: a pool that imports every frame holds as many entries
// in its third frame as in its first (a break-test's mutant kept every frame's imports, a host
// leak over a long viewer session that no other test saw).
TEST_F(FrameTest, ImportsLastOneFrame) {
    ResourcePool pool(context());
    std::vector<size_t> bounds;
    for (int frame = 0; frame < 3; ++frame) {
        FrameGraph graph(pool, kSizes);
        graph.declare(screenImage("image"));
        graph.importBuffer("imported", VK_NULL_HANDLE);
        bounds.push_back(pool.idBound());
    }
    EXPECT_EQ(bounds, (std::vector<size_t>{2, 2, 2}));
    // What the format checks of bound storage images ask: a declared image's format, an imported
    // one's, none for a buffer.
    FrameGraph graph(pool, kSizes);
    const vk::Image outside{.format = VK_FORMAT_R16G16B16A16_SFLOAT};
    const ResourceId declared = graph.declare(screenImage("image"));
    const ResourceId imported = graph.importImage("outside", outside, Access::ComputeSampled);
    const ResourceId buffer = graph.importBuffer("imported", VK_NULL_HANDLE);
    EXPECT_EQ(pool.formatOf(declared), VK_FORMAT_R32_SFLOAT);
    EXPECT_EQ(pool.formatOf(imported), VK_FORMAT_R16G16B16A16_SFLOAT);
    EXPECT_EQ(pool.formatOf(buffer), VK_FORMAT_UNDEFINED);
}

// Passes whose work reaches nothing that outlives the frame are culled, chains of them too; a
// pass that writes a persistent, imported or host-visible resource (the copy: no pass reads the
// buffer after it) and one that declares no write (an effect the graph cannot see) are kept.
TEST_F(FrameTest, PassesWhoseWorkNobodyReadsAreCulled) {
    ResourcePool pool(context());
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(screenImage("a")), b = graph.declare(screenImage("b"));
    const ResourceId unread = graph.declare(screenImage("unread"));
    const ResourceId early = graph.declare(screenImage("early"));
    const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
    const ResourceId host = graph.declare(BufferDecl{.name = "host",
                                                     .size = SizeClass::Fixed,
                                                     .bytes = 64,
                                                     .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                     .memory = vk::MemoryUse::Readback});
    const ResourceId imported = graph.importBuffer("imported", VK_NULL_HANDLE);
    graph.addPass(pass("gbuffer", Phase::GBuffer, {{a, Access::ComputeWrite}}));
    graph.addPass(pass("early", Phase::LightSpace, {{early, Access::ComputeWrite}}));
    graph.addPass(pass("unused", Phase::ScreenSpace,
                       {{early, Access::ComputeSampled}, {unread, Access::ComputeWrite}}));
    graph.addPass(
        pass("light", Phase::PerLight, {{a, Access::ComputeSampled}, {b, Access::ComputeWrite}}));
    graph.addPass(pass("composite", Phase::Composite,
                       {{b, Access::ComputeSampled}, {out, Access::ComputeWrite}}));
    graph.addPass(pass("copy", Phase::Readback,
                       {{out, Access::TransferRead}, {host, Access::TransferWrite}}));
    graph.addPass(pass("upload", Phase::LightSpace, {{imported, Access::ComputeWrite}}));
    graph.addPass(pass("effect", Phase::PerLight, {{a, Access::ComputeSampled}}));
    EXPECT_EQ(order(graph), (std::vector<std::string>{"upload", "gbuffer", "light", "effect",
                                                      "composite", "copy"}));
    std::vector<std::string> culled;
    for (size_t p : graph.culled())
        culled.push_back(graph.passes()[p].name);
    EXPECT_EQ(culled, (std::vector<std::string>{"early", "unused"}));
}

// Scopes of one name add up (every light's depth pass, the virtual pages' marking and rendering
// are one "shadow"), in the order each name was first recorded.
TEST_F(FrameTest, ScopesOfOneNameAddUp) {
    const std::vector<PassTime> times = vk::addUpByName({{"shadow", CostGroup::ShadowMaps},
                                                         {"gbuffer", CostGroup::Frame},
                                                         {"shadow", CostGroup::ShadowMaps},
                                                         {"visibility", CostGroup::PerPixel},
                                                         {"shadow", CostGroup::ShadowMaps}},
                                                        {1.0, 2.0, 4.0, 8.0, 16.0});
    ASSERT_EQ(times.size(), 3u);
    EXPECT_EQ(times[0].pass, "shadow");
    EXPECT_EQ(times[0].medianMs, 21.0);
    EXPECT_EQ(times[1].pass, "gbuffer");
    EXPECT_EQ(times[1].cost, CostGroup::Frame);
    EXPECT_EQ(times[2].medianMs, 8.0);
    EXPECT_EQ(times[2].cost, CostGroup::PerPixel);
}

// Every pass of a real frame counts where its work is, as its declaration says: the frame's
// G-buffer, the shadow maps (the depth passes, post passes such as vsm's blur and smrt's bounds,
// virtual pages), the per-pixel work (visibility, smrt's filter, the contact layer, the
// composite). What each report's and the sweep's cost columns add up (CostGroup).
TEST_F(FrameTest, EveryPassOfAFrameCountsWhereItsWorkIs) {
    const Scene scene = loadScene("builtin:spot");
    const auto expected = [](std::string_view pass) {
        if (pass == "gbuffer")
            return CostGroup::Frame;
        if (pass == "visibility" || pass == "filter" || pass == "composite" || pass == "contact")
            return CostGroup::PerPixel;
        return CostGroup::ShadowMaps;
    };
    struct Case {
        Technique technique;
        std::vector<std::pair<std::string, std::string>> sets;
        std::vector<std::string> passes; // that must be there
    };
    const std::vector<Case> cases = {
        {Technique::Hard, {{"composite.fused", "false"}}, {"shadow", "gbuffer", "visibility"}},
        {Technique::Vsm, {}, {"shadow", "vsm_blur_rows", "composite"}},
        {Technique::Smrt, {{"smrt.filter", "2"}}, {"filter", "visibility"}},
        {Technique::Pcf, {{"contact.length", "0.2"}}, {"contact"}},
        {Technique::Hard, {{"virtual.enabled", "true"}}, {"shadow"}}};
    for (const Case& c : cases) {
        RenderOptions o{
            .width = 32, .height = 32, .shadowMapSize = 256, .frames = 1, .technique = c.technique};
        for (const auto& [key, value] : c.sets)
            o.parameters.set(key, value);
        const RenderResult r = sharedRenderer().render(scene, o);
        const std::string label = std::string(techniqueName(c.technique)) +
                                  (c.sets.empty() ? "" : " " + c.sets.front().first);
        for (const std::string& name : c.passes)
            EXPECT_TRUE(std::any_of(r.passes.begin(), r.passes.end(),
                                    [&](const PassTime& p) { return p.pass == name; }))
                << label << ": no " << name;
        for (const PassTime& p : r.passes)
            EXPECT_EQ(p.cost, expected(p.pass)) << label << ": " << p.pass;
    }
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
                       .cost = CostGroup::Frame,
                       .phase = Phase::Composite,
                       .uses = {{staging, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           const VkBufferCopy region{.size = 4 * 8 * 4};
                           vkCmdCopyBuffer(c.cmd, c.buffer(staging), c.buffer(host), 1, &region);
                       }});
        graph.addPass({.name = "copy image",
                       .cost = CostGroup::Frame,
                       .phase = Phase::PerLight,
                       .uses = {{image, Access::TransferRead}, {staging, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           vk::copyImageToBuffer(c.cmd, c.image(image).get(), c.buffer(staging));
                       }});
        graph.addPass(
            {.name = "clear",
             .cost = CostGroup::Frame,
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
        for (const PlannedPass& planned : graph.plan()) // a buffer has no layout to drop
            for (const PlannedBarrier& b : planned.barriers)
                EXPECT_TRUE(pool.isImage(b.resource) || !b.fromUndefined) << "frame " << frame;
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
