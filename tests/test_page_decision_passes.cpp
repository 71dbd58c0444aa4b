// Pages decided on the device (src/render/page_decision_passes.h, shaders/page_decisions.comp)
// against the CPU reference they restate (decidePages, itself checked against the host cache in
// tests/test_page_decisions.cpp): on random frames, in pools of whole tiles of a workgroup's
// 128 pages and parts of one, the same pages rendered where in the same order, the same table,
// the same counts, and the same owners carried to the next frame (freed ones included).
#include "gpu_fixture.h"
#include "page_frames.h"
#include "render/page_decision_passes.h"
#include "render/page_draw_passes.h"

#include <algorithm>

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
            EXPECT_EQ(passes.counts().resident,
                      std::count_if(owners.begin(), owners.end(),
                                    [](const PageOwner& o) { return o.level != PageOwner::kFree; }))
                << at;
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

namespace {

// The tiles the candidates pass reads by its rule, given the owners as it sees them: each
// workgroup reads tiles until none of its candidates has fewer than `missing` candidates before
// it in the order (free first, then least recently used, then by index).
uint32_t tilesByRule(const std::vector<PageOwner>& owners, uint32_t frame, uint32_t missing) {
    if (missing == 0)
        return 0;
    const auto n = static_cast<uint32_t>(owners.size());
    const uint32_t tiles = (n + PAGES_BLOCK - 1) / PAGES_BLOCK;
    auto key = [&](uint32_t p) {
        return std::tuple(owners[p].level == PageOwner::kFree ? 0u : 1u, owners[p].lastUsed, p);
    };
    auto candidate = [&](uint32_t p) {
        return owners[p].level == PageOwner::kFree || owners[p].lastUsed < frame;
    };
    uint32_t read = 0;
    for (uint32_t group = 0; group < tiles; ++group)
        for (uint32_t t = 0; t < tiles; ++t) {
            ++read;
            bool still = false;
            for (uint32_t p = group * PAGES_BLOCK; p < std::min(n, (group + 1) * PAGES_BLOCK);
                 ++p) {
                uint32_t before = 0;
                for (uint32_t q = 0; q < std::min(n, (t + 1) * PAGES_BLOCK); ++q)
                    before += candidate(q) && key(q) < key(p);
                still = still || (candidate(p) && before < missing);
            }
            if (!still)
                break;
        }
    return read;
}

} // namespace

// The candidates pass stops reading the pool once no candidate of a workgroup can rank below the
// missing pages' count. A first frame asks for 200 pages of a spot's finest level, a second for
// 60 others (their chains partly resident): the tiles read are those the rule gives, fewer than
// the whole pool for every workgroup. With nothing missing, no tile is read.
TEST_F(VirtualTest, TheCandidatesPassStopsOnceItsRanksAreBeyondTheMissingPages) {
    const vk::Context& ctx = sharedRenderer().context();
    const uint32_t poolPages = 700, tiles = (poolPages + PAGES_BLOCK - 1) / PAGES_BLOCK;
    render::PageDecisionPasses passes(ctx, poolPages);
    uint32_t offset = 0;
    const std::vector<VirtualLevel> levels =
        virtualLevels(kSpot, 0, kField, {0, 2, 0}, small(), {.nearestSurface = 5.0f}, offset);
    auto decide = [&](uint32_t first, uint32_t count, uint32_t frame) {
        std::vector<uint32_t> requests(offset, 0u);
        std::fill_n(requests.begin() + levels[0].tableOffset + first, count, 1u);
        passes.prepare({.levels = &levels, .requests = requests, .frame = frame});
        ctx.submitAndWait([&](VkCommandBuffer cmd) { passes.record(cmd); });
        return passes.result();
    };
    decide(0, 200, 1);
    std::vector<PageOwner> seen = passes.owners(); // as the second frame's candidates see them
    const PageDecisions second = decide(400, 60, 2);
    const std::vector<PageOwner> after = passes.owners();
    std::vector<bool> rendered(poolPages, false);
    for (const auto& [physical, key] : second.render)
        rendered[physical] = true;
    for (uint32_t p = 0; p < poolPages; ++p)
        if (!rendered[p] && after[p].lastUsed == 2)
            seen[p].lastUsed = 2; // kept: asked for again
    const auto missing = static_cast<uint32_t>(second.render.size()) + second.dropped;
    ASSERT_GT(missing, 56u); // more than the first frame's last tile holds free
    const uint32_t expected = tilesByRule(seen, 2, missing);
    EXPECT_EQ(passes.candidateTilesRead(), expected);
    EXPECT_LT(expected, tiles * tiles);
    std::printf("%u missing: %u tiles read of %u\n", missing, expected, tiles * tiles);
    // The same pages again: all resident, nothing missing.
    EXPECT_TRUE(decide(400, 60, 3).render.empty());
    EXPECT_EQ(passes.candidateTilesRead(), 0u);
}

