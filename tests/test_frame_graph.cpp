// The frame graph (src/render/frame_graph.h) on its own: the order it gives passes, the barriers
// it places, and what its pool keeps across frames; then a small graph run on the device, with
// synchronization validation watching every barrier it placed (a missing one is a validation
// message, which fails the test).
#include "gpu_fixture.h"
#include "render/frame_graph.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/sync.h"

#include <algorithm>
#include <cstring>
#include <optional>

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
    const bool timed = !name.empty();
    return {.name = std::move(name),
            .cost = timed ? std::optional(CostGroup::PerPixel) : std::nullopt,
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

// The reads and writes are checked every frame, not only a resource's first: last frame's
// contents of a per-frame image are not there to read, a persistent one's only while its key
// holds; a read of what only a later pass writes (a cycle through the phases) and a write
// nothing kept reads are errors too.
TEST_F(FrameTest, ReadsAndWritesAreCheckedEveryFrame) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto frames = [](Lifetime lifetime, bool secondWrites, uint64_t secondKey) {
        ResourcePool pool(context());
        for (int frame = 0; frame < 2; ++frame) {
            FrameGraph graph(pool, kSizes);
            ImageDecl decl = screenImage("image", lifetime);
            decl.key = frame == 0 ? 1 : secondKey;
            const ResourceId image = graph.declare(decl);
            const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
            if (frame == 0 || secondWrites)
                graph.addPass(pass("write", Phase::ScreenSpace, {{image, Access::ComputeWrite}}));
            graph.addPass(pass("read", Phase::PerLight,
                               {{image, Access::ComputeSampled}, {out, Access::ComputeWrite}}));
            context().submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        }
    };
    frames(Lifetime::PerFrame, true, 1);
    frames(Lifetime::Persistent, false, 1); // its key kept its contents
    EXPECT_DEATH(frames(Lifetime::PerFrame, false, 1), "reads image, which no earlier pass writes");
    EXPECT_DEATH(frames(Lifetime::Persistent, false, 2), "reads image, which no earlier pass");
    const auto oneFrame = [](Phase writer, bool read) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image"));
        const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
        graph.addPass(
            pass("write", writer, {{image, Access::ComputeWrite}, {out, Access::ComputeWrite}}));
        if (read)
            graph.addPass(pass("read", Phase::ScreenSpace,
                               {{image, Access::ComputeSampled}, {out, Access::ComputeReadWrite}}));
        graph.plan();
    };
    oneFrame(Phase::LightSpace, true);
    EXPECT_DEATH(oneFrame(Phase::PerLight, true), "reads image, which only a later pass writes");
    EXPECT_DEATH(oneFrame(Phase::LightSpace, false), "writes image, which no later pass reads");
    // A read-write is a read: of nothing, when it comes first; and its write needs a reader.
    const auto readWrite = [](bool written, bool readAfter) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image"));
        const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
        if (written)
            graph.addPass(pass("write", Phase::ScreenSpace, {{image, Access::ComputeWrite}}));
        graph.addPass(pass("layer", Phase::PerLight,
                           {{image, Access::ComputeReadWrite}, {out, Access::ComputeWrite}}));
        if (readAfter)
            graph.addPass(pass("read", Phase::Composite,
                               {{image, Access::ComputeSampled}, {out, Access::ComputeReadWrite}}));
        graph.plan();
    };
    readWrite(true, true);
    EXPECT_DEATH(readWrite(false, true), "\"layer\" reads image, which no earlier pass writes");
    EXPECT_DEATH(readWrite(true, false), "\"layer\" writes image, which no later pass reads");
}

// A pass's cost group is part of its declaration: a timed pass without one, or an untimed one
// with one, is a programmer error the plan reports every frame.
TEST_F(FrameTest, ATimedPassDeclaresItsCostGroupAndAnUntimedOneNone) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto planned = [](std::string name, std::optional<CostGroup> cost) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image", Lifetime::Persistent));
        graph.addPass({.name = std::move(name),
                       .cost = cost,
                       .phase = Phase::PerLight,
                       .uses = {{image, Access::ComputeWrite}},
                       .record = [](PassContext&) {}});
        graph.plan();
    };
    EXPECT_DEATH(planned("visibility", std::nullopt), "visibility\" is timed but declares no");
    EXPECT_DEATH(planned("", CostGroup::ShadowMaps), "is untimed but declares a cost group");
    planned("visibility", CostGroup::PerPixel); // and these plan
    planned("", std::nullopt);
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
