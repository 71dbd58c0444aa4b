// Pages decided on the device (src/render/page_decision_passes.h, shaders/page_decisions.comp)
// against the CPU reference they restate (decidePages, itself checked against the host cache in
// tests/test_page_decisions.cpp): on random frames, in pools of whole tiles of a workgroup's
// 128 pages and parts of one, the same pages rendered where in the same order, the same table,
// the same counts, and the same owners carried to the next frame (freed ones included).
#include "gpu_fixture.h"
#include "page_frames.h"
#include "render/page_decision_passes.h"

using namespace penumbra;
using namespace penumbra::test;

namespace {

struct PoolRun {
    uint32_t poolPages;
    VirtualSettings sizes;
    uint32_t frames;
};

} // namespace

TEST_F(VirtualTest, PagesDecidedOnTheDeviceEqualTheReferenceFrameByFrame) {
    const vk::Context& ctx = sharedRenderer().context();
    // Pools of two workgroups' tiles of 128 and of two and parts; and the default map's levels
    // (128 pages a side: tables of hundreds of thousands of entries, a scan of more blocks than
    // a workgroup holds).
    for (const PoolRun& run : {PoolRun{small().poolPages(), small(), 40}, PoolRun{300, small(), 40},
                               PoolRun{700, VirtualSettings{}, 10}}) {
        const uint32_t poolPages = run.poolPages;
        std::mt19937 rng(poolPages);
        render::PageDecisionPasses passes(ctx, poolPages);
        std::vector<PageOwner> owners(poolPages);
        glm::vec3 camera{0.0f, 2.0f, 0.0f};
        uint32_t cached = 0, evicted = 0, dropped = 0, rendered = 0, freed = 0;
        size_t entries = 0;
        for (uint32_t frame = 1; frame <= run.frames; ++frame) {
            Frame f = randomFrame(rng, camera, run.sizes);
            if (frame % 5 == 0) // every page at once: more than any pool holds
                std::fill(f.requests.begin(), f.requests.end(), 1u);
            entries = std::max(entries, f.requests.size());
            const std::vector<std::vector<PageRect>> rects =
                f.moved.empty() ? std::vector<std::vector<PageRect>>{}
                                : movedPageRects(f.levels, f.moved, run.sizes.pageSize);
            const PageDecisionInputs in{.levels = &f.levels,
                                        .requests = f.requests,
                                        .lightsRekeyed = f.rekeyed,
                                        .moved = rects,
                                        .frame = frame};
            const std::vector<PageOwner> before = owners;
            const PageDecisions want = decidePages(owners, in);
            passes.prepare(in);
            ctx.submitAndWait([&](VkCommandBuffer cmd) { passes.record(cmd); });
            const PageDecisions got = passes.result();
            const std::string at =
                "pool " + std::to_string(poolPages) + " frame " + std::to_string(frame);
            ASSERT_EQ(got.render, want.render) << at;
            ASSERT_EQ(got.table, want.table) << at;
            EXPECT_EQ(got.requested, want.requested) << at;
            EXPECT_EQ(got.cached, want.cached) << at;
            EXPECT_EQ(got.evicted, want.evicted) << at;
            EXPECT_EQ(got.dropped, want.dropped) << at;
            const std::vector<PageOwner> device = passes.owners();
            for (uint32_t p = 0; p < poolPages; ++p) {
                ASSERT_EQ(device[p].level, owners[p].level) << at << " page " << p;
                ASSERT_EQ(device[p].page, owners[p].page) << at << " page " << p;
                ASSERT_EQ(device[p].lastUsed, owners[p].lastUsed) << at << " page " << p;
                freed += before[p].level != PageOwner::kFree && owners[p].level == PageOwner::kFree;
            }
            cached += want.cached, evicted += want.evicted, dropped += want.dropped;
            rendered += static_cast<uint32_t>(want.render.size());
        }
        std::printf("pool %u, up to %zu entries: %u rendered, %u cached, %u evicted, %u dropped, "
                    "%u freed\n",
                    poolPages, entries, rendered, cached, evicted, dropped, freed);
        // The sequence reached every rule.
        EXPECT_GT(cached, 0u);
        EXPECT_GT(evicted, 0u);
        EXPECT_GT(freed, 0u);
        EXPECT_GT(rendered, 0u);
        EXPECT_GT(dropped, 0u);
    }
}
