// Virtual shadow maps on the host (src/core/virtual_maps.h) and the page lookup's shared maths
// (shaders/include/virtual_pages.h): a sun's clipmap levels (doubling, centred on the camera,
// snapped to pages that keep their place in the world), a spot's and a point light's mips, the
// page's own projection, the atlas lookup, and the page cache (kept pages, least recently used
// first out, the coarsest pages kept when the pool is full, a light's pages dropped when it
// changes).
#include "core/projection.h"
#include "core/virtual_maps.h"
#include "virtual_field.h"
#include "virtual_pages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

using namespace penumbra;
using namespace penumbra::virtual_field;

namespace {

// A world point's place in a level: its uv and depth.
glm::vec3 uvOf(const VirtualLevel& level, glm::vec3 world) {
    const glm::vec4 c = textureMatrix() * level.projection.viewProj * glm::vec4(world, 1.0f);
    return glm::vec3(c) / c.w;
}

// The level's page (its window's own coordinates) that holds a world point.
glm::ivec2 pageOf(const VirtualLevel& level, glm::vec3 world, uint32_t pageSize) {
    const glm::vec2 uv = glm::vec2(uvOf(level, world));
    const auto size = static_cast<float>(level.pagesPerSide * pageSize);
    return gpu::virtualPageOf(glm::ivec2(glm::floor(uv * size)), pageSize);
}

} // namespace

TEST(VirtualMaps, ClipmapLevelsDoubleCentreOnTheCameraAndSnapToPages) {
    const VirtualSettings s = small();
    const glm::vec3 eye{37.3f, 2.0f, -81.9f};
    const std::vector<VirtualLevel> levels = levelsOf(kSun, eye);
    ASSERT_EQ(levels.size(), s.sunLevels());
    EXPECT_EQ(s.sunLevels(), s.levels + 5u) << "32 pages a side: five mips above the scene's";
    const glm::vec2 eyeLight = glm::vec2(levels[0].projection.view * glm::vec4(eye, 1.0f));
    const glm::vec4 scene = fitDirectional(kSun, kField, s.size).window;
    uint32_t offset = 0, clamped = 0;
    for (uint32_t l = 0; l < levels.size(); ++l) {
        const VirtualLevel& v = levels[l];
        const glm::vec4 w = v.projection.window;
        const float pageWorld = (w.y - w.x) / static_cast<float>(v.pagesPerSide);
        EXPECT_EQ(v.level, l);
        EXPECT_EQ(v.tableOffset, offset);
        offset += v.tableEntries();
        EXPECT_NEAR(w.w - w.z, w.y - w.x, 1e-4f * (w.y - w.x)) << "square";
        EXPECT_NEAR(v.projection.texelWorldSize * static_cast<float>(s.pageSize), pageWorld,
                    1e-5f * pageWorld);
        // Every level shares the first's orientation and depth range; each level's texel is
        // twice the one below's.
        EXPECT_EQ(v.projection.view, levels[0].projection.view);
        EXPECT_EQ(v.projection.nearPlane, levels[0].projection.nearPlane);
        EXPECT_EQ(v.projection.farPlane, levels[0].projection.farPlane);
        if (l > 0) {
            EXPECT_NEAR(v.projection.texelWorldSize, 2.0f * levels[l - 1].projection.texelWorldSize,
                        1e-5f * v.projection.texelWorldSize);
        }
        if (l >= s.levels) { // the scene level's mips: its window, half the pages a side
            EXPECT_EQ(v.pagesPerSide, s.pagesPerSide() >> (l - s.levels + 1));
            EXPECT_EQ(w, levels[s.levels - 1].projection.window);
            continue;
        }
        EXPECT_EQ(v.pagesPerSide, s.pagesPerSide());
        // Whole pages: the window starts at its first page's place in the level's grid.
        EXPECT_NEAR(w.x, static_cast<float>(v.firstPage.x) * pageWorld,
                    1e-4f * pageWorld + 1e-6f * std::abs(w.x));
        EXPECT_NEAR(w.z, static_cast<float>(v.firstPage.y) * pageWorld,
                    1e-4f * pageWorld + 1e-6f * std::abs(w.z));
        // Centred on the camera to within a page, but kept over the scene along an axis where
        // it is smaller than the scene.
        const glm::vec2 centre(0.5f * (w.x + w.y), 0.5f * (w.z + w.w));
        glm::vec2 expected = eyeLight;
        for (int a = 0; a < 2; ++a) {
            const float lo = scene[2 * a] + 0.5f * (w.y - w.x);
            const float hi = scene[2 * a + 1] - 0.5f * (w.y - w.x);
            expected[a] = lo > hi ? 0.5f * (scene[2 * a] + scene[2 * a + 1])
                                  : std::clamp(eyeLight[a], lo, hi);
        }
        EXPECT_LE(std::abs(centre.x - expected.x), 1.0001f * pageWorld) << "level " << l;
        EXPECT_LE(std::abs(centre.y - expected.y), 1.0001f * pageWorld) << "level " << l;
        clamped += expected != eyeLight;
    }
    EXPECT_EQ(offset, virtualTableEntries(kSun, s));
    EXPECT_EQ(levels.size(), virtualViewCount(kSun, s));
    EXPECT_GE(clamped, 2u) << "the coarse levels stay over the scene";
    EXPECT_LE(clamped, 4u) << "the fine levels follow the camera";
    EXPECT_EQ(levels.back().pagesPerSide, 1u);
    // The scene's level holds the whole scene.
    for (float x : {kField.min.x, kField.max.x})
        for (float y : {kField.min.y, kField.max.y})
            for (float z : {kField.min.z, kField.max.z}) {
                const glm::vec3 uvz = uvOf(levels[s.levels - 1], {x, y, z});
                EXPECT_TRUE(gpu::virtualHolds(glm::vec2(uvz), 1.0f, 0.0f)) << x << " " << y;
                EXPECT_GE(uvz.z, 0.0f);
                EXPECT_LE(uvz.z, 1.0f);
            }
}