namespace {

// The lists PageDrawPasses left (shaders/page_draws.comp, recordLists): every page the decisions
// `d` render, once, in the list of its level's kind (orthographic or perspective), with the
// matrix that takes the world to its square of a pool of side x side pages (pageViewProj's crop,
// then NDC [-1, 1] to the square, restated here) and the square's bounds in the pool's NDC.
// Counts the pages of each kind into `listed`.
void expectListed(const render::PageDrawPasses& draws, const PageDecisions& d,
                  const std::vector<VirtualLevel>& levels, uint32_t side, const std::string& at,
                  size_t listed[2]) {
    const std::vector<gpu::PageDrawData> lists[2] = {draws.listed(PAGE_DRAW_ORTHO),
                                                     draws.listed(PAGE_DRAW_PERSPECTIVE)};
    ASSERT_EQ(lists[0].size() + lists[1].size(), d.render.size()) << at;
    for (const auto& [physical, key] : d.render) {
        const VirtualLevel* level = levelOf(levels, key);
        ASSERT_NE(level, nullptr) << at;
        const uint32_t kind =
            level->projection.perspective ? PAGE_DRAW_PERSPECTIVE : PAGE_DRAW_ORTHO;
        const float s = static_cast<float>(side);
        const glm::vec2 lo = -1.0f + 2.0f * glm::vec2(physical % side, physical / side) / s;
        glm::mat4 place(1.0f);
        place[0][0] = place[1][1] = 1.0f / s;
        place[3].x = lo.x + 1.0f / s;
        place[3].y = lo.y + 1.0f / s;
        const glm::mat4 want = place * pageViewProj(*level, key.page - level->firstPage);
        const auto found = std::find_if(lists[kind].begin(), lists[kind].end(), [&](const auto& p) {
            return std::abs(p.square.x - lo.x) < 1e-6f && std::abs(p.square.y - lo.y) < 1e-6f;
        });
        ASSERT_NE(found, lists[kind].end()) << at << ": physical page " << physical;
        EXPECT_NEAR(found->square.z, lo.x + 2.0f / s, 1e-6f) << at;
        EXPECT_NEAR(found->square.w, lo.y + 2.0f / s, 1e-6f) << at;
        float scale = 1.0f;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                scale = std::max(scale, std::abs(want[c][r]));
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                ASSERT_NEAR(found->poolFromWorld[c][r], want[c][r], 1e-5f * scale)
                    << at << ": physical page " << physical << ", column " << c << " row " << r;
        ++listed[kind];
    }
}

std::vector<std::vector<PageRect>> movedRects(const Frame& f) {
    return f.moved.empty() ? std::vector<std::vector<PageRect>>{}
                           : movedPageRects(f.levels, f.moved, small().pageSize);
}

} // namespace

// The page draws' lists over random frames of suns, spots and bulbs in a pool of 20x20 pages
// (parts of workgroups): as expectListed says.
TEST_F(VirtualTest, ThePageDrawListsPlaceEachRenderedPageInItsSquare) {
    const vk::Context& ctx = sharedRenderer().context();
    const uint32_t side = 20, poolPages = side * side;
    std::mt19937 rng(11);
    render::PageDecisionPasses passes(ctx, poolPages);
    render::PageDrawPasses draws(ctx, 1, true);
    glm::vec3 camera{0.0f, 2.0f, 0.0f};
    size_t listed[2] = {0, 0};
    for (uint32_t frame = 1; frame <= 12; ++frame) {
        const Frame f = randomFrame(rng, camera);
        const std::vector<std::vector<PageRect>> rects = movedRects(f);
        passes.prepare({.levels = &f.levels,
                        .requests = f.requests,
                        .lightsRekeyed = f.rekeyed,
                        .moved = rects,
                        .frame = frame});
        draws.prepare(f.levels, 0);
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            passes.record(cmd);
            draws.recordLists(cmd, passes, side, 0);
        });
        expectListed(draws, passes.result(), f.levels, side, "frame " + std::to_string(frame),
                     listed);
    }
    std::printf("%zu orthographic and %zu perspective pages listed\n", listed[0], listed[1]);
    EXPECT_GT(listed[PAGE_DRAW_ORTHO], 0u);
    EXPECT_GT(listed[PAGE_DRAW_PERSPECTIVE], 0u);
}

