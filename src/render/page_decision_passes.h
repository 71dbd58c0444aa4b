#pragma once
// Virtual pages decided on the device (docs/techniques.md, "Pages decided on the device"): the
// passes of decidePages (src/core/page_decisions.h) as compute dispatches (shaders/
// page_decisions.comp) over buffers the device keeps: the pool's owners from frame to frame, and
// each frame the page table and the list of pages to render, with no read-back in between. The
// host uploads what only it knows: the frame's levels (with each one's parent and its place in
// the missing pages' priority order), the lights re-keyed and the pages under moved casters.
#include "core/page_decisions.h"
#include "page_passes.h"
#include "vk/pipelines.h"
#include "vk/resources.h"
#include "vk/timestamps.h"

#include <vector>

namespace penumbra::render {

// Where its buffers live: `readable` (tests) keeps the owners, table and render list where the
// host reads them back; a frame's keep them in device memory. `slots`: frames in flight, each
// with its own host-written inputs and counts (a frame uses the slot it prepared).
struct PageDecisionOptions {
    bool readable = true;
    uint32_t slots = 1;
};

class PageDecisionPasses {
public:
    // A pool of `poolPages` physical pages, every one free.
    PageDecisionPasses(const vk::Context& ctx, uint32_t poolPages, PageDecisionOptions o = {});

    // Writes this frame's inputs into `slot` (the levels, lights re-keyed, moved pages;
    // `in.requests` when not empty: a test's, else the marking's buffer given to record). Throws
    // InputError when the frame's entries exceed what one dispatch reaches. The buffers of the
    // table's entries grow when it holds more than entryCapacity(): no frame may be in flight.
    void prepare(const PageDecisionInputs& in, uint32_t slot = 0);
    uint32_t entryCapacity() const { return mEntryCapacity; }
    void reserve(uint32_t entries);
    // The pool lost its contents: the next record frees every page first.
    void freeAll() { mOwnersUnset = true; }
    // The passes, in order, barriers between them, after every command submitted before (the
    // buffers they write are read by frames in flight); `requests`: one word per entry (the
    // page marking's), or VK_NULL_HANDLE for the ones prepare was given. The table, the render
    // list and the counts are ready for compute, indirect and transfer reads after.
    // `timer`: each pass timed as "pages.<pass>" (benchmarks).
    void record(VkCommandBuffer cmd, VkBuffer requests = VK_NULL_HANDLE,
                vk::GpuTimer* timer = nullptr, uint32_t slot = 0);

    // What the last recorded decisions said, once their commands finished: read back (tests;
    // the frame reads them on the device). result() and owners() need `readable`.
    PageDecisions result(uint32_t slot = 0) const;
    std::vector<PageOwner> owners() const;
    const gpu::PageCounts& counts(uint32_t slot = 0) const;
    // The candidates pass's work in the last decisions: tiles of the pool its workgroups read
    // (each stops once none of its candidates can rank below the missing pages' count).
    uint32_t candidateTilesRead() const;

    uint32_t poolPages() const { return mPoolPages; }
    VkBuffer table() const { return mTable.get(); }
    VkBuffer renderList() const { return mRender.get(); }
    VkBuffer countsBuffer(uint32_t slot) const { return mSlots.at(slot).counts.get(); }
    VkBuffer levels(uint32_t slot) const { return mSlots.at(slot).levels.get(); }
    uint32_t levelCount(uint32_t slot) const { return mSlots.at(slot).push.levelCount; }

private:
    struct Slot {
        vk::Buffer levels, moved, rekeyed, requests, counts; // the host's, each frame
        gpu::PagePush push{};
        std::vector<VirtualLevel> levelsNow; // the last prepared frame's: the result's keys
    };
    const vk::Context& mCtx;
    uint32_t mPoolPages;
    PageDecisionOptions mOptions;
    vk::PipelineLayout mLayout;
    std::vector<vk::PipelineHandle> mPasses; // by PAGES_PASS_*
    vk::Buffer mOwners, mCandidates, mRender;
    vk::Buffer mWanted, mMissing, mSums, mRanked, mTable; // per table entry
    std::vector<Slot> mSlots;
    uint32_t mEntryCapacity = 0;
    uint32_t mLastSlot = 0;
    bool mOwnersUnset = false; // in device memory: every page freed by the first record
};

} // namespace penumbra::render