TEST(VirtualMaps, ACameraMoveKeepsEveryPageWhereItWasInTheWorld) {
    const VirtualSettings s = small();
    const std::vector<VirtualLevel> before = levelsOf(kSun, {10, 2, 10});
    const std::vector<VirtualLevel> after = levelsOf(kSun, {23.7f, 2, -4.1f});
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> near(-30.0f, 30.0f);
    size_t compared = 0, moved = 0;
    for (uint32_t l = 0; l < before.size(); ++l) {
        moved += before[l].firstPage != after[l].firstPage;
        for (int i = 0; i < 200; ++i) {
            const glm::vec3 p{near(rng) + 15.0f, 1.0f, near(rng)};
            const glm::vec2 a = glm::vec2(uvOf(before[l], p)), b = glm::vec2(uvOf(after[l], p));
            if (!gpu::virtualHolds(a, 1.0f, 0.0f) || !gpu::virtualHolds(b, 1.0f, 0.0f))
                continue;
            // The same absolute page (the same key), and the same texel in it.
            const glm::ivec2 pa = pageOf(before[l], p, s.pageSize),
                             pb = pageOf(after[l], p, s.pageSize);
            EXPECT_EQ(before[l].firstPage + pa, after[l].firstPage + pb) << "level " << l;
            const uint32_t ea =
                gpu::virtualEntryIndex(before[l].tableOffset, before[l].pagesPerSide, pa);
            const uint32_t eb =
                gpu::virtualEntryIndex(after[l].tableOffset, after[l].pagesPerSide, pb);
            EXPECT_EQ(pageKeyOf(before[l], ea), pageKeyOf(after[l], eb)) << "level " << l;
            const float size = static_cast<float>(s.size);
            const glm::vec2 ta = a * size - glm::vec2(pa) * float(s.pageSize);
            const glm::vec2 tb = b * size - glm::vec2(pb) * float(s.pageSize);
            EXPECT_NEAR(ta.x, tb.x, 2e-2f);
            EXPECT_NEAR(ta.y, tb.y, 2e-2f);
            ++compared;
        }
    }
    EXPECT_GT(compared, 500u);
    EXPECT_GT(moved, 2u) << "the fine levels follow the camera";
    // Levels at least as large as the scene do not move.
    EXPECT_EQ(before[s.levels - 1].firstPage, after[s.levels - 1].firstPage);
}

// The chain a reader falls back on: for a page of any level, the page of every coarser level (of
// its light and face) that holds its middle, and nothing else.
TEST(VirtualMaps, EveryPageComesWithThePagesThatHoldItInCoarserLevels) {
    const VirtualSettings s = small();
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {12, 2, -7});
        std::mt19937 rng(11);
        size_t checked = 0;
        for (int i = 0; i < 40; ++i) {
            const VirtualLevel& level = levels[rng() % levels.size()];
            const uint32_t entry =
                level.tableOffset + static_cast<uint32_t>(rng() % level.tableEntries());
            const PageKey key = pageKeyOf(level, entry);
            const std::vector<PageKey> chain = withCoarserPages({key}, levels);
            // The page's middle in the world, at mid depth.
            const glm::ivec2 local = key.page - level.firstPage;
            const glm::vec2 uv = (glm::vec2(local) + 0.5f) / static_cast<float>(level.pagesPerSide);
            const glm::vec4 ndc(uv * 2.0f - 1.0f, 0.5f, 1.0f);
            const glm::vec4 w = glm::inverse(level.projection.viewProj) * ndc;
            const glm::vec3 middle = glm::vec3(w) / w.w;
            std::vector<PageKey> expected{key};
            for (const VirtualLevel& coarser : levels)
                if (coarser.face == level.face && coarser.level > level.level) {
                    const glm::vec2 c = glm::vec2(uvOf(coarser, middle));
                    if (!gpu::virtualHolds(c, 1.0f, 0.0f))
                        break;
                    const glm::ivec2 page = pageOf(coarser, middle, s.pageSize);
                    expected.push_back({.light = 0,
                                        .face = coarser.face,
                                        .level = coarser.level,
                                        .page = coarser.firstPage + page});
                }
            ASSERT_EQ(chain.size(), expected.size()) << int(light.type) << " level " << level.level;
            for (size_t k = 0; k < chain.size(); ++k)
                EXPECT_EQ(chain[k], expected[k]) << int(light.type) << " level " << level.level;
            checked += chain.size();
        }
        EXPECT_GT(checked, 80u);
    }
}

