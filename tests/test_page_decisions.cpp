// Pages decided as the device will decide them (src/core/page_decisions.h): on random frames of
// three lights' levels (a sun's window moving with the camera, a spot, a bulb that comes and
// goes), random requests, lights re-keyed and casters moved, in a pool too small for them, the
// passes decide exactly what the host cache decides: the same pages rendered where, the same
// table, the same counts.
#include "core/page_decisions.h"
#include "page_frames.h"

#include <gtest/gtest.h>

#include <random>

using namespace penumbra;
using namespace penumbra::virtual_field;
using namespace penumbra::test;

TEST(PageDecisions, EqualTheHostCacheFrameByFrame) {
    for (const uint32_t seed : {1u, 2u, 3u}) {
        std::mt19937 rng(seed);
        const uint32_t poolPages = small().poolPages();
        PageCache cache(poolPages);
        std::vector<PageOwner> owners(poolPages);
        std::vector<uint64_t> keys = {1, 1, 1};
        for (uint32_t light = 0; light < 3; ++light)
            cache.keyLight(light, keys[light]);
        glm::vec3 camera{0.0f, 2.0f, 0.0f};
        uint32_t cached = 0, evicted = 0, dropped = 0, rekeyed = 0, moved = 0, rendered = 0;
        for (uint32_t frame = 1; frame <= 40; ++frame) {
            const Frame f = randomFrame(rng, camera);
            // The host's frame, as SceneRenderer::updatePages makes it.
            for (const uint32_t light : f.rekeyed)
                rekeyed += cache.keyLight(light, ++keys[light]);
            moved += dropMovedPages(cache, f.levels, f.moved, small().pageSize);
            const PageCache::Update want = cache.update(
                withCoarserPages(requestedPages(f.levels, f.requests.data()), f.levels), frame);
            const std::vector<uint32_t> table =
                pageTable(f.levels, cache, static_cast<uint32_t>(f.requests.size()));
            // The passes'.
            const std::vector<std::vector<PageRect>> rects =
                f.moved.empty() ? std::vector<std::vector<PageRect>>{}
                                : movedPageRects(f.levels, f.moved, small().pageSize);
            const PageDecisions got = decidePages(owners, {.levels = &f.levels,
                                                           .requests = f.requests,
                                                           .lightsRekeyed = f.rekeyed,
                                                           .moved = rects,
                                                           .frame = frame});
            ASSERT_EQ(got.render, want.render) << "seed " << seed << " frame " << frame;
            ASSERT_EQ(got.table, table) << "seed " << seed << " frame " << frame;
            EXPECT_EQ(got.requested, want.requested);
            EXPECT_EQ(got.cached, want.cached);
            EXPECT_EQ(got.evicted, want.evicted);
            EXPECT_EQ(got.dropped, want.dropped);
            for (uint32_t p = 0; p < poolPages; ++p) {
                const std::optional<PageKey> key = cache.keyOf(p);
                ASSERT_EQ(owners[p].level != PageOwner::kFree, key.has_value()) << p;
                if (key) {
                    EXPECT_EQ(owners[p].level, packLevel(key->light, key->face, key->level));
                    EXPECT_EQ(owners[p].page, key->page);
                }
            }
            cached += want.cached, evicted += want.evicted, dropped += want.dropped;
            rendered += uint32_t(want.render.size());
        }
        std::printf("seed %u: %u rendered, %u cached, %u evicted, %u dropped; %u re-keyed away, "
                    "%u moved away\n",
                    seed, rendered, cached, evicted, dropped, rekeyed, moved);
        // The sequence reached every rule.
        EXPECT_GT(cached, 0u) << seed;
        EXPECT_GT(evicted, 0u) << seed;
        EXPECT_GT(dropped, 0u) << seed;
        EXPECT_GT(rekeyed, 0u) << seed;
        EXPECT_GT(moved, 0u) << seed;
        EXPECT_GT(rendered, 0u) << seed;
    }
}
