#include "pool_shortage.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::cli {

void PoolShortage::add(const RenderResult& result) {
    const auto& pages = result.virtualMaps;
    if (!pages)
        return;
    poolPages = pages->poolPages;
    frames += pages->droppedFrames;
    rendered += static_cast<uint32_t>(pages->renderedPerFrame.size());
    mostRequested = std::max(mostRequested, pages->requested);
    mostDropped = std::max(mostDropped, pages->dropped);
}

std::string PoolShortage::warning(std::string_view who) const {
    if (frames == 0)
        return {};
    return fmt::format("warning: {}{}the virtual pool holds {} pages; {} of {} frames (warm-ups "
                       "included) asked for more (at most {} pages, {} of them read coarser "
                       "pages; raise virtual.poolSize)",
                       who, who.empty() ? "" : ": ", poolPages, frames, rendered, mostRequested,
                       mostDropped);
}

} // namespace penumbra::cli