TEST(VirtualMaps, APagesProjectionFillsItsViewportWithTheLevelsTexels) {
    const VirtualSettings s = small();
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {5, 3, 5});
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(-20.0f, 20.0f);
        size_t checked = 0;
        for (const VirtualLevel& level : levels) {
            const float size = static_cast<float>(level.pagesPerSide * s.pageSize);
            for (int i = 0; i < 50; ++i) {
                const glm::vec3 p{u(rng), u(rng) * 0.2f + 2.0f, u(rng)};
                const glm::vec3 uvz = uvOf(level, p);
                if (!gpu::virtualHolds(glm::vec2(uvz), 1.0f, 0.0f) || uvz.z < 0.0f || uvz.z > 1.0f)
                    continue;
                const glm::vec2 texel = glm::vec2(uvz) * size;
                const glm::ivec2 page =
                    gpu::virtualPageOf(glm::ivec2(glm::floor(texel)), s.pageSize);
                const glm::vec4 c = pageViewProj(level, page) * glm::vec4(p, 1.0f);
                const glm::vec3 ndc = glm::vec3(c) / c.w;
                // In the page's viewport, at the texel's place in the page; the depth unchanged.
                const glm::vec2 local = (glm::vec2(ndc) * 0.5f + 0.5f) * float(s.pageSize);
                const glm::vec2 expected = texel - glm::vec2(page) * float(s.pageSize);
                EXPECT_NEAR(local.x, expected.x, 2e-2f) << level.level;
                EXPECT_NEAR(local.y, expected.y, 2e-2f) << level.level;
                EXPECT_NEAR(ndc.z, uvz.z, 1e-5f);
                ++checked;
            }
        }
        EXPECT_GT(checked, 50u);
    }
}

TEST(VirtualMaps, LocalLightsHaveMipsDownToOnePage) {
    const VirtualSettings s = small();
    EXPECT_EQ(s.localLevels(), 6u); // 32 pages a side: 32, 16, 8, 4, 2, 1
    for (const Light& light : {kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {});
        const uint32_t faces = light.type == LightType::Point ? 6u : 1u;
        ASSERT_EQ(levels.size(), faces * s.localLevels());
        uint32_t offset = 0;
        for (uint32_t i = 0; i < levels.size(); ++i) {
            const VirtualLevel& v = levels[i];
            const VirtualLevel& first = levels[i - v.level];
            EXPECT_EQ(v.face, i / s.localLevels());
            EXPECT_EQ(v.level, i % s.localLevels());
            EXPECT_EQ(v.pagesPerSide, s.pagesPerSide() >> v.level);
            EXPECT_EQ(v.tableOffset, offset);
            offset += v.tableEntries();
            EXPECT_FLOAT_EQ(v.projection.texelWorldSize,
                            first.projection.texelWorldSize * float(1u << v.level));
            EXPECT_EQ(v.projection.viewProj, first.projection.viewProj);
            EXPECT_TRUE(v.projection.perspective);
        }
        EXPECT_EQ(levels.back().pagesPerSide, 1u);
        EXPECT_EQ(offset, virtualTableEntries(light, s));
        EXPECT_EQ(levels.size(), virtualViewCount(light, s));
    }
}

TEST(VirtualMaps, APixelTakesTheFinestLevelNoFinerThanItself) {
    const float texel0 = 0.01f;
    for (uint32_t k = 0; k < 8; ++k)
        for (float f : {1.0f, 1.3f, 1.99f}) {
            const float pixel = texel0 * std::ldexp(f, static_cast<int>(k));
            EXPECT_EQ(gpu::virtualLevelFor(pixel, texel0, 0.0f, 16u), k) << pixel;
            EXPECT_EQ(gpu::virtualLevelFor(pixel, texel0, 1.0f, 16u), k + 1u);
            EXPECT_EQ(gpu::virtualLevelFor(pixel, texel0, -1.0f, 16u), k == 0 ? 0u : k - 1u);
        }
    EXPECT_EQ(gpu::virtualLevelFor(0.001f, texel0, 0.0f, 16u), 0u) << "finer than level 0";
    EXPECT_EQ(gpu::virtualLevelFor(1e6f, texel0, 0.0f, 5u), 4u) << "coarser than the last";
}

