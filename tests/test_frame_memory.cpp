// The placement of a frame's transient images in shared memory (src/render/frame_memory.cpp):
// small cases with known answers, then random frames checked against the rules every plan must
// keep (images over the same bytes never used by overlapping passes, offsets aligned, memory
// types every image in a block accepts).
#include "render/frame_memory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace penumbra::render;

namespace {

// The rules, checked pair by pair.
void expectSound(const AliasPlan& plan, const std::vector<TransientNeed>& needs) {
    ASSERT_EQ(plan.placements.size(), needs.size());
    VkDeviceSize separate = 0;
    for (size_t a = 0; a < needs.size(); ++a) {
        const AliasPlan::Placement& p = plan.placements[a];
        separate += needs[a].size;
        ASSERT_LT(p.block, plan.blocks.size());
        EXPECT_EQ(p.offset % needs[a].alignment, 0u) << "need " << a;
        EXPECT_LE(p.offset + needs[a].size, plan.blocks[p.block].size) << "need " << a;
        EXPECT_EQ(plan.blocks[p.block].memoryTypeBits & ~needs[a].memoryTypeBits, 0u)
            << "need " << a << ": its block's memory types are ones it accepts";
        EXPECT_NE(plan.blocks[p.block].memoryTypeBits, 0u);
        for (size_t b = 0; b < needs.size(); ++b) {
            const AliasPlan::Placement& q = plan.placements[b];
            const bool sameBytes = a != b && p.block == q.block &&
                                   p.offset < q.offset + needs[b].size &&
                                   q.offset < p.offset + needs[a].size;
            EXPECT_EQ(sharesBytes(plan, needs, a, b), sameBytes) << a << ", " << b;
            if (sameBytes) {
                EXPECT_TRUE(needs[a].last < needs[b].first || needs[b].last < needs[a].first)
                    << "needs " << a << " and " << b << " share bytes and passes";
            }
        }
    }
    EXPECT_EQ(plan.separateBytes, separate);
}

} // namespace

TEST(FrameMemory, ImagesOfDisjointPassesShareAndOthersDoNot) {
    // A: passes 0-2; B: 3-5 (after A: shares A's bytes); C: 2-3 (overlaps both).
    const std::vector<TransientNeed> needs{{.first = 0, .last = 2, .size = 1000, .alignment = 256},
                                           {.first = 3, .last = 5, .size = 1000, .alignment = 256},
                                           {.first = 2, .last = 3, .size = 500, .alignment = 256}};
    const AliasPlan plan = planAliasing(needs);
    expectSound(plan, needs);
    ASSERT_EQ(plan.blocks.size(), 1u);
    EXPECT_EQ(plan.placements[0].offset, 0u);
    EXPECT_EQ(plan.placements[1].offset, 0u) << "B takes A's bytes";
    EXPECT_EQ(plan.placements[2].offset, 1024u) << "C after both, aligned";
    EXPECT_EQ(plan.blocks[0].size, 1524u);
    EXPECT_EQ(plan.separateBytes, 2500u);
    EXPECT_EQ(plan.sharedBytes(), 1524u);
    EXPECT_TRUE(sharesBytes(plan, needs, 0, 1));
    EXPECT_FALSE(sharesBytes(plan, needs, 0, 2));
    EXPECT_FALSE(sharesBytes(plan, needs, 0, 0)) << "an image does not alias itself";
}

// A device that aligns small images to more than their size (an NVIDIA GPU: 1 KiB for 512
// bytes): two images side by side in one block would take more than two blocks of their own,
// so they get those; where one takes the other's bytes the block still saves.
TEST(FrameMemory, ABlockThatSavesNothingIsSplit) {
    const std::vector<TransientNeed> apart{{.first = 0, .last = 1, .size = 512, .alignment = 1024},
                                           {.first = 1, .last = 2, .size = 512, .alignment = 1024}};
    const AliasPlan split = planAliasing(apart);
    expectSound(split, apart);
    ASSERT_EQ(split.blocks.size(), 2u);
    EXPECT_EQ(split.sharedBytes(), split.separateBytes);
    EXPECT_EQ(split.blocks[0].size + split.blocks[1].size, 1024u);
    EXPECT_NE(split.placements[0].block, split.placements[1].block);
    std::vector<TransientNeed> sharing = apart;
    sharing[1].first = 2;
    const AliasPlan shared = planAliasing(sharing);
    ASSERT_EQ(shared.blocks.size(), 1u);
    EXPECT_EQ(shared.sharedBytes(), 512u);
    EXPECT_TRUE(sharesBytes(shared, sharing, 0, 1));
}

