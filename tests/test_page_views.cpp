// The viewer's virtual-map views on the host (apps/viewer/page_views.h): a page lands in its own
// cell (column x, row y), the window around the used pages holds them all and stays inside the
// table, and the pool's cells follow their owners' levels.
#include "page_views.h"

#include <gtest/gtest.h>

namespace penumbra::viewer {
namespace {

VirtualPages::Level levelWith(uint32_t n, std::vector<std::pair<glm::uvec2, PageState>> pages) {
    VirtualPages::Level level{.pagesPerSide = n,
                              .pages = std::vector<PageState>(size_t{n} * n, PageState::Absent)};
    for (const auto& [at, state] : pages)
        level.pages[size_t{at.y} * n + at.x] = state;
    return level;
}

// The colour at the centre of cell (x, y) of an n x n grid drawn into width x height.
std::array<uint8_t, 3> cell(const std::vector<uint8_t>& rgba, uint32_t width, uint32_t height,
                            uint32_t n, uint32_t x, uint32_t y) {
    const uint32_t side = std::min(width, height);
    const uint32_t px = (width - side) / 2 + static_cast<uint32_t>((x + 0.5) * side / n);
    const uint32_t py = (height - side) / 2 + static_cast<uint32_t>((y + 0.5) * side / n);
    const uint8_t* p = &rgba[4 * (size_t{py} * width + px)];
    return {p[0], p[1], p[2]};
}

} // namespace

TEST(PageViews, APageIsDrawnInItsOwnColumnAndRow) {
    const VirtualPages::Level level =
        levelWith(16, {{{5, 2}, PageState::Rendered}, {{6, 2}, PageState::Cached}});
    const PageWindow window = usedWindow(level);
    EXPECT_EQ(window.side, 8u) << "at least 8 pages a side";
    ASSERT_LE(window.x, 5u);
    ASSERT_LE(window.y, 2u);
    EXPECT_GE(window.x + window.side, 8u) << "a page of margin";
    const std::vector<uint8_t> image = pageTableImage(level, window, 120, 96);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const PageState expected = level.pages[size_t{window.y + y} * 16 + window.x + x];
            EXPECT_EQ(cell(image, 120, 96, 8, x, y), pageStateColor(expected)) << x << " " << y;
        }
    EXPECT_NE(pageStateColor(PageState::Rendered), pageStateColor(PageState::Cached));
    // The whole table: the page at column 5, row 2, not row 5, column 2.
    const std::vector<uint8_t> whole = pageTableImage(level, {0, 0, 16}, 64, 64);
    EXPECT_EQ(cell(whole, 64, 64, 16, 5, 2), pageStateColor(PageState::Rendered));
    EXPECT_EQ(cell(whole, 64, 64, 16, 2, 5), pageStateColor(PageState::Absent));
}

TEST(PageViews, TheUsedWindowHoldsEveryUsedPageAndStaysInsideTheTable) {
    EXPECT_EQ(usedWindow(levelWith(32, {})).side, 32u) << "nothing used: the whole table";
    const VirtualPages::Level corner =
        levelWith(32, {{{31, 31}, PageState::Kept}, {{30, 29}, PageState::Dropped}});
    PageWindow w = usedWindow(corner);
    EXPECT_EQ(w.x + w.side, 32u);
    EXPECT_EQ(w.y + w.side, 32u);
    const VirtualPages::Level spread =
        levelWith(32, {{{1, 20}, PageState::Kept}, {{25, 22}, PageState::Cached}});
    w = usedWindow(spread);
    EXPECT_EQ(w.side, 27u) << "the used box, 25 pages wide, and a page each side";
    EXPECT_LE(w.x, 1u);
    EXPECT_GE(w.x + w.side, 26u);
    EXPECT_LE(w.y, 20u);
    EXPECT_GE(w.y + w.side, 23u);
    EXPECT_LE(w.x + w.side, 32u);
    EXPECT_EQ(usedWindow(levelWith(4, {{{0, 0}, PageState::Kept}})).side, 4u) << "a small table";
}

TEST(PageViews, ThePoolShowsEachPagesLevelAndWhetherItRendered) {
    VirtualPages pages;
    pages.levels = {levelWith(4, {}), levelWith(2, {})};
    pages.levels[0].level = 0;
    pages.levels[1].level = 3;
    pages.poolPagesPerSide = 2;
    pages.poolOwner = {-1, 0, 1, -2};
    pages.poolRendered = {0, 1, 0, 0};
    const std::vector<uint8_t> image = poolImage(pages, 40, 40);
    EXPECT_EQ(cell(image, 40, 40, 2, 0, 0), (std::array<uint8_t, 3>{20, 20, 20})) << "free";
    EXPECT_EQ(cell(image, 40, 40, 2, 1, 0), poolLevelColor(0, 4, true));
    EXPECT_EQ(cell(image, 40, 40, 2, 0, 1), poolLevelColor(3, 4, false));
    EXPECT_NE(poolLevelColor(0, 4, true), poolLevelColor(0, 4, false));
    EXPECT_NE(poolLevelColor(0, 4, false), poolLevelColor(3, 4, false));
    const auto elsewhere = cell(image, 40, 40, 2, 1, 1);
    EXPECT_EQ(elsewhere[0], elsewhere[2]) << "grey";
    EXPECT_NE(elsewhere, cell(image, 40, 40, 2, 0, 0));
}

} // namespace penumbra::viewer
