// History resources in the frame graph (render/frame_graph.h): last frame's version of a
// resource declared with Lifetime::History, and the clears that stand in for a history that
// holds nothing. The pool swaps the two versions (ResourcePool::acquire).
#include "render/frame_graph.h"

#include "penumbra/error.h"

#include <algorithm>

namespace penumbra::render {

ResourceId FrameGraph::previous(ResourceId id) const {
    return mPool.previousOf(id);
}

bool FrameGraph::historyValid(ResourceId id) const {
    return mPool.holdsContents(mPool.previousOf(id));
}

// Last frame's versions of history resources read this frame that hold nothing: cleared first,
// by passes the graph adds ahead of every other.
void FrameGraph::clearStaleHistory() {
    std::vector<ResourceId> stale;
    for (const PassDecl& pass : mPasses)
        for (const Use& use : pass.uses)
            if (reads(use.access) && mPool.isPrevious(use.resource) &&
                !mPool.holdsContents(use.resource) &&
                std::find(stale.begin(), stale.end(), use.resource) == stale.end())
                stale.push_back(use.resource);
    for (ResourceId id : stale) {
        auto clear = [id, image = mPool.isImage(id)](PassContext& c) {
            if (image) {
                const vk::Image& target = c.image(id).get();
                const VkImageSubresourceRange all{target.aspect, 0, VK_REMAINING_MIP_LEVELS, 0,
                                                  VK_REMAINING_ARRAY_LAYERS};
                if (target.aspect & VK_IMAGE_ASPECT_COLOR_BIT) {
                    const VkClearColorValue zero{};
                    vkCmdClearColorImage(c.cmd, target.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                         &zero, 1, &all);
                } else {
                    const VkClearDepthStencilValue zero{};
                    vkCmdClearDepthStencilImage(
                        c.cmd, target.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
                }
            } else {
                vkCmdFillBuffer(c.cmd, c.buffer(id), 0, VK_WHOLE_SIZE, 0);
            }
        };
        mPasses.insert(mPasses.begin(), PassDecl{.name = "",
                                                 .phase = Phase::LightSpace,
                                                 .uses = {{id, Access::TransferWrite}},
                                                 .record = clear});
    }
}

} // namespace penumbra::render
