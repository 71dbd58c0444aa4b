#pragma once
// A virtual pool too small for what a run's frames asked for (virtual.poolSize), said once after
// the run: runs of many quiet renders (render --fps, compare --timeline and --camera-path) would
// otherwise say nothing, or the same line a frame.
#include "penumbra/renderer.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace penumbra::cli {

struct PoolShortage {
    uint32_t poolPages = 0;
    uint32_t frames = 0;   // frames whose pool was too small for their view
    uint32_t rendered = 0; // frames rendered, warm-ups included
    uint32_t mostRequested = 0, mostDropped = 0;

    // One render's frames (nothing without virtual maps).
    void add(const RenderResult& result);
    // "warning: WHO: the virtual pool holds ..." (no WHO when empty); empty when no frame was
    // short.
    std::string warning(std::string_view who = {}) const;
};

} // namespace penumbra::cli
