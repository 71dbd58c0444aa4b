#pragma once
// The viewer's debug views of virtual shadow maps, drawn on the host into the display's overlay
// (RGBA8, rows top to bottom): a level's page table and the physical pool. Colours in
// docs/viewer.md's legend and the interface's.
#include "penumbra/renderer.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::viewer {

// A page's colour in the page-table view.
std::array<uint8_t, 3> pageStateColor(PageState state);
// A level's colour in the pool view (finest red, through yellow and green, to the coarsest blue),
// at full brightness when the page was rendered this frame.
std::array<uint8_t, 3> poolLevelColor(uint32_t level, uint32_t levels, bool rendered);

// A square window of a level's pages: its first page and side in pages.
struct PageWindow {
    uint32_t x = 0, y = 0, side = 0;
};
// The smallest square around the pages that are not Absent, with a page of margin, at least 8
// pages a side (the whole table when it is smaller, or when no page is used).
PageWindow usedWindow(const VirtualPages::Level& level);

// One cell per page of `window`, the square grid fitted into width x height and centred (cells
// of at least 6 pixels get a 1-pixel gap so that single pages can be told apart).
std::vector<uint8_t> pageTableImage(const VirtualPages::Level& level, PageWindow window,
                                    uint32_t width, uint32_t height);
std::vector<uint8_t> poolImage(const VirtualPages& pages, uint32_t width, uint32_t height);

// "light 0 level 3" or "light 1 +x level 0".
std::string levelName(const VirtualPages::Level& level, bool cube);

} // namespace penumbra::viewer