// virtual.lodFromImage: virtual.lodBias counts from a 1920x1080 image, half a level finer per
// halving of the pixels, two levels finer at most, one coarser at most.
TEST(VirtualMaps, TheLevelBiasFollowsTheImagesPixelCount) {
    const VirtualSettings v{.lodBias = -0.5f};
    EXPECT_FLOAT_EQ(v.levelBias(1920, 1080), -0.5f);
    EXPECT_FLOAT_EQ(v.levelBias(960, 540), -1.5f); // a quarter of the pixels: one level finer
    EXPECT_FLOAT_EQ(v.levelBias(1920, 540), -1.0f);
    EXPECT_FLOAT_EQ(v.levelBias(480, 270), -2.5f);
    EXPECT_FLOAT_EQ(v.levelBias(320, 180), -2.5f); // the finest it goes
    EXPECT_NEAR(v.levelBias(512, 512), -0.5f + 0.5f * std::log2(512.0f * 512.0f / 2073600.0f),
                1e-5f);
    EXPECT_FLOAT_EQ(v.levelBias(3840, 2160), 0.5f);
    EXPECT_FLOAT_EQ(v.levelBias(7680, 4320), 0.5f); // the coarsest
    const VirtualSettings off{.lodBias = 1.25f, .lodFromImage = false};
    EXPECT_FLOAT_EQ(off.levelBias(320, 180), 1.25f);
    EXPECT_FLOAT_EQ(off.levelBias(3840, 2160), 1.25f);
    ParameterValues p;
    EXPECT_TRUE(VirtualSettings::of(p).lodFromImage);
    p.set("virtual.lodFromImage", "false");
    EXPECT_FALSE(VirtualSettings::of(p).lodFromImage);
}

TEST(VirtualMaps, AnAtlasTexelBelongsToOnePageAndOneTexel) {
    const uint32_t pageSize = 8, side = 4;
    std::set<std::pair<int, int>> seen;
    for (uint32_t entry = 1; entry <= side * side; ++entry)
        for (int y = 0; y < int(pageSize); ++y)
            for (int x = 0; x < int(pageSize); ++x) {
                // Texel (x, y) of virtual page (5, 3), resident in physical page entry - 1.
                const glm::ivec2 texel = glm::ivec2(5, 3) * int(pageSize) + glm::ivec2(x, y);
                const glm::ivec2 a = gpu::virtualAtlasTexel(entry, texel, pageSize, side);
                EXPECT_EQ(a / int(pageSize), glm::ivec2((entry - 1) % side, (entry - 1) / side));
                EXPECT_EQ(a % int(pageSize), glm::ivec2(x, y));
                EXPECT_TRUE(seen.insert({a.x, a.y}).second);
            }
    EXPECT_EQ(seen.size(), size_t(side * side * pageSize * pageSize));
    EXPECT_EQ(gpu::virtualEntryIndex(100u, 32u, {3, 2}), 100u + 2u * 32u + 3u);
}

namespace {
PageKey key(uint32_t level, int x, uint32_t light = 0) {
    return {.light = light, .level = level, .page = {x, 0}};
}
} // namespace

TEST(PageCache, PagesStayResidentAndOnlyNewOnesRender) {
    PageCache cache(8);
    const std::vector<PageKey> view{key(0, 1), key(0, 2), key(1, 1), key(0, 1)};
    PageCache::Update first = cache.update(view, 1);
    EXPECT_EQ(first.requested, 3u) << "a page asked for twice is one";
    EXPECT_EQ(first.render.size(), 3u);
    EXPECT_EQ(first.cached, 0u);
    PageCache::Update second = cache.update(view, 2);
    EXPECT_TRUE(second.render.empty());
    EXPECT_EQ(second.cached, 3u);
    PageCache::Update third = cache.update({key(0, 1), key(0, 3)}, 3);
    ASSERT_EQ(third.render.size(), 1u);
    EXPECT_EQ(third.render[0].second, key(0, 3));
    EXPECT_EQ(third.evicted, 0u) << "free pages first";
    EXPECT_EQ(cache.resident(), 4u);
    std::set<uint32_t> physical;
    for (const PageKey& k : {key(0, 1), key(0, 2), key(1, 1), key(0, 3)})
        physical.insert(cache.physicalOf(k).value());
    EXPECT_EQ(physical.size(), 4u);
}

TEST(PageCache, TheLeastRecentlyUsedPageGoesFirst) {
    PageCache cache(4);
    cache.update({key(0, 1), key(0, 2), key(0, 3), key(0, 4)}, 1);
    cache.update({key(0, 1), key(0, 3)}, 2);
    cache.update({key(0, 2)}, 3);
    // Page 4 was last used in frame 1, page 1 and 3 in frame 2, page 2 in frame 3.
    const uint32_t slot4 = cache.physicalOf(key(0, 4)).value();
    PageCache::Update u = cache.update({key(0, 5)}, 4);
    ASSERT_EQ(u.render.size(), 1u);
    EXPECT_EQ(u.evicted, 1u);
    EXPECT_EQ(u.render[0].first, slot4);
    EXPECT_FALSE(cache.physicalOf(key(0, 4)));
    const uint32_t slot1 = cache.physicalOf(key(0, 1)).value();
    const uint32_t slot3 = cache.physicalOf(key(0, 3)).value();
    u = cache.update({key(0, 6), key(0, 2)}, 5);
    ASSERT_EQ(u.render.size(), 1u);
    EXPECT_TRUE(u.render[0].first == slot1 || u.render[0].first == slot3);
    EXPECT_TRUE(cache.physicalOf(key(0, 2))) << "requested this frame: never evicted";
}

