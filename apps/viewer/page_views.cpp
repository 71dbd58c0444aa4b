#include "page_views.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::viewer {
namespace {

constexpr std::array<uint8_t, 3> kLetterbox{40, 40, 48};
constexpr std::array<uint8_t, 3> kGap{10, 10, 10};
constexpr std::array<uint8_t, 3> kFree{20, 20, 20};
constexpr std::array<uint8_t, 3> kElsewhere{110, 110, 110}; // held for no level shown now

// Draws an n x n grid of cells, cell (x, y) coloured by `color(x, y)`, into an RGBA image.
template <class CellColor>
std::vector<uint8_t> gridImage(uint32_t n, uint32_t width, uint32_t height, CellColor color) {
    std::vector<uint8_t> rgba(size_t{width} * height * 4, 255);
    const uint32_t side = std::min(width, height);
    const uint32_t x0 = (width - side) / 2, y0 = (height - side) / 2;
    const bool gaps = n > 0 && side / n >= 6;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            std::array<uint8_t, 3> c = kLetterbox;
            if (n > 0 && x >= x0 && y >= y0 && x < x0 + side && y < y0 + side) {
                // The cell under the pixel: floor((x - x0) n / side), exact in integers.
                const uint64_t cx = uint64_t{x - x0} * n / side, cy = uint64_t{y - y0} * n / side;
                const bool edge = gaps && (uint64_t{x - x0 + 1} * n / side != cx ||
                                           uint64_t{y - y0 + 1} * n / side != cy);
                c = edge ? kGap : color(static_cast<uint32_t>(cx), static_cast<uint32_t>(cy));
            }
            std::copy(c.begin(), c.end(), rgba.begin() + 4 * (size_t{y} * width + x));
        }
    return rgba;
}

} // namespace

std::array<uint8_t, 3> pageStateColor(PageState state) {
    switch (state) {
    case PageState::Absent:
        return kFree;
    case PageState::Kept:
        return {60, 90, 170};
    case PageState::Cached:
        return {60, 175, 85};
    case PageState::Rendered:
        return {235, 70, 50};
    case PageState::Dropped:
        return {245, 215, 40};
    }
    return kFree;
}

std::array<uint8_t, 3> poolLevelColor(uint32_t level, uint32_t levels, bool rendered) {
    // Hue from red (finest) to blue (coarsest), brightness half unless rendered this frame.
    const float t = levels > 1 ? float(level) / float(levels - 1) : 0.0f;
    const float r = std::clamp(1.5f - 2.0f * t, 0.0f, 1.0f);
    const float g = std::clamp(1.0f - 2.0f * std::abs(t - 0.45f), 0.0f, 1.0f);
    const float b = std::clamp(2.0f * t - 0.5f, 0.0f, 1.0f);
    const float scale = rendered ? 255.0f : 140.0f;
    const float floor = rendered ? 60.0f : 30.0f; // no cell as dark as a free one
    auto channel = [&](float v) { return static_cast<uint8_t>(floor + (scale - floor) * v); };
    return {channel(r), channel(g), channel(b)};
}

PageWindow usedWindow(const VirtualPages::Level& level) {
    const uint32_t n = level.pagesPerSide;
    uint32_t x0 = n, y0 = n, x1 = 0, y1 = 0; // the used pages' box, inclusive
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x)
            if (level.pages[size_t{y} * n + x] != PageState::Absent)
                x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x),
                y1 = std::max(y1, y);
    if (x0 > x1)
        return {0, 0, n};
    const uint32_t side = std::min(n, std::max({8u, x1 - x0 + 3, y1 - y0 + 3}));
    // Centred on the box, moved back inside the table.
    auto start = [&](uint32_t lo, uint32_t hi) {
        const int64_t centred = (int64_t{lo} + hi + 1 - side) / 2;
        return static_cast<uint32_t>(std::clamp<int64_t>(centred, 0, n - side));
    };
    return {start(x0, x1), start(y0, y1), side};
}

std::vector<uint8_t> pageTableImage(const VirtualPages::Level& level, PageWindow window,
                                    uint32_t width, uint32_t height) {
    const uint32_t n = level.pagesPerSide;
    return gridImage(window.side, width, height, [&](uint32_t x, uint32_t y) {
        return pageStateColor(level.pages.at(size_t{window.y + y} * n + window.x + x));
    });
}

std::vector<uint8_t> poolImage(const VirtualPages& pages, uint32_t width, uint32_t height) {
    uint32_t levels = 0;
    for (const VirtualPages::Level& l : pages.levels)
        levels = std::max(levels, l.level + 1);
    const uint32_t n = pages.poolPagesPerSide;
    return gridImage(n, width, height, [&](uint32_t x, uint32_t y) {
        const size_t physical = size_t{y} * n + x;
        const int32_t owner = pages.poolOwner.at(physical);
        if (owner == -1)
            return kFree;
        if (owner < 0)
            return kElsewhere;
        return poolLevelColor(pages.levels.at(static_cast<size_t>(owner)).level, levels,
                              pages.poolRendered.at(physical) != 0);
    });
}

std::string levelName(const VirtualPages::Level& level, bool cube) {
    static const char* const kFaces[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    return cube ? fmt::format("light {} {} level {}", level.light, kFaces[level.face % 6],
                              level.level)
                : fmt::format("light {} level {}", level.light, level.level);
}

} // namespace penumbra::viewer