TEST(FrameMemory, APassThatUsesBothKeepsThemApart) {
    // The last pass of one is the first of the other: one pass sees both.
    const std::vector<TransientNeed> needs{{.first = 0, .last = 1, .size = 64},
                                           {.first = 1, .last = 2, .size = 64}};
    const AliasPlan plan = planAliasing(needs);
    expectSound(plan, needs);
    EXPECT_EQ(plan.sharedBytes(), 128u);
    EXPECT_FALSE(sharesBytes(plan, needs, 0, 1));
    EXPECT_EQ(plan.blocks.size(), 2u) << "side by side they save nothing: a block each";
}

// Two blocks that would both take an image without growing: the first gets it.
TEST(FrameMemory, OfBlocksThatGrowAlikeTheFirstTakesTheImage) {
    const std::vector<TransientNeed> needs{
        {.first = 0, .last = 0, .size = 100, .memoryTypeBits = 0b01},
        {.first = 0, .last = 0, .size = 100, .memoryTypeBits = 0b10},
        {.first = 1, .last = 1, .size = 100, .memoryTypeBits = 0b11}};
    const AliasPlan plan = planAliasing(needs);
    expectSound(plan, needs);
    EXPECT_TRUE(sharesBytes(plan, needs, 0, 2));
    EXPECT_FALSE(sharesBytes(plan, needs, 1, 2));
}

TEST(FrameMemory, MemoryTypesNoImageAcceptsTogetherTakeBlocksOfTheirOwn) {
    const std::vector<TransientNeed> needs{
        {.first = 0, .last = 0, .size = 64, .memoryTypeBits = 0b0011},
        {.first = 1, .last = 1, .size = 64, .memoryTypeBits = 0b0100},
        {.first = 2, .last = 2, .size = 32, .memoryTypeBits = 0b1100}};
    const AliasPlan plan = planAliasing(needs);
    expectSound(plan, needs);
    ASSERT_EQ(plan.blocks.size(), 2u);
    EXPECT_NE(plan.placements[0].block, plan.placements[1].block);
    EXPECT_EQ(plan.placements[2].block, plan.placements[1].block) << "types 2 and 3: only with B";
    EXPECT_EQ(plan.blocks[plan.placements[1].block].memoryTypeBits, 0b0100u);
    EXPECT_EQ(plan.sharedBytes(), 128u);
}

TEST(FrameMemory, TheLargestGoesFirstAndSmallOnesFillAroundIt) {
    // Two small images in turn under one large one's passes... and after it.
    const std::vector<TransientNeed> needs{{.first = 4, .last = 4, .size = 100},
                                           {.first = 5, .last = 5, .size = 100},
                                           {.first = 0, .last = 3, .size = 400}};
    const AliasPlan plan = planAliasing(needs);
    expectSound(plan, needs);
    EXPECT_EQ(plan.sharedBytes(), 400u);
    EXPECT_EQ(plan.placements[2].offset, 0u);
    EXPECT_EQ(plan.placements[0].offset, 0u);
    EXPECT_EQ(plan.placements[1].offset, 0u);
}