TEST(PageCache, AFullPoolKeepsTheCoarsestPagesAndSaysWhatItDropped) {
    PageCache cache(3);
    PageCache::Update u = cache.update({key(0, 1), key(0, 2), key(3, 0), key(1, 7), key(2, 4)}, 1);
    EXPECT_EQ(u.requested, 5u);
    EXPECT_EQ(u.dropped, 2u);
    EXPECT_EQ(u.render.size(), 3u);
    EXPECT_TRUE(cache.physicalOf(key(3, 0)));
    EXPECT_TRUE(cache.physicalOf(key(2, 4)));
    EXPECT_TRUE(cache.physicalOf(key(1, 7)));
    EXPECT_FALSE(cache.physicalOf(key(0, 1)));
    // Next frame, the same: nothing evicted for a page of the same frame.
    u = cache.update({key(0, 1), key(0, 2), key(3, 0), key(1, 7), key(2, 4)}, 2);
    EXPECT_EQ(u.dropped, 2u);
    EXPECT_EQ(u.evicted, 0u);
    EXPECT_TRUE(u.render.empty());
}

TEST(PageCache, ALightThatChangesLosesItsPagesAndOnlyItsOwn) {
    PageCache cache(8);
    EXPECT_EQ(cache.keyLight(0, 11), 0u);
    EXPECT_EQ(cache.keyLight(1, 22), 0u);
    cache.update({key(0, 1, 0), key(0, 2, 0), key(0, 1, 1)}, 1);
    EXPECT_EQ(cache.keyLight(0, 11), 0u) << "the same key keeps them";
    EXPECT_EQ(cache.keyLight(1, 22), 0u);
    EXPECT_EQ(cache.keyLight(0, 12), 2u);
    EXPECT_FALSE(cache.physicalOf(key(0, 1, 0)));
    EXPECT_TRUE(cache.physicalOf(key(0, 1, 1)));
    const PageCache::Update u = cache.update({key(0, 1, 0), key(0, 1, 1)}, 2);
    EXPECT_EQ(u.render.size(), 1u);
    EXPECT_EQ(u.cached, 1u);
}

TEST(PageCache, TheLightsKeyFollowsWhatItsPagesHold) {
    const VirtualSettings s = small();
    auto keyOf = [&](const Light& light, glm::vec3 camera, const VirtualSettings& v,
                     glm::vec2 bias) {
        return pageContentsKey(light, levelsOf(light, camera, v), v, bias);
    };
    const glm::vec2 bias{0.0005f, 2.0f};
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const uint64_t k = keyOf(light, {0, 2, 0}, s, bias);
        EXPECT_EQ(keyOf(light, {50, 2, -30}, s, bias), k) << "a camera move keeps the pages";
        Light moved = light;
        if (light.type == LightType::Point)
            moved.position.x += 0.01f;
        else
            moved.direction = glm::normalize(light.direction + glm::vec3(0.01f, 0, 0));
        EXPECT_NE(keyOf(moved, {0, 2, 0}, s, bias), k);
        EXPECT_NE(keyOf(light, {0, 2, 0}, s, {0.001f, 2.0f}), k);
        VirtualSettings bigger = s;
        bigger.size *= 2;
        EXPECT_NE(keyOf(light, {0, 2, 0}, bigger, bias), k);
    }
}

TEST(PageCache, RequestsBecomeTheTablesResidentEntries) {
    const VirtualSettings s = small();
    const std::vector<VirtualLevel> levels = levelsOf(kPoint, {});
    const uint32_t entries = levels.back().tableOffset + levels.back().tableEntries();
    std::vector<uint32_t> requests(entries, 0u);
    const std::vector<uint32_t> asked{0, 5, 1023, levels[7].tableOffset + 3, entries - 1};
    for (uint32_t e : asked)
        requests[e] = 1u;
    const std::vector<PageKey> pages = requestedPages(levels, requests.data());
    ASSERT_EQ(pages.size(), asked.size());
    PageCache cache(s.poolPages());
    cache.update(pages, 1);
    const std::vector<uint32_t> table = pageTable(levels, cache, entries);
    std::set<uint32_t> physical;
    for (uint32_t e = 0; e < entries; ++e) {
        const bool wanted = std::find(asked.begin(), asked.end(), e) != asked.end();
        EXPECT_EQ(table[e] != VIRTUAL_NOT_RESIDENT, wanted) << e;
        if (wanted)
            physical.insert(table[e]);
    }
    EXPECT_EQ(physical.size(), asked.size());
}

