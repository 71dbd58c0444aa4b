// The placement of a frame's transient images in shared memory (render/frame_memory.h).
#include "render/frame_memory.h"

#include "penumbra/error.h"

#include <algorithm>
#include <numeric>

namespace penumbra::render {
namespace {

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
    return (value + alignment - 1) / alignment * alignment;
}

bool spansOverlap(const TransientNeed& a, const TransientNeed& b) {
    return a.first <= b.last && b.first <= a.last;
}

} // namespace

VkDeviceSize AliasPlan::sharedBytes() const {
    VkDeviceSize sum = 0;
    for (const Block& b : blocks)
        sum += b.size;
    return sum;
}

bool sharesBytes(const AliasPlan& plan, std::span<const TransientNeed> needs, size_t a, size_t b) {
    const AliasPlan::Placement& pa = plan.placements[a];
    const AliasPlan::Placement& pb = plan.placements[b];
    return a != b && pa.block == pb.block && pa.offset < pb.offset + needs[b].size &&
           pb.offset < pa.offset + needs[a].size;
}

AliasPlan planAliasing(std::span<const TransientNeed> needs, VkDeviceSize maxBlockBytes) {
    AliasPlan plan;
    plan.placements.resize(needs.size());
    std::vector<size_t> order(needs.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return needs[a].size > needs[b].size; });
    std::vector<std::vector<size_t>> placedIn; // per block, the needs placed so far
    for (const size_t i : order) {
        const TransientNeed& need = needs[i];
        PENUMBRA_CHECK(need.size > 0 && need.alignment > 0 && need.first <= need.last,
                       "planAliasing: an empty image or a span that ends before it begins");
        // Per block: the lowest offset clear of every need placed there whose passes overlap
        // this one's, and how much the block would grow.
        size_t best = placedIn.size();
        VkDeviceSize bestOffset = 0, bestGrowth = 0;
        for (size_t b = 0; b < placedIn.size(); ++b) {
            if ((plan.blocks[b].memoryTypeBits & need.memoryTypeBits) == 0)
                continue;
            std::vector<VkDeviceSize> candidates{0};
            for (const size_t j : placedIn[b])
                if (spansOverlap(need, needs[j]))
                    candidates.push_back(plan.placements[j].offset + needs[j].size);
            std::sort(candidates.begin(), candidates.end());
            VkDeviceSize offset = 0;
            for (const VkDeviceSize candidate : candidates) {
                offset = alignUp(candidate, need.alignment);
                const bool clear =
                    std::none_of(placedIn[b].begin(), placedIn[b].end(), [&](size_t j) {
                        return spansOverlap(need, needs[j]) &&
                               offset < plan.placements[j].offset + needs[j].size &&
                               plan.placements[j].offset < offset + need.size;
                    });
                if (clear)
                    break;
            }
            const VkDeviceSize end = offset + need.size;
            if (end > maxBlockBytes)
                continue;
            const VkDeviceSize growth = end > plan.blocks[b].size ? end - plan.blocks[b].size : 0;
            if (best == placedIn.size() || growth < bestGrowth) {
                best = b;
                bestOffset = offset;
                bestGrowth = growth;
            }
        }
        if (best == placedIn.size()) {
            plan.blocks.push_back({.size = 0, .memoryTypeBits = need.memoryTypeBits});
            placedIn.emplace_back();
        }
        AliasPlan::Block& block = plan.blocks[best];
        block.memoryTypeBits &= need.memoryTypeBits;
        block.size = std::max(block.size, bestOffset + need.size);
        plan.placements[i] = {.block = best, .offset = bestOffset};
        placedIn[best].push_back(i);
        plan.separateBytes += need.size;
    }
    // A block that saves nothing (its images take no common bytes, or the alignment's padding
    // costs what they share; a real GPU aligns small images to more than their size) is split:
    // each of its images in a block of its own, as if it had never been shared.
    std::vector<AliasPlan::Block> kept;
    for (size_t b = 0; b < placedIn.size(); ++b) {
        VkDeviceSize own = 0;
        for (const size_t j : placedIn[b])
            own += needs[j].size;
        if (plan.blocks[b].size < own) {
            for (const size_t j : placedIn[b])
                plan.placements[j].block = kept.size();
            kept.push_back(plan.blocks[b]);
            continue;
        }
        for (const size_t j : placedIn[b]) {
            plan.placements[j] = {.block = kept.size(), .offset = 0};
            kept.push_back({.size = needs[j].size, .memoryTypeBits = needs[j].memoryTypeBits});
        }
    }
    plan.blocks = std::move(kept);
    return plan;
}

} // namespace penumbra::render
