#include "render/page_decision_passes.h"

#include "penumbra/error.h"
#include "virtual_pages.h" // shaders/include: VIRTUAL_NOT_RESIDENT
#include "vk/sync.h"

#include <algorithm>
#include <climits>
#include <cstring>

namespace penumbra::render {
namespace {

constexpr VkBufferUsageFlags kStorage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr uint64_t kMostEntries = PAGES_MOST_ENTRIES;

vk::Buffer storage(const vk::Context& ctx, size_t bytes, vk::MemoryUse use, const char* name) {
    return vk::createBuffer(ctx, std::max<size_t>(bytes, 16), kStorage, use, name);
}

// Host-written inputs: the buffer grows to hold `values` (a frame's commands still in flight
// must not read a buffer that grows: the frame's slots are to own one each).
template <typename T>
void upload(const vk::Context& ctx, vk::Buffer& b, const std::vector<T>& values, const char* name) {
    const size_t bytes = values.size() * sizeof(T);
    if (!b.get() || b.size < bytes)
        b = storage(ctx, std::max(bytes, size_t{2} * b.size), vk::MemoryUse::Upload, name);
    std::memcpy(b.mapped, values.data(), bytes);
}

// The next pass reads or writes what the last one wrote.
void computeBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 from) {
    vk::memoryBarrier(cmd, from, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

uint32_t groupsOf(uint32_t count) {
    return (count + PAGES_BLOCK - 1) / PAGES_BLOCK;
}

} // namespace

PageDecisionPasses::PageDecisionPasses(const vk::Context& ctx, uint32_t poolPages,
                                       PageDecisionOptions o)
    : mCtx(ctx), mPoolPages(poolPages), mOptions(o), mSlots(std::max(o.slots, 1u)) {
    PENUMBRA_CHECK(poolPages > 0 && poolPages <= kMostEntries, "page pool size");
    mLayout = vk::createLayoutOf(ctx, {"page_decisions.comp"}, VK_SHADER_STAGE_COMPUTE_BIT,
                                 sizeof(gpu::PagePush));
    for (uint32_t pass = PAGES_PASS_FREE; pass <= PAGES_PASS_TABLE; ++pass) {
        const vk::SpecConstant which{SPEC_PAGE_PASS, pass};
        mPasses.push_back(
            vk::createComputePipeline(ctx, mLayout, "page_decisions.comp", {&which, 1}));
    }
    const vk::MemoryUse kept = o.readable ? vk::MemoryUse::Readback : vk::MemoryUse::DeviceLocal;
    mOwners = storage(ctx, poolPages * sizeof(gpu::PageOwnerData), kept, "page owners");
    if (o.readable) {
        const std::vector<gpu::PageOwnerData> free(poolPages,
                                                   {.page = {0, 0}, .level = PAGES_FREE});
        std::memcpy(mOwners.mapped, free.data(), free.size() * sizeof(gpu::PageOwnerData));
    }
    mOwnersUnset = !o.readable;
    mCandidates =
        storage(ctx, poolPages * sizeof(uint32_t), vk::MemoryUse::DeviceLocal, "page candidates");
    mRender = vk::createBuffer(ctx, std::max<size_t>(poolPages * sizeof(gpu::PageRenderData), 16),
                               kStorage, kept, "pages to render");
    for (Slot& slot : mSlots) { // zero until a frame decides in the slot (the viewer reads them)
        slot.counts = vk::createBuffer(ctx, sizeof(gpu::PageCounts),
                                       kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                           VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                                       vk::MemoryUse::Readback, "page counts");
        std::memset(slot.counts.mapped, 0, sizeof(gpu::PageCounts));
    }
}

void PageDecisionPasses::reserve(uint32_t entries) {
    if (entries <= mEntryCapacity)
        return;
    mEntryCapacity = std::max(entries, mEntryCapacity * 2);
    const size_t bytes = size_t{mEntryCapacity} * sizeof(uint32_t);
    if (mOptions.readable) // a test's requests; a frame's are the marking's buffer
        for (Slot& each : mSlots)
            each.requests = storage(mCtx, bytes, vk::MemoryUse::Upload, "page requests");
    mWanted = storage(mCtx, bytes, vk::MemoryUse::DeviceLocal, "pages wanted");
    mMissing = storage(mCtx, bytes, vk::MemoryUse::DeviceLocal, "pages missing");
    mRanked = storage(mCtx, bytes, vk::MemoryUse::DeviceLocal, "missing pages ranked");
    mSums = storage(mCtx, groupsOf(mEntryCapacity) * sizeof(uint32_t), vk::MemoryUse::DeviceLocal,
                    "page scan sums");
    mTable = storage(mCtx, bytes,
                     mOptions.readable ? vk::MemoryUse::Readback : vk::MemoryUse::DeviceLocal,
                     "page table");
}

void PageDecisionPasses::prepare(const PageDecisionInputs& in, uint32_t slotIndex) {
    Slot& slot = mSlots.at(slotIndex);
    const std::vector<VirtualLevel>& levels = *in.levels;
    uint64_t total = 0;
    for (const VirtualLevel& l : levels) {
        PENUMBRA_CHECK(l.tableOffset == total, "levels' tables follow one another");
        total += l.tableEntries();
    }
    if (total > kMostEntries)
        throw InputError("virtual", "a frame of " + std::to_string(total) +
                                        " page-table entries: the device decides at most " +
                                        std::to_string(kMostEntries));
    const auto entries = static_cast<uint32_t>(total);
    PENUMBRA_CHECK(in.requests.empty() || in.requests.size() == entries, "one request per entry");
    reserve(entries);
    if (!in.requests.empty()) {
        PENUMBRA_CHECK(mOptions.readable, "PageDecisionPasses: requests from the host in a frame");
        std::memcpy(slot.requests.mapped, in.requests.data(), in.requests.size_bytes());
    }

    // The missing pages' priority.
    const std::vector<size_t> order = missingPageOrder(levels);
    std::vector<gpu::PageLevelData> records(levels.size());
    uint32_t prioritySlot = 0;
    for (const size_t i : order) {
        records[i].priorityStart = prioritySlot;
        prioritySlot += levels[i].tableEntries();
    }
    std::vector<gpu::PageRectData> rects;
    for (size_t i = 0; i < levels.size(); ++i) {
        const VirtualLevel& l = levels[i];
        const VirtualLevel* parent =
            levelOf(levels, {.light = l.light, .face = l.face, .level = l.level + 1});
        gpu::PageLevelData& r = records[i];
        r.firstPage = l.firstPage;
        r.name = packLevel(l.light, l.face, l.level);
        r.pagesPerSide = l.pagesPerSide;
        r.tableOffset = l.tableOffset;
        r.parent = parent ? static_cast<uint32_t>(parent - levels.data()) : PAGES_NONE;
        r.followsCamera = l.followsCamera ? 1u : 0u;
        r.movedFirst = static_cast<uint32_t>(rects.size());
        if (!in.moved.empty())
            for (const PageRect& m : in.moved[i])
                rects.push_back(m.wholeLevel
                                    ? gpu::PageRectData{{INT_MIN, INT_MIN}, {INT_MAX, INT_MAX}}
                                    : gpu::PageRectData{m.lo, m.hi});
        r.movedCount = static_cast<uint32_t>(rects.size()) - r.movedFirst;
    }
    uint32_t rekeyedWords = 0;
    for (const uint32_t light : in.lightsRekeyed)
        rekeyedWords = std::max(rekeyedWords, light / 32 + 1);
    std::vector<uint32_t> rekeyed(rekeyedWords, 0u);
    for (const uint32_t light : in.lightsRekeyed)
        rekeyed[light / 32] |= 1u << (light % 32);

    upload(mCtx, slot.levels, records, "page levels");
    upload(mCtx, slot.moved, rects, "moved pages");
    upload(mCtx, slot.rekeyed, rekeyed, "lights re-keyed");
    slot.push = {.frame = in.frame,
                 .entries = entries,
                 .pages = mPoolPages,
                 .levelCount = static_cast<uint32_t>(levels.size()),
                 .anyMoved = in.moved.empty() ? 0u : 1u,
                 .rekeyedWords = rekeyedWords,
                 .scanBlocks = groupsOf(entries)};
    slot.levelsNow = levels;
}

void PageDecisionPasses::record(VkCommandBuffer cmd, VkBuffer requests, vk::GpuTimer* timer,
                                uint32_t slotIndex) {
    const Slot& slot = mSlots.at(slotIndex);
    mLastSlot = slotIndex;
    // A frame before may still read the table and the render list.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    if (mOwnersUnset) // every page free: level PAGES_FREE; the same key for each (by index)
        vkCmdFillBuffer(cmd, mOwners.get(), 0, VK_WHOLE_SIZE, PAGES_FREE);
    mOwnersUnset = false;
    vkCmdFillBuffer(cmd, mWanted.get(), 0, VK_WHOLE_SIZE, 0u);
    vkCmdFillBuffer(cmd, mTable.get(), 0, VK_WHOLE_SIZE, VIRTUAL_NOT_RESIDENT);
    vkCmdFillBuffer(cmd, slot.counts.get(), 0, VK_WHOLE_SIZE, 0u);
    computeBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    vk::PushDescriptors descriptors;
    descriptors.storageBuffer(PAGES_LEVELS, slot.levels.get())
        .storageBuffer(PAGES_REQUESTS, requests ? requests : slot.requests.get())
        .storageBuffer(PAGES_OWNERS, mOwners.get())
        .storageBuffer(PAGES_MOVED, slot.moved.get())
        .storageBuffer(PAGES_REKEYED, slot.rekeyed.get())
        .storageBuffer(PAGES_WANTED, mWanted.get())
        .storageBuffer(PAGES_MISSING, mMissing.get())
        .storageBuffer(PAGES_SUMS, mSums.get())
        .storageBuffer(PAGES_RANKED, mRanked.get())
        .storageBuffer(PAGES_CANDIDATES, mCandidates.get())
        .storageBuffer(PAGES_RENDER, mRender.get())
        .storageBuffer(PAGES_TABLE, mTable.get())
        .storageBuffer(PAGES_COUNTS, slot.counts.get())
        .push(mCtx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mLayout);
    const gpu::PagePush& push = slot.push;
    vkCmdPushConstants(cmd, mLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    const uint32_t pages = groupsOf(mPoolPages), entries = groupsOf(push.entries);
    const uint32_t groups[] = {pages, entries,         pages, entries, push.scanBlocks,
                               1,     push.scanBlocks, pages, pages,   pages};
    for (uint32_t pass = PAGES_PASS_FREE; pass <= PAGES_PASS_TABLE; ++pass) {
        if (pass > PAGES_PASS_FREE)
            computeBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        static constexpr const char* kNames[] = {"free", "want", "hold",       "missing", "scan",
                                                 "sums", "rank", "candidates", "assign",  "table"};
        if (timer)
            timer->begin(cmd, std::string("pages.") + kNames[pass], CostGroup::ShadowMaps);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mPasses[pass].get());
        if (groups[pass] > 0)
            vkCmdDispatch(cmd, groups[pass], 1, 1);
        if (timer)
            timer->end(cmd);
    }
    // The table and the render list for the frame's passes (the counts for indirect draws and
    // copies); the counts and owners for the host.
    vk::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT |
            VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_HOST_READ_BIT |
            VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

const gpu::PageCounts& PageDecisionPasses::counts(uint32_t slot) const {
    return *static_cast<const gpu::PageCounts*>(mSlots.at(slot).counts.mapped);
}

PageDecisions PageDecisionPasses::result(uint32_t slotIndex) const {
    PENUMBRA_CHECK(mOptions.readable, "PageDecisionPasses: read back from device memory");
    const gpu::PageCounts& counts = this->counts(slotIndex);
    const Slot& slot = mSlots.at(slotIndex);
    PageDecisions d{.requested = counts.requested,
                    .cached = counts.cached,
                    .evicted = counts.evicted,
                    .dropped = counts.dropped};
    const auto* table = static_cast<const uint32_t*>(mTable.mapped);
    d.table.assign(table, table + slot.push.entries);
    const auto* render = static_cast<const gpu::PageRenderData*>(mRender.mapped);
    for (uint32_t r = 0; r < counts.rendered; ++r) {
        const VirtualLevel* level = nullptr;
        for (const VirtualLevel& l : slot.levelsNow)
            if (render[r].entry >= l.tableOffset &&
                render[r].entry < l.tableOffset + l.tableEntries())
                level = &l;
        PENUMBRA_CHECK(level != nullptr, "a rendered page's entry");
        d.render.emplace_back(render[r].physical, pageKeyOf(*level, render[r].entry));
    }
    return d;
}

uint32_t PageDecisionPasses::candidateTilesRead() const {
    return counts(mLastSlot).tilesRead;
}

std::vector<PageOwner> PageDecisionPasses::owners() const {
    PENUMBRA_CHECK(mOptions.readable, "PageDecisionPasses: read back from device memory");
    const auto* owners = static_cast<const gpu::PageOwnerData*>(mOwners.mapped);
    std::vector<PageOwner> out(mPoolPages);
    for (uint32_t p = 0; p < mPoolPages; ++p)
        out[p] = {.level = owners[p].level, .page = owners[p].page, .lastUsed = owners[p].lastUsed};
    return out;
}

} // namespace penumbra::render