// virtual.staticLayer's pages: a stale page keeps its place and its static layer, leaves the
// table until an update renders it again (only when asked for), and says its layer is held; a
// page dropped, evicted or newly placed holds none.
TEST(PageCache, AStalePageKeepsItsPlaceAndStaticLayerButLeavesTheTable) {
    const VirtualSettings s = small();
    const std::vector<VirtualLevel> levels = levelsOf(kPoint, {});
    const uint32_t entries = levels.back().tableOffset + levels.back().tableEntries();
    const auto keyAt = [&](uint32_t entry) { return pageKeyOf(levels[0], entry); };
    PageCache cache(4);
    const PageCache::Update first = cache.update({keyAt(0), keyAt(1), keyAt(2)}, 1);
    ASSERT_EQ(first.staticHeld.size(), first.render.size());
    EXPECT_EQ(std::count(first.staticHeld.begin(), first.staticHeld.end(), 1), 0);
    const uint32_t where1 = cache.physicalOf(keyAt(1)).value();
    EXPECT_EQ(cache.staleIf([&](const PageKey& k) { return k == keyAt(1) || k == keyAt(2); }, true),
              2u);
    EXPECT_TRUE(cache.stale(where1));
    EXPECT_EQ(cache.resident(), 3u);
    std::vector<uint32_t> table = pageTable(levels, cache, entries);
    EXPECT_NE(table[levels[0].tableOffset + 0], VIRTUAL_NOT_RESIDENT);
    EXPECT_EQ(table[levels[0].tableOffset + 1], VIRTUAL_NOT_RESIDENT) << "stale: not read";
    EXPECT_EQ(table[levels[0].tableOffset + 2], VIRTUAL_NOT_RESIDENT);
    // Asked for again: rendered in its place with its layer; the other stays stale.
    const PageCache::Update second = cache.update({keyAt(0), keyAt(1), keyAt(3)}, 2);
    ASSERT_EQ(second.render.size(), 2u);
    ASSERT_EQ(second.staticHeld.size(), 2u);
    EXPECT_EQ(second.cached, 1u);
    for (size_t i = 0; i < second.render.size(); ++i) {
        const bool stale = second.render[i].second == keyAt(1);
        EXPECT_EQ(second.staticHeld[i], stale ? 1 : 0) << i;
        if (stale) {
            EXPECT_EQ(second.render[i].first, where1);
        }
    }
    EXPECT_FALSE(cache.stale(where1));
    const uint32_t where2 = cache.physicalOf(keyAt(2)).value();
    EXPECT_TRUE(cache.stale(where2));
    table = pageTable(levels, cache, entries);
    EXPECT_EQ(table[levels[0].tableOffset + 1], where1 + 1u);
    EXPECT_EQ(table[levels[0].tableOffset + 2], VIRTUAL_NOT_RESIDENT);
    // Rendered once, a page holds its layer: stale again, it is drawn over it; stale with its
    // layer lost (a first move), it is drawn whole, and holds its layer after.
    cache.staleIf([&](const PageKey& k) { return k == keyAt(3); }, true);
    const PageCache::Update third = cache.update({keyAt(3)}, 3);
    ASSERT_EQ(third.render.size(), 1u);
    EXPECT_EQ(third.staticHeld.at(0), 1);
    for (const bool keepLayer : {false, true}) {
        cache.staleIf([&](const PageKey& k) { return k == keyAt(3); }, keepLayer);
        const PageCache::Update again = cache.update({keyAt(3)}, 3);
        ASSERT_EQ(again.render.size(), 1u);
        EXPECT_EQ(again.render[0].first, third.render[0].first) << "in its place";
        EXPECT_EQ(again.staticHeld.at(0), keepLayer ? 1 : 0);
    }
    // Dropped, a stale page is gone, and placed again it holds no layer.
    EXPECT_EQ(cache.dropIf([&](const PageKey& k) { return k == keyAt(2); }), 1u);
    EXPECT_FALSE(cache.stale(where2));
    const PageCache::Update fourth = cache.update({keyAt(2)}, 4);
    ASSERT_EQ(fourth.render.size(), 1u);
    EXPECT_EQ(fourth.staticHeld.at(0), 0);
    // A stale page not asked for is taken as a free one is, before the least recently used valid
    // page (key 1, last asked for in frame 2; key 0 in frame 5), and is not counted evicted; its
    // new owner holds no layer and is not stale.
    EXPECT_TRUE(cache.update({keyAt(0), keyAt(2), keyAt(3)}, 5).render.empty()); // key 0: newer
    cache.staleIf([&](const PageKey& k) { return k == keyAt(0); }, true);
    const uint32_t where0 = cache.physicalOf(keyAt(0)).value();
    const PageCache::Update taken = cache.update({keyAt(2), keyAt(3), keyAt(8)}, 6);
    ASSERT_EQ(taken.render.size(), 1u);
    EXPECT_EQ(taken.render[0].first, where0);
    EXPECT_EQ(taken.evicted, 0u);
    EXPECT_TRUE(cache.physicalOf(keyAt(1)));
    cache.staleIf([&](const PageKey& k) { return k == keyAt(8); }, true);
    const PageCache::Update fifth = cache.update({keyAt(4), keyAt(5), keyAt(6), keyAt(7)}, 7);
    ASSERT_EQ(fifth.render.size(), 4u);
    EXPECT_EQ(fifth.evicted, 3u) << "keys 1, 2, 3; key 8 was stale";
    EXPECT_EQ(std::count(fifth.staticHeld.begin(), fifth.staticHeld.end(), 1), 0);
    EXPECT_FALSE(cache.stale(where0));
    EXPECT_EQ(cache.keyOf(where0).has_value(), true);
    EXPECT_NE(*cache.keyOf(where0), keyAt(0));
    (void)s;
}