// Frames in flight: two frames' inputs written into two slots before either is decided, then
// decided one after the other in one command buffer, as a viewer records them. Each slot's
// decisions are its own frame's (its counts, and for the later one the table, the pages and the
// lists); the owners carry from the first to the second as the reference's do.
TEST_F(VirtualTest, EachSlotDecidesWithItsOwnFramesInputs) {
    const vk::Context& ctx = sharedRenderer().context();
    const uint32_t side = 20, poolPages = side * side;
    std::mt19937 rng(5);
    render::PageDecisionPasses passes(ctx, poolPages, {.readable = true, .slots = 2});
    render::PageDrawPasses draws(ctx, 2, true);
    std::vector<PageOwner> owners(poolPages);
    glm::vec3 camera{0.0f, 2.0f, 0.0f};
    size_t listed[2] = {0, 0};
    for (uint32_t round = 0; round < 4; ++round) {
        const Frame a = randomFrame(rng, camera), b = randomFrame(rng, camera);
        const std::vector<std::vector<PageRect>> rectsA = movedRects(a), rectsB = movedRects(b);
        const PageDecisionInputs inA{.levels = &a.levels,
                                     .requests = a.requests,
                                     .lightsRekeyed = a.rekeyed,
                                     .moved = rectsA,
                                     .frame = 2 * round + 1};
        const PageDecisionInputs inB{.levels = &b.levels,
                                     .requests = b.requests,
                                     .lightsRekeyed = b.rekeyed,
                                     .moved = rectsB,
                                     .frame = 2 * round + 2};
        const PageDecisions wantA = decidePages(owners, inA);
        const PageDecisions wantB = decidePages(owners, inB);
        passes.prepare(inA, 0);
        draws.prepare(a.levels, 0);
        passes.prepare(inB, 1);
        draws.prepare(b.levels, 1);
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            passes.record(cmd, VK_NULL_HANDLE, nullptr, 0);
            passes.record(cmd, VK_NULL_HANDLE, nullptr, 1);
            draws.recordLists(cmd, passes, side, 1);
        });
        const std::string at = "round " + std::to_string(round);
        EXPECT_EQ(passes.counts(0).rendered, wantA.render.size()) << at;
        EXPECT_EQ(passes.counts(0).requested, wantA.requested) << at;
        const PageDecisions gotB = passes.result(1);
        ASSERT_EQ(gotB.render, wantB.render) << at;
        ASSERT_EQ(gotB.table, wantB.table) << at;
        EXPECT_EQ(gotB.requested, wantB.requested) << at;
        expectListed(draws, gotB, b.levels, side, at, listed);
    }
    EXPECT_GT(listed[PAGE_DRAW_ORTHO] + listed[PAGE_DRAW_PERSPECTIVE], 0u);
}

// Lights past the first word of the re-keyed bits (index 32 on): a re-keyed light 40 loses every
// page and draws them again; light 1 keeps its own, as the reference says.
TEST_F(VirtualTest, ReKeyedLightsPastTheFirstWordLoseTheirPages) {
    const vk::Context& ctx = sharedRenderer().context();
    const uint32_t poolPages = 300;
    render::PageDecisionPasses passes(ctx, poolPages);
    std::vector<PageOwner> owners(poolPages);
    uint32_t offset = 0;
    std::vector<VirtualLevel> levels =
        virtualLevels(kSpot, 1, kField, {0, 2, 0}, small(), {.nearestSurface = 5.0f}, offset);
    const size_t farFirst = levels.size();
    const std::vector<VirtualLevel> far =
        virtualLevels(kSpot, 40, kField, {0, 2, 0}, small(), {.nearestSurface = 5.0f}, offset);
    levels.insert(levels.end(), far.begin(), far.end());
    std::vector<uint32_t> requests(offset, 0u);
    std::fill_n(requests.begin() + levels[0].tableOffset, 50, 1u);
    std::fill_n(requests.begin() + levels[farFirst].tableOffset, 50, 1u);
    for (uint32_t frame = 1; frame <= 2; ++frame) {
        const std::vector<uint32_t> rekeyed =
            frame == 2 ? std::vector<uint32_t>{40} : std::vector<uint32_t>{};
        const PageDecisionInputs in{
            .levels = &levels, .requests = requests, .lightsRekeyed = rekeyed, .frame = frame};
        const PageDecisions want = decidePages(owners, in);
        passes.prepare(in);
        ctx.submitAndWait([&](VkCommandBuffer cmd) { passes.record(cmd); });
        const PageDecisions got = passes.result();
        ASSERT_EQ(got.render, want.render) << "frame " << frame;
        ASSERT_EQ(got.table, want.table) << "frame " << frame;
        if (frame == 2) {
            ASSERT_FALSE(got.render.empty());
            for (const auto& [physical, key] : got.render)
                EXPECT_EQ(key.light, 40u) << "light 1 keeps its pages";
        }
    }
}
