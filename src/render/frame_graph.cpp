#include "render/frame_graph.h"

#include "penumbra/error.h"
#include "vk/sync.h"

#include <algorithm>
#include <numeric>

namespace penumbra::render {
namespace {

vk::ImageState imageState(Access access) {
    switch (access) {
    case Access::DepthAttachment:
        return vk::kDepthWrite;
    case Access::ColorAttachment:
        return vk::kColorWrite;
    case Access::FragmentSampled:
        return vk::kFragmentSampled;
    case Access::ComputeSampled:
        return vk::kComputeSampled;
    case Access::ComputeWrite:
        return vk::kComputeWrite;
    case Access::ComputeReadWrite:
        return vk::kComputeReadWrite;
    // Transfers at every transfer stage: copies, blits and clears alike.
    case Access::TransferRead:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    case Access::TransferWrite:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    default:
        break;
    }
    fatal(__FILE__, __LINE__, "FrameGraph: a buffer access on an image");
}

vk::BufferState bufferState(Access access) {
    constexpr VkPipelineStageFlags2 shaders = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                              VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    constexpr VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    switch (access) {
    case Access::UniformRead:
        return {shaders, VK_ACCESS_2_UNIFORM_READ_BIT};
    case Access::ComputeRead:
        return {compute, VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
    case Access::ComputeWrite:
        return {compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    case Access::ComputeReadWrite:
        return {compute,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    case Access::IndirectRead:
        return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | compute,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
    case Access::TransferRead:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
    case Access::TransferWrite:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
    case Access::HostRead:
        return {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
    default:
        break;
    }
    fatal(__FILE__, __LINE__, "FrameGraph: an image access on a buffer");
}

} // namespace

std::string_view phaseName(Phase phase) {
    switch (phase) {
    case Phase::LightSpace:
        return "light space";
    case Phase::GBuffer:
        return "G-buffer";
    case Phase::ScreenSpace:
        return "screen space";
    case Phase::PerLight:
        return "per light";
    case Phase::Composite:
        return "composite";
    case Phase::Readback:
        break;
    }
    return "readback";
}

const PooledImage& PassContext::image(ResourceId id) const {
    return graph.image(id);
}

VkBuffer PassContext::buffer(ResourceId id) const {
    return graph.buffer(id);
}

FrameGraph::FrameGraph(ResourcePool& pool, const FrameSizes& sizes) : mPool(pool), mSizes(sizes) {
    mPool.beginFrame();
}

ResourceId FrameGraph::declare(const ImageDecl& decl) {
    return mPool.acquire(decl, mSizes);
}

ResourceId FrameGraph::declare(const BufferDecl& decl) {
    return mPool.acquire(decl, mSizes);
}

ResourceId FrameGraph::importImage(std::string name, const vk::Image& image, Access current) {
    return mPool.importImage(std::move(name), image, current);
}

ResourceId FrameGraph::importBuffer(std::string name, VkBuffer buffer) {
    return mPool.importBuffer(std::move(name), buffer);
}

bool FrameGraph::holdsContents(ResourceId id) const {
    return mPool.holdsContents(id);
}

void FrameGraph::addPass(PassDecl pass) {
    PENUMBRA_CHECK(!mPlanned, "FrameGraph: a pass added after the frame was planned");
    mPasses.push_back(std::move(pass));
}

const PooledImage& FrameGraph::image(ResourceId id) const {
    return mPool.image(id);
}

VkBuffer FrameGraph::buffer(ResourceId id) const {
    return mPool.buffer(id);
}

const std::vector<PlannedPass>& FrameGraph::plan() {
    if (mPlanned)
        return mPlan;
    mPlanned = true;
    mPool.realize();
    std::vector<size_t> order(mPasses.size());
    std::iota(order.begin(), order.end(), size_t{0});
    // By phase, keeping the declaration order within each (which the checks below hold to the
    // order the passes' reads and writes imply).
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return mPasses[a].phase < mPasses[b].phase; });
    // Each resource's access as the plan leaves it, starting from the pool's (the last frame's).
    struct Track {
        std::optional<Access> last;
        bool touched = false; // used in this frame
    };
    std::vector<Track> track;
    auto trackOf = [&](ResourceId id) -> Track& {
        if (id >= track.size())
            track.resize(id + 1);
        Track& t = track[id];
        if (!t.touched)
            t.last = mPool.lastAccess(id);
        return t;
    };
    for (size_t index : order) {
        const PassDecl& pass = mPasses[index];
        PENUMBRA_CHECK(pass.name.empty() != pass.cost.has_value(),
                       "FrameGraph: pass \"" + pass.name + "\" " +
                           (pass.name.empty() ? "is untimed but declares a cost group"
                                              : "is timed but declares no cost group"));
        PlannedPass planned{.pass = index};
        for (size_t u = 0; u < pass.uses.size(); ++u) {
            const Use& use = pass.uses[u];
            for (size_t v = 0; v < u; ++v)
                PENUMBRA_CHECK(pass.uses[v].resource != use.resource ||
                                   pass.uses[v].access == use.access,
                               "FrameGraph: pass " + pass.name + " uses " +
                                   std::string(mPool.name(use.resource)) + " in two ways");
            Track& t = trackOf(use.resource);
            const bool image = mPool.isImage(use.resource);
            const bool firstThisFrame = !t.touched;
            t.touched = true;
            bool duplicate = false;
            for (size_t v = 0; v < u; ++v)
                duplicate = duplicate || pass.uses[v].resource == use.resource;
            if (duplicate)
                continue;
            // A per-frame resource nothing ever wrote cannot be read.
            PENUMBRA_CHECK(!reads(use.access) || t.last.has_value() ||
                               mPool.persistent(use.resource) || mPool.isImported(use.resource),
                           "FrameGraph: pass " + pass.name + " reads " +
                               std::string(mPool.name(use.resource)) +
                               ", which no earlier pass writes");
            const bool discard =
                firstThisFrame && !reads(use.access) && !mPool.persistent(use.resource);
            if (!t.last) {
                // Never used: an image's layout must be set; a buffer (host-written, or about to
                // be written) needs nothing.
                if (image)
                    planned.barriers.push_back({.resource = use.resource,
                                                .from = use.access,
                                                .to = use.access,
                                                .fromUndefined = true});
            } else if (*t.last != use.access || writes(use.access) || writes(*t.last)) {
                planned.barriers.push_back({.resource = use.resource,
                                            .from = *t.last,
                                            .to = use.access,
                                            .fromUndefined = image && discard});
            }
            t.last = use.access;
        }
        mPlan.push_back(std::move(planned));
    }
    return mPlan;
}

void FrameGraph::record(VkCommandBuffer cmd, vk::GpuTimer* timer) {
    plan();
    for (const PlannedPass& planned : mPlan) {
        const PassDecl& pass = mPasses[planned.pass];
        vk::Barriers barriers;
        for (const PlannedBarrier& b : planned.barriers) {
            if (mPool.isImage(b.resource)) {
                const vk::Image& image = mPool.image(b.resource).get();
                barriers.image(image, b.fromUndefined ? vk::kUndefined : imageState(b.from),
                               imageState(b.to));
            } else {
                barriers.buffer(mPool.buffer(b.resource), bufferState(b.from), bufferState(b.to));
            }
        }
        barriers.record(cmd);
        const bool timed = timer && !pass.name.empty();
        if (timed)
            timer->begin(cmd, pass.name, *pass.cost);
        PassContext context{.cmd = cmd, .graph = *this};
        pass.record(context);
        if (timed)
            timer->end(cmd);
        for (const Use& use : pass.uses) {
            mPool.setLastAccess(use.resource, use.access);
            if (writes(use.access) && mPool.persistent(use.resource))
                mPool.setHoldsContents(use.resource);
        }
    }
}

} // namespace penumbra::render