// The debug views' picture (virtualPages): each page's state in its level's table, and the
// pool's owners, across frames that keep, cache, render, drop and (after the camera moved a
// sun's window on) hold pages no level shows.
TEST(PageCache, TheDebugViewsSayWhatEachPageIsAndWhoHoldsThePool) {
    const std::vector<VirtualLevel> levels = levelsOf(kSun, {0, 2, 0});
    const VirtualLevel& fine = levels[0];
    auto at = [&](uint32_t x, uint32_t y) { return pageKeyOf(fine, y * fine.pagesPerSide + x); };
    auto stateOf = [](const VirtualPages& v, const VirtualLevel& level, const PageKey& k) {
        const glm::ivec2 local = k.page - level.firstPage;
        return v.levels[0].pages.at(size_t(local.y) * level.pagesPerSide + size_t(local.x));
    };
    auto rendered = [](const PageCache::Update& u) {
        std::vector<uint32_t> physical;
        for (const auto& [p, k] : u.render)
            physical.push_back(p);
        return physical;
    };
    const PageKey a = at(3, 4), b = at(4, 4), c = at(3, 5), d = at(9, 1), e = at(10, 1),
                  f = at(11, 1);
    PageCache cache(4);
    cache.update({a, b, c}, 1);
    PageCache::Update u = cache.update({a, d}, 2);
    VirtualPages v = virtualPages(levels, cache, {a, d}, rendered(u), 2);
    ASSERT_EQ(v.levels.size(), levels.size());
    EXPECT_EQ(v.levels[0].pagesPerSide, fine.pagesPerSide);
    EXPECT_EQ(stateOf(v, fine, a), PageState::Cached);
    EXPECT_EQ(stateOf(v, fine, d), PageState::Rendered);
    EXPECT_EQ(stateOf(v, fine, b), PageState::Kept);
    EXPECT_EQ(stateOf(v, fine, c), PageState::Kept);
    EXPECT_EQ(std::count(v.levels[0].pages.begin(), v.levels[0].pages.end(), PageState::Absent),
              ptrdiff_t(fine.tableEntries()) - 4);
    for (size_t l = 1; l < v.levels.size(); ++l)
        for (PageState s : v.levels[l].pages)
            ASSERT_EQ(s, PageState::Absent) << "level " << l;
    ASSERT_EQ(v.poolOwner.size(), 4u);
    EXPECT_EQ(v.poolPagesPerSide, 2u);
    for (uint32_t p = 0; p < 4; ++p) {
        EXPECT_EQ(v.poolOwner[p], 0) << p;
        EXPECT_EQ(v.poolRendered[p], p == cache.physicalOf(d).value()) << p;
    }

    // A full pool: a and d stay cached, two new pages take b's and c's places, one is dropped.
    const std::vector<PageKey> five{a, d, e, f, at(12, 1)};
    u = cache.update(five, 3);
    EXPECT_EQ(u.dropped, 1u);
    v = virtualPages(levels, cache, five, rendered(u), 2);
    int states[5] = {};
    for (const PageKey& k : five)
        ++states[static_cast<int>(stateOf(v, fine, k))];
    EXPECT_EQ(states[int(PageState::Cached)], 2);
    EXPECT_EQ(states[int(PageState::Rendered)], 2);
    EXPECT_EQ(states[int(PageState::Dropped)], 1);
    EXPECT_EQ(stateOf(v, fine, b), PageState::Absent) << "evicted";

    // The camera moves far: the finest level's window no longer shows those pages, but the pool
    // still holds them until they are evicted.
    const std::vector<VirtualLevel> moved = levelsOf(kSun, {300, 2, -300});
    v = virtualPages(moved, cache, {}, {}, 2);
    for (uint32_t p = 0; p < 4; ++p)
        EXPECT_EQ(v.poolOwner[p], -2) << p;
    for (PageState s : v.levels[0].pages)
        ASSERT_EQ(s, PageState::Absent);
    // An empty pool: every page free.
    v = virtualPages(levels, PageCache(4), {}, {}, 2);
    for (int32_t owner : v.poolOwner)
        EXPECT_EQ(owner, -1);
}

