// Transient images that share memory (render/resource_pool.h, realize; render/frame_memory.h):
// per-frame images the graph lets share are placed anew whenever what they are, or which of them
// are used beside which, change; otherwise they stay where they are.
#include "render/frame_memory.h"
#include "render/pool_entry.h"
#include "render/resource_pool.h"

#include <algorithm>

namespace penumbra::render {

void ResourcePool::placeTransients(std::span<const UseSpan> spans) {
    std::vector<ResourceId> chosen;
    std::vector<size_t> ends; // the chosen spans' first and last passes, in order
    for (ResourceId id = 0; id < mEntries.size() && id < spans.size(); ++id) {
        Entry* e = mEntries[id].get();
        const auto* decl = e ? std::get_if<ImageDecl>(&e->decl) : nullptr;
        if (!decl || decl->lifetime != Lifetime::PerFrame || !spans[id].shareable)
            continue;
        if (!e->ownMemory) // asked once: an entry keeps its shape and extent while it lives
            e->ownMemory = needsOwnMemory(imageDesc(*e));
        if (*e->ownMemory)
            continue;
        chosen.push_back(id);
        ends.insert(ends.end(), {spans[id].first, spans[id].last});
    }
    // Placed for the order of the spans' ends, not their passes' indices: which spans overlap
    // (all a placement depends on) stays the same when passes elsewhere come or go.
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    const auto rank = [&](size_t pass) {
        return static_cast<size_t>(std::lower_bound(ends.begin(), ends.end(), pass) - ends.begin());
    };
    std::vector<std::tuple<const Entry*, size_t, size_t>> placedFor;
    for (const ResourceId id : chosen)
        placedFor.emplace_back(mEntries[id].get(), rank(spans[id].first), rank(spans[id].last));
    const bool unchanged = placedFor == mPlacedFor &&
                           std::none_of(chosen.begin(), chosen.end(),
                                        [&](ResourceId id) { return mEntries[id]->pending; });
    if (unchanged)
        return;
    // Every image placed before goes (those no longer chosen are made alone by realize), then
    // the memory they were placed in.
    waitIdle();
    for (auto& e : mEntries)
        if (e && e->aliased) {
            e->image = {}; // its views before the image they view
            e->ownedImage = {};
            e->aliased = false;
            e->sharesWith.clear();
            e->pending = true;
            e->last.reset();
        }
    mShared.clear();
    mPlacedFor = std::move(placedFor);
    std::vector<TransientNeed> needs;
    std::vector<vk::ImageDesc> descs;
    for (const ResourceId id : chosen) {
        Entry& e = *mEntries[id];
        descs.push_back(imageDesc(e));
        VkMemoryRequirements asks{};
        e.ownedImage = vk::createUnboundImage(mCtx, descs.back(), asks);
        needs.push_back(
            {.first = spans[id].first,
             .last = spans[id].last,
             .size = asks.size,
             .alignment = asks.alignment,
             // Device-local types only: whatever types a block's images
             // have in common is then one its memory can be allocated from.
             .memoryTypeBits =
                 asks.memoryTypeBits & mCtx.memoryTypesWith(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)});
    }
    const AliasPlan plan = planAliasing(needs, mCtx.maxMemoryAllocationSize());
    for (const AliasPlan::Block& block : plan.blocks)
        mShared.push_back(vk::allocateDeviceLocal(
            mCtx, {.size = block.size, .alignment = 1, .memoryTypeBits = block.memoryTypeBits},
            "transient images"));
    for (size_t i = 0; i < chosen.size(); ++i) {
        Entry& e = *mEntries[chosen[i]];
        const AliasPlan::Placement& at = plan.placements[i];
        vk::bindImage(mCtx, e.ownedImage, descs[i], mShared[at.block].get(), at.offset);
        makeViews(e);
        e.aliased = true;
        e.pending = false;
        e.last.reset();
        ++mCreations;
        for (size_t j = 0; j < chosen.size(); ++j)
            if (sharesBytes(plan, needs, i, j))
                e.sharesWith.push_back(mEntries[chosen[j]].get());
    }
    mTransient = {.separate = plan.separateBytes, .shared = plan.sharedBytes()};
}

std::vector<ResourceId> ResourcePool::sharesMemoryWith(ResourceId id) const {
    std::vector<ResourceId> ids;
    for (const Entry* other : entry(id).sharesWith)
        for (ResourceId o = 0; o < mEntries.size(); ++o)
            if (mEntries[o].get() == other)
                ids.push_back(o);
    return ids;
}

} // namespace penumbra::render