TEST(FrameMemory, RandomFramesKeepEveryRule) {
    std::mt19937 random(20261204);
    for (int frame = 0; frame < 300; ++frame) {
        std::vector<TransientNeed> needs(1 + random() % 12);
        for (TransientNeed& n : needs) {
            n.first = random() % 10;
            n.last = n.first + random() % 4;
            n.alignment = VkDeviceSize{1} << (random() % 9);
            n.size = 1 + random() % 5000;
            n.memoryTypeBits = static_cast<uint32_t>(1 + random() % 15);
        }
        // Half the frames on a device whose largest allocation is small.
        const VkDeviceSize maxBlock = frame % 2 ? 4000 + random() % 8000 : ~VkDeviceSize{0};
        const AliasPlan plan = planAliasing(needs, maxBlock);
        expectSound(plan, needs);
        // A block past the limit is one image's alone (others may take its bytes, never more).
        for (size_t b = 0; b < plan.blocks.size(); ++b) {
            VkDeviceSize largest = 0;
            for (size_t i = 0; i < needs.size(); ++i)
                if (plan.placements[i].block == b)
                    largest = std::max(largest, needs[i].size);
            EXPECT_LE(plan.blocks[b].size, std::max(maxBlock, largest))
                << "frame " << frame << ": block " << b << " past the device's largest allocation";
        }
        // Never worse than one block per image, and a block of several images saves bytes.
        EXPECT_LE(plan.sharedBytes(), plan.separateBytes) << "frame " << frame;
        for (size_t b = 0; b < plan.blocks.size(); ++b) {
            VkDeviceSize own = 0;
            size_t images = 0;
            for (size_t i = 0; i < needs.size(); ++i)
                if (plan.placements[i].block == b) {
                    own += needs[i].size;
                    ++images;
                }
            EXPECT_GE(images, 1u) << "frame " << frame << ": block " << b << " holds nothing";
            if (images > 1) {
                EXPECT_LT(plan.blocks[b].size, own) << "frame " << frame << ": block " << b;
            }
        }
        if (testing::Test::HasFailure())
            return;
    }
}

TEST(FrameMemory, AnImageGoesToTheBlockItGrowsLeast) {
    // A and B in blocks of their own (no memory type in common); C accepts both. In A's block it
    // would go above A (their passes overlap), in B's it takes B's bytes.
    const std::vector<TransientNeed> needs{
        {.first = 0, .last = 1, .size = 100, .memoryTypeBits = 0b01},
        {.first = 0, .last = 0, .size = 80, .memoryTypeBits = 0b10},
        {.first = 1, .last = 1, .size = 30, .memoryTypeBits = 0b11}};
    const AliasPlan plan = planAliasing(needs);
    expectSound(plan, needs);
    EXPECT_EQ(plan.placements[2].block, plan.placements[1].block);
    EXPECT_EQ(plan.placements[2].offset, 0u);
    EXPECT_EQ(plan.sharedBytes(), 180u);
}

TEST(FrameMemory, BlocksStayUnderTheDevicesLargestAllocation) {
    // A and B (400 bytes) are used together, C (400) after both, D (2000) after all three. Under
    // a 600-byte allocation limit B cannot go beside A: it gets a block of its own. D is larger
    // than the limit and gets a block alone, whose bytes the others may take, never growing it.
    const std::vector<TransientNeed> needs{{.first = 0, .last = 1, .size = 400},
                                           {.first = 0, .last = 1, .size = 400},
                                           {.first = 2, .last = 2, .size = 400},
                                           {.first = 3, .last = 3, .size = 2000}};
    const AliasPlan plan = planAliasing(needs, 600);
    expectSound(plan, needs);
    ASSERT_EQ(plan.blocks.size(), 2u);
    EXPECT_EQ(plan.placements[3].block, 0u) << "the largest first";
    EXPECT_EQ(plan.blocks[0].size, 2000u);
    EXPECT_EQ(plan.placements[0].block, 0u);
    EXPECT_EQ(plan.placements[2].block, 0u);
    EXPECT_EQ(plan.placements[1].block, 1u) << "beside A it would pass the limit";
    EXPECT_EQ(plan.blocks[1].size, 400u);
    // Without the limit, one block: B goes above A within D's bytes.
    const AliasPlan unlimited = planAliasing(needs);
    ASSERT_EQ(unlimited.blocks.size(), 1u);
    EXPECT_EQ(unlimited.blocks[0].size, 2000u);
    EXPECT_EQ(unlimited.placements[1].offset, 400u);
}
