// Transient images that share memory (src/render/pool_aliasing.cpp, render/frame_memory.h), on
// the device: two images whose passes do not overlap take the same bytes and each is read back
// as its own passes wrote it; one handed out of the frame, marked as an output or used beside
// another keeps bytes of its own; the first use of shared bytes waits for the last use before.
#include "frame_clears.h"
#include "gpu_fixture.h"
#include "render/access_states.h"
#include "render/frame_graph.h"
#include "vk/context.h"
#include "vk/resources.h"

#include <cstring>

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

namespace {

const FrameSizes kSizes{.width = 4, .height = 2};
constexpr uint32_t kPixels = 8;

ImageDecl transient(std::string name) {
    return {.name = std::move(name),
            .size = SizeClass::Screen,
            .format = VK_FORMAT_R32_SFLOAT,
            .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT};
}

struct Frame {
    bool overlap = false;   // b is written while a is still to be read
    bool handOut = false;   // c is copied out in the readback phase (else in the light phase)
    bool passFirst = false; // an unrelated pass comes first: every later pass's index moves
};

struct Seen {
    float a = 0, b = 0, c = 0;
    bool aSharesWithB = false, cShares = false;
    ResourcePool::TransientBytes bytes;
    std::vector<Access> bWaitsFor; // the barrier before b's first use
};

// a: written and copied out in LightSpace; b: the same in PerLight (or, overlapping, written in
// LightSpace before a is copied); c: written in PerLight, copied out where the frame says.
Seen runFrame(ResourcePool& pool, const Frame& f) {
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(transient("a"));
    const ResourceId b = graph.declare(transient("b"));
    const ResourceId c = graph.declare(transient("c"));
    const ResourceId host = graph.declare(BufferDecl{.name = "host",
                                                     .size = SizeClass::Fixed,
                                                     .bytes = 3 * kPixels * sizeof(float),
                                                     .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                     .memory = vk::MemoryUse::Readback});
    const auto write = [&](std::string name, ResourceId id, Phase phase, float value) {
        graph.addPass({.name = "",
                       .phase = phase,
                       .uses = {{id, Access::ColorAttachment}},
                       .record = [id, value](PassContext& ctx) {
                           clearThrough(ctx.cmd, ctx.image(id).view(),
                                        {kSizes.width, kSizes.height}, false, value);
                       }});
        static_cast<void>(name);
    };
    const auto copyOut = [&](ResourceId id, Phase phase, uint32_t slot) {
        graph.addPass({.name = "",
                       .phase = phase,
                       .uses = {{id, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [id, host, slot](PassContext& ctx) {
                           const VkBufferImageCopy region{
                               .bufferOffset = slot * kPixels * sizeof(float),
                               .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                               .imageExtent = {kSizes.width, kSizes.height, 1}};
                           vkCmdCopyImageToBuffer(ctx.cmd, ctx.image(id).get().get(),
                                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                                  ctx.buffer(host), 1, &region);
                       }});
    };
    if (f.passFirst)
        graph.addPass({.name = "",
                       .phase = Phase::LightSpace,
                       .uses = {{host, Access::TransferWrite}},
                       .record = [host](PassContext& ctx) {
                           vkCmdFillBuffer(ctx.cmd, ctx.buffer(host), 0, VK_WHOLE_SIZE, 0);
                       }});
    write("a", a, Phase::LightSpace, 1.0f);
    if (f.overlap)
        write("b", b, Phase::LightSpace, 2.0f);
    copyOut(a, Phase::LightSpace, 0);
    if (!f.overlap)
        write("b", b, Phase::PerLight, 2.0f);
    copyOut(b, Phase::PerLight, 1);
    write("c", c, Phase::PerLight, 3.0f);
    copyOut(c, f.handOut ? Phase::Readback : Phase::PerLight, 2);
    Seen seen;
    for (const PlannedPass& planned : graph.plan())
        for (const PlannedBarrier& barrier : planned.barriers)
            if (barrier.resource == b && seen.bWaitsFor.empty() && !barrier.after.empty())
                seen.bWaitsFor = barrier.after;
    sharedRenderer().context().submitAndWait(
        [&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
    float read[3 * kPixels];
    std::memcpy(read, pool.mapped("host"), sizeof(read));
    for (uint32_t i = 0; i < kPixels; ++i) {
        EXPECT_EQ(read[i], 1.0f) << "a, pixel " << i;
        EXPECT_EQ(read[kPixels + i], 2.0f) << "b, pixel " << i;
        EXPECT_EQ(read[2 * kPixels + i], 3.0f) << "c, pixel " << i;
    }
    const std::vector<ResourceId> withA = pool.sharesMemoryWith(a);
    seen.aSharesWithB = std::find(withA.begin(), withA.end(), b) != withA.end();
    seen.cShares = !pool.sharesMemoryWith(c).empty();
    seen.bytes = pool.transientBytes();
    return seen;
}

} // namespace

TEST_F(FrameTest, TransientsOfDisjointPassesShareMemoryAndEachReadsItsOwn) {
    ResourcePool pool(sharedRenderer().context());
    const Seen first = runFrame(pool, {.handOut = true});
    EXPECT_TRUE(first.aSharesWithB);
    EXPECT_FALSE(first.cShares) << "handed out of the frame: its bytes are its own";
    EXPECT_GT(first.bytes.shared, 0u);
    EXPECT_EQ(2 * first.bytes.shared, first.bytes.separate) << "a and b alike, in one place";
    ASSERT_EQ(first.bWaitsFor.size(), 1u);
    EXPECT_EQ(first.bWaitsFor[0], Access::TransferRead) << "b's first write waits for a's copy";
    // The same frame again: nothing placed anew.
    const uint64_t made = pool.creations();
    const Seen again = runFrame(pool, {.handOut = true});
    EXPECT_EQ(pool.creations(), made);
    EXPECT_TRUE(again.aSharesWithB);
    ASSERT_EQ(again.bWaitsFor.size(), 1u);
    // A pass elsewhere moves every index but no overlap: still nothing placed anew.
    const Seen moved = runFrame(pool, {.handOut = true, .passFirst = true});
    EXPECT_EQ(pool.creations(), made);
    EXPECT_TRUE(moved.aSharesWithB);
    // The same images now used beside each other: placed anew, each with its own bytes (each
    // reads back its own values).
    const uint64_t allocations = vk::liveDeviceMemory().allocations;
    const Seen overlapping = runFrame(pool, {.overlap = true, .handOut = true});
    EXPECT_FALSE(overlapping.aSharesWithB);
    EXPECT_GT(pool.creations(), made);
    // And back: the first placement again, in as many allocations (the last placement's blocks
    // freed, not kept beside the new ones).
    const Seen back = runFrame(pool, {.handOut = true});
    EXPECT_TRUE(back.aSharesWithB);
    EXPECT_EQ(vk::liveDeviceMemory().allocations, allocations);
    // c copied out beside the others: it may share too (with a, whose passes end before it).
    const Seen inside = runFrame(pool, {.handOut = false});
    EXPECT_TRUE(inside.cShares);
    EXPECT_EQ(3 * inside.bytes.shared, inside.bytes.separate);
}

// An image the driver requires memory of its own for (VkMemoryDedicatedRequirements; stood in
// for here, since lavapipe asks it of none) is never placed in shared memory: it is made alone
// and reads back its own values, and the others still share.
TEST_F(FrameTest, AnImageThatNeedsItsOwnMemoryIsNeverShared) {
    ResourcePool pool(sharedRenderer().context());
    std::vector<std::string> asked;
    pool.needsOwnMemory = [&asked](const vk::ImageDesc& desc) {
        asked.push_back(desc.name);
        return desc.name == "b";
    };
    const Seen seen = runFrame(pool, {.handOut = false});
    EXPECT_FALSE(seen.aSharesWithB);
    EXPECT_TRUE(seen.cShares) << "a and c still share";
    EXPECT_EQ(2 * seen.bytes.shared, seen.bytes.separate) << "b counted with neither";
    EXPECT_EQ(asked, (std::vector<std::string>{"a", "b", "c"})) << "each transient asked once";
    // The next frame keeps every image: the driver is not asked again, and b stays alone.
    const Seen again = runFrame(pool, {.handOut = false});
    EXPECT_EQ(asked.size(), 3u);
    EXPECT_FALSE(again.aSharesWithB);
    EXPECT_TRUE(again.cShares);
}

TEST_F(FrameTest, TransientsWhosePassesOverlapOrThatLeaveTheFrameKeepTheirOwnBytes) {
    ResourcePool pool(sharedRenderer().context());
    const Seen overlapping = runFrame(pool, {.overlap = true, .handOut = true});
    EXPECT_FALSE(overlapping.aSharesWithB) << "b is written before a is read";
    EXPECT_EQ(overlapping.bytes.shared, overlapping.bytes.separate);
    EXPECT_TRUE(overlapping.bWaitsFor.empty());
    // An output never shares, whatever its passes.
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(transient("a"));
    const ResourceId b = graph.declare(transient("b"));
    graph.markOutput(b);
    for (const auto& [id, phase] : {std::pair{a, Phase::LightSpace}, std::pair{b, Phase::PerLight}})
        graph.addPass({.name = "",
                       .phase = phase,
                       .uses = {{id, Access::ColorAttachment}},
                       .record = [](PassContext&) {}});
    graph.addPass({.name = "",
                   .phase = Phase::LightSpace,
                   .uses = {{a, Access::TransferRead}},
                   .record = [](PassContext&) {}});
    graph.plan();
    EXPECT_TRUE(pool.sharesMemoryWith(a).empty());
    EXPECT_TRUE(pool.sharesMemoryWith(b).empty());
    // Nor does an image only bound (a stand-in no pass writes, which a caller may read after
    // the frame), though its one pass ends before another image's begin.
    FrameGraph bound(pool, kSizes);
    const ResourceId standIn = bound.declare(transient("stand-in"));
    const ResourceId kept = bound.declare(transient("kept"));
    const ResourceId later = bound.declare(transient("later"));
    bound.markBoundOnly(standIn);
    bound.markOutput(kept);
    bound.addPass({.name = "",
                   .phase = Phase::LightSpace,
                   .uses = {{standIn, Access::TransferRead}, {kept, Access::ColorAttachment}},
                   .record = [](PassContext&) {}});
    for (const Access access : {Access::ColorAttachment, Access::TransferRead})
        bound.addPass({.name = "",
                       .phase = Phase::PerLight,
                       .uses = {{later, access}},
                       .record = [](PassContext&) {}});
    bound.plan();
    EXPECT_TRUE(pool.sharesMemoryWith(standIn).empty());
    EXPECT_TRUE(pool.sharesMemoryWith(later).empty());
}

// What a barrier before shared bytes waits for: its own last use, and those of the images whose
// bytes it takes.
TEST(FrameMemory, ABarrierBeforeSharedBytesWaitsForTheirLastUses) {
    const PlannedBarrier b{.resource = 0,
                           .from = Access::ComputeSampled,
                           .to = Access::ColorAttachment,
                           .fromUndefined = true,
                           .after = {Access::TransferRead, Access::ComputeWrite}};
    const vk::ImageState from = imageSource(b);
    EXPECT_EQ(from.layout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(from.stage,
              imageState(Access::TransferRead).stage | imageState(Access::ComputeWrite).stage);
    EXPECT_EQ(from.access,
              imageState(Access::TransferRead).access | imageState(Access::ComputeWrite).access);
    PlannedBarrier kept = b;
    kept.fromUndefined = false;
    kept.after.clear();
    const vk::ImageState own = imageSource(kept);
    EXPECT_EQ(own.layout, imageState(Access::ComputeSampled).layout);
    EXPECT_EQ(own.stage, imageState(Access::ComputeSampled).stage);
}
