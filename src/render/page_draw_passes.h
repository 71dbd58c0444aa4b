#pragma once
// The pages the device decided (PageDecisionPasses), drawn in the same command buffer
// (docs/techniques.md, "Pages decided on the device"): a setup dispatch lists each rendered
// page's matrix from the world to its square of the pool (shaders/page_draws.comp); then, over
// the whole pool as one viewport, an instanced clear of the squares at the far plane and the
// casters drawn once per page by indirect draws whose instance counts the device copies from the
// lists' lengths (shaders/page_draw.glsl: clip distances keep each instance in its square). Every
// caster is drawn into every page: the host path's per-page cluster culling has no device
// counterpart yet.
#include "core/virtual_maps.h"
#include "render/page_decision_passes.h"
#include "render/resource_pool.h"
#include "render/scene_upload.h"

namespace penumbra::render {

struct FramePipelines;

class PageDrawPasses {
public:
    // `readable` (tests): the lists where the host reads them back.
    PageDrawPasses(const vk::Context& ctx, uint32_t slots, bool readable = false);

    // The frame's levels' view-projections (in the decisions' level order), into `slot`.
    void prepare(const std::vector<VirtualLevel>& levels, uint32_t slot);
    // After decisions.record for the same slot: recordLists, then the clear and the casters into
    // `pool` (a depth attachment the caller's barriers leave writable; its contents kept).
    void record(VkCommandBuffer cmd, const PageDecisionPasses& decisions, const GpuScene& scene,
                const PooledImage& pool, uint32_t poolPagesPerSide, float constantBias,
                float slopeBias, uint32_t slot);
    // The setup alone: each page to render listed with its matrix and square, by kind; the
    // lists ready for vertex reads and their lengths for copies after.
    void recordLists(VkCommandBuffer cmd, const PageDecisionPasses& decisions,
                     uint32_t poolPagesPerSide, uint32_t slot);
    // A list (PAGE_DRAW_ORTHO or PAGE_DRAW_PERSPECTIVE) as the last lists left it, once their
    // commands finished (`readable`).
    std::vector<gpu::PageDrawData> listed(uint32_t kind) const;

private:
    struct Slot {
        vk::Buffer views, commands; // PageViewData by level; the indirect draws
    };
    const vk::Context& mCtx;
    vk::PipelineLayout mSetupLayout, mClearLayout, mOpaqueLayout, mMaskedLayout;
    vk::PipelineHandle mSetup, mClear;
    vk::PipelineHandle mOpaque[2], mMasked[2]; // by PAGE_DRAW_ORTHO / PAGE_DRAW_PERSPECTIVE
    vk::Buffer mList, mListCounts;
    uint32_t mListPages = 0;   // the lists' room: pages of the largest pool so far
    uint32_t mListedPages = 0; // the last lists' pool: where the second list starts
    bool mReadable;
    std::vector<Slot> mSlots;
};

} // namespace penumbra::render