// The levels are fitted to bounds snapped outward to a grid and to a nearest surface rounded
// down a quarter of an octave: a caster that moves a little inside them keeps every light's key,
// one that crosses the grid changes it.
TEST(VirtualMaps, LevelsFitSteadyBoundsAndNearestSurfaces) {
    const Bounds steady = steadyBounds(kField); // largest side 800: a grid of 16
    EXPECT_EQ(steady.min, glm::vec3(-400, 0, -400));
    EXPECT_EQ(steady.max, glm::vec3(400, 32, 400));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> any(-50.0f, 50.0f), side(0.01f, 40.0f);
    for (int i = 0; i < 50; ++i) {
        const glm::vec3 lo{any(rng), any(rng), any(rng)};
        const Bounds b{.min = lo, .max = lo + glm::vec3(side(rng), side(rng), side(rng))};
        const Bounds s = steadyBounds(b);
        const float largest = std::max({b.extent().x, b.extent().y, b.extent().z});
        const float grid = std::exp2(std::ceil(std::log2(largest / 64.0f)));
        for (int a = 0; a < 3; ++a) {
            EXPECT_LE(s.min[a], b.min[a]);
            EXPECT_LT(b.min[a] - s.min[a], grid);
            EXPECT_GE(s.max[a], b.max[a]);
            EXPECT_LT(s.max[a] - b.max[a], grid);
            EXPECT_EQ(std::fmod(s.min[a], grid), 0.0f);
        }
    }
    for (float d : {0.3f, 5.0f, 5.1f, 4.7f, 1000.0f}) {
        const float n = steadyNearestSurface(d);
        EXPECT_LE(n, d);
        EXPECT_GT(n, d * std::exp2(-0.25f));
        EXPECT_EQ(std::fmod(4.0f * std::log2(n), 1.0f), 0.0f) << d;
    }
    EXPECT_EQ(steadyNearestSurface(5.0f), steadyNearestSurface(5.1f));
    EXPECT_TRUE(std::isinf(steadyNearestSurface(INFINITY)));
    const VirtualSettings s = small();
    auto keyOf = [&](const Light& light, const Bounds& bounds, float nearest) {
        uint32_t offset = 0;
        return pageContentsKey(
            light,
            virtualLevels(light, 0, bounds, {0, 2, 0}, s, {.nearestSurface = nearest}, offset), s,
            {0.0005f, 2.0f});
    };
    Bounds taller = kField, deeper = kField;
    taller.max.y = 31.5f; // inside the grid's 32
    deeper.min.y = -0.5f; // past the grid's 0: every light's far plane or the sun's depths
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const uint64_t k = keyOf(light, kField, 5.0f);
        EXPECT_EQ(keyOf(light, taller, 5.1f), k) << int(light.type);
        EXPECT_NE(keyOf(light, deeper, 5.0f), k) << int(light.type);
    }
    EXPECT_NE(keyOf(kPoint, kField, 4.7f), keyOf(kPoint, kField, 5.0f));
}

TEST(VirtualMaps, EntryOfIsPageKeyOfsInverseInsideTheWindowOnly) {
    // A level whose window starts off the origin and whose table starts past others'.
    const VirtualLevel level{.light = 2,
                             .face = 3,
                             .level = 1,
                             .firstPage = {-5, 7},
                             .pagesPerSide = 4,
                             .tableOffset = 100};
    for (uint32_t e = 0; e < level.tableEntries(); ++e) {
        const PageKey key = pageKeyOf(level, level.tableOffset + e);
        EXPECT_EQ(entryOf(level, key.page), level.tableOffset + e) << e;
    }
    // Each side's first page outside: none (one past the last column is not the next row's
    // first, one before the first row not the previous level's).
    for (const glm::ivec2 outside : {glm::ivec2(-1, 0), glm::ivec2(4, 0), glm::ivec2(0, -1),
                                     glm::ivec2(0, 4), glm::ivec2(4, 3), glm::ivec2(3, 4)})
        EXPECT_FALSE(entryOf(level, level.firstPage + outside)) << outside.x << "," << outside.y;

    const VirtualLevel other{.light = 2, .face = 2, .level = 1};
    const std::vector<VirtualLevel> levels{other, level};
    EXPECT_EQ(levelOf(levels, {.light = 2, .face = 3, .level = 1}), &levels[1]);
    EXPECT_EQ(levelOf(levels, {.light = 2, .face = 2, .level = 1}), &levels[0]);
    EXPECT_EQ(levelOf(levels, {.light = 2, .face = 3, .level = 0}), nullptr);
    EXPECT_EQ(levelOf(levels, {.light = 1, .face = 3, .level = 1}), nullptr);
}

// Warm-up frames before a render's timed ones: two when the host decides (one frame asks, the
// next renders what it asked for), one when the device decides in the frame or without pages.
TEST(VirtualMaps, WarmUpFramesFollowWhoDecides) {
    EXPECT_EQ((VirtualSettings{.enabled = true}.warmUpFrames()), 2u);
    EXPECT_EQ((VirtualSettings{.enabled = true, .deviceDecides = true}.warmUpFrames()), 1u);
    EXPECT_EQ((VirtualSettings{.enabled = false}.warmUpFrames()), 1u);
    EXPECT_EQ((VirtualSettings{.enabled = false, .deviceDecides = true}.warmUpFrames()), 1u);
}
