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

class PageDecisionPasses {
public:
    // A pool of `poolPages` physical pages, every one free.
    PageDecisionPasses(const vk::Context& ctx, uint32_t poolPages);

    // Writes this frame's inputs (the levels, lights re-keyed, moved pages; `in.requests` when
    // not empty: a test's, else the marking's buffer given to record), growing the buffers the
    // table's entries need. Throws InputError when the frame's entries exceed what one dispatch
    // reaches.
    void prepare(const PageDecisionInputs& in);
    // The passes, in order, barriers between them; `requests`: one word per entry (the page
    // marking's), or VK_NULL_HANDLE for the ones prepare was given. The table and the render list
    // are ready for compute reads after.
    // `timer`: each pass timed as "pages.<pass>" (benchmarks).
    void record(VkCommandBuffer cmd, VkBuffer requests = VK_NULL_HANDLE,
                vk::GpuTimer* timer = nullptr);

    // What the last recorded decisions said, once their commands finished: read back (tests;
    // the frame reads them on the device).
    PageDecisions result() const;
    std::vector<PageOwner> owners() const;
    // The candidates pass's work in the last decisions: tiles of the pool its workgroups read
    // (each stops once none of its candidates can rank below the missing pages' count).
    uint32_t candidateTilesRead() const;

    VkBuffer table() const { return mTable.get(); }
    VkBuffer renderList() const { return mRender.get(); }

private:
    const vk::Context& mCtx;
    uint32_t mPoolPages;
    vk::PipelineLayout mLayout;
    std::vector<vk::PipelineHandle> mPasses; // by PAGES_PASS_*
    vk::Buffer mOwners, mCandidates, mRender, mCounts;
    vk::Buffer mLevels, mMoved, mRekeyed;                            // the host's, each frame
    vk::Buffer mRequests, mWanted, mMissing, mSums, mRanked, mTable; // per table entry
    uint32_t mEntryCapacity = 0;
    gpu::PagePush mPush{};
    std::vector<VirtualLevel> mLevelsNow; // the last prepared frame's: the result's keys
};

} // namespace penumbra::render
