#include "render/frame_graph.h"

#include "render/access_states.h"

#include "penumbra/error.h"
#include "vk/sync.h"

#include <algorithm>

namespace penumbra::render {
std::string_view phaseName(Phase phase) {
    switch (phase) {
    case Phase::Geometry:
        return "geometry";
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
    for (const Use& use : usesOf(pass.bindings, pass.name))
        pass.uses.push_back(use);
    checkStorageFormats(pass.bindings, pass.name,
                        [this](ResourceId id) { return mPool.formatOf(id); });
    for (const Use& use : pass.uses)
        PENUMBRA_CHECK(!writes(use.access) || !mPool.isPrevious(use.resource),
                       "FrameGraph: pass \"" + pass.name + "\" writes " +
                           std::string(mPool.name(use.resource)) + ", last frame's version");
    mPasses.push_back(std::move(pass));
}

void FrameGraph::markOutput(ResourceId id) {
    mark(id).output = true;
}

void FrameGraph::markBoundOnly(ResourceId id) {
    mark(id).boundOnly = true;
}

const PooledImage& FrameGraph::image(ResourceId id) const {
    return mPool.image(id);
}

VkBuffer FrameGraph::buffer(ResourceId id) const {
    return mPool.buffer(id);
}

bool FrameGraph::outlivesFrame(ResourceId id) const {
    return mPool.persistent(id) || mPool.hostVisible(id) || // persistent: imported ones too
           (mPool.history(id) && !mPool.isPrevious(id)) ||  // the next frame reads it
           (id < mMarks.size() && mMarks[id].output);
}

std::vector<size_t> FrameGraph::cull(const std::vector<size_t>& order) {
    // Backwards: a pass is kept when its work leaves the frame (it writes a resource that
    // outlives it, or it declares no write: an effect the graph cannot see, such as the host's
    // read) or a kept pass after it reads what it writes. A write never ends a resource's
    // liveness: passes may write parts of one (a light's layer of the maps).
    std::vector<bool> read(resourceCount(), false);
    std::vector<size_t> kept;
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        const PassDecl& pass = mPasses[*it];
        bool keep = std::none_of(pass.uses.begin(), pass.uses.end(),
                                 [](const Use& u) { return writes(u.access); });
        for (const Use& use : pass.uses)
            keep =
                keep || (writes(use.access) && (outlivesFrame(use.resource) || read[use.resource]));
        if (!keep) {
            mCulled.push_back(*it);
            continue;
        }
        kept.push_back(*it);
        for (const Use& use : pass.uses)
            if (reads(use.access))
                read[use.resource] = true;
    }
    std::reverse(kept.begin(), kept.end());
    std::reverse(mCulled.begin(), mCulled.end());
    return kept;
}

void FrameGraph::checkReadsAndWrites(const std::vector<size_t>& order) const {
    // Every frame, not only a resource's first: a per-frame resource holds nothing from the last
    // frame, a persistent one only what its key kept. Indices into `order`, -1 for none.
    const size_t count = resourceCount();
    std::vector<int> firstWrite(count, -1), lastWrite(count, -1), lastRead(count, -1);
    for (size_t k = 0; k < order.size(); ++k)
        for (const Use& use : mPasses[order[k]].uses) {
            const auto at = static_cast<int>(k);
            if (writes(use.access)) {
                if (firstWrite[use.resource] < 0)
                    firstWrite[use.resource] = at;
                lastWrite[use.resource] = at;
            }
            if (reads(use.access))
                lastRead[use.resource] = at;
        }
    for (size_t k = 0; k < order.size(); ++k) {
        const PassDecl& pass = mPasses[order[k]];
        const auto at = static_cast<int>(k);
        for (const Use& use : pass.uses) {
            const ResourceId id = use.resource;
            // Built only for a message (the checks run every frame).
            const auto said = [&](const char* verb, const char* why) {
                return "FrameGraph: pass \"" + pass.name + "\" " + verb + " " +
                       std::string(mPool.name(id)) + ", which " + why;
            };
            const bool holds = mPool.isImported(id) || mPool.holdsContents(id) ||
                               (id < mMarks.size() && mMarks[id].boundOnly);
            if (reads(use.access) && !holds && !(firstWrite[id] >= 0 && firstWrite[id] < at)) {
                PENUMBRA_CHECK(lastWrite[id] <= at,
                               said("reads", "only a later pass writes (a cycle, or a pass in "
                                             "too early a phase)"));
                fatal(__FILE__, __LINE__, said("reads", "no earlier pass writes"));
            }
            PENUMBRA_CHECK(!writes(use.access) || outlivesFrame(id) || lastRead[id] > at,
                           said("writes", "no later pass reads"));
        }
    }
}

std::vector<ResourcePool::UseSpan> FrameGraph::useSpans(const std::vector<size_t>& order) const {
    // Shareable: per-frame (the pool checks), used by a kept pass, and never handed out of the
    // frame (a readback's copy, the caller's own passes after the present pass, an output) or
    // only bound. What leaves the frame must not be overwritten by a later occupant.
    std::vector<ResourcePool::UseSpan> spans(resourceCount());
    std::vector<bool> used(resourceCount(), false), handedOut(resourceCount(), false);
    for (size_t k = 0; k < order.size(); ++k) {
        const PassDecl& pass = mPasses[order[k]];
        for (const Use& use : pass.uses) {
            ResourcePool::UseSpan& span = spans[use.resource];
            if (!used[use.resource])
                span.first = k;
            used[use.resource] = true;
            span.last = k;
            if (pass.phase == Phase::Readback)
                handedOut[use.resource] = true;
        }
    }
    for (ResourceId id = 0; id < spans.size(); ++id) {
        const bool marked = id < mMarks.size() && (mMarks[id].output || mMarks[id].boundOnly);
        spans[id].shareable = used[id] && !handedOut[id] && !marked;
    }
    return spans;
}

FrameGraph::Marks& FrameGraph::mark(ResourceId id) {
    if (id >= mMarks.size())
        mMarks.resize(id + 1);
    return mMarks[id];
}

size_t FrameGraph::resourceCount() const {
    return mPool.idBound();
}

const std::vector<PlannedPass>& FrameGraph::plan() {
    if (mPlanned)
        return mPlan;
    mPlanned = true;
    clearStaleHistory();
    const std::vector<size_t> order = cull(dependencyOrder());
    mPool.realize(useSpans(order));
    checkReadsAndWrites(order);
    // Each resource's access as the plan leaves it, starting from the pool's (the last frame's).
    struct Track {
        std::optional<Access> last;
        bool touched = false; // used in this frame
    };
    std::vector<Track> track(resourceCount()); // sized once: references into it stay valid
    auto trackOf = [&](ResourceId id) -> Track& {
        PENUMBRA_CHECK(id < track.size(), "FrameGraph: a resource of another frame");
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
            const bool discard =
                firstThisFrame && !reads(use.access) && !mPool.persistent(use.resource);
            // Memory shared with other transients: the first use waits for their last ones
            // (this frame's earlier passes, or last frame's for those used later).
            std::vector<Access> after;
            if (firstThisFrame)
                for (const ResourceId other : mPool.sharesMemoryWith(use.resource))
                    if (const std::optional<Access> last = trackOf(other).last)
                        after.push_back(*last);
            if (!t.last) {
                // Never used: an image's layout must be set; a buffer (host-written, or about to
                // be written) needs nothing.
                if (image)
                    planned.barriers.push_back({.resource = use.resource,
                                                .from = use.access,
                                                .to = use.access,
                                                .fromUndefined = true,
                                                .after = std::move(after)});
            } else if (*t.last != use.access || writes(use.access) || writes(*t.last) ||
                       !after.empty()) {
                planned.barriers.push_back({.resource = use.resource,
                                            .from = *t.last,
                                            .to = use.access,
                                            .fromUndefined = image && discard,
                                            .after = std::move(after)});
            }
            t.last = use.access;
        }
        mPlan.push_back(std::move(planned));
    }
    return mPlan;
}

vk::ImageState imageSource(const PlannedBarrier& b) {
    vk::ImageState from = b.fromUndefined ? vk::kUndefined : imageState(b.from);
    for (const Access other : b.after) {
        const vk::ImageState was = imageState(other);
        from.stage |= was.stage;
        from.access |= was.access;
    }
    return from;
}

void FrameGraph::record(VkCommandBuffer cmd, vk::GpuTimer* timer) {
    plan();
    for (const PlannedPass& planned : mPlan) {
        const PassDecl& pass = mPasses[planned.pass];
        vk::Barriers barriers;
        for (const PlannedBarrier& b : planned.barriers) {
            if (mPool.isImage(b.resource)) {
                const vk::Image& image = mPool.image(b.resource).get();
                barriers.image(image, imageSource(b), imageState(b.to));
            } else {
                barriers.buffer(mPool.buffer(b.resource), bufferState(b.from), bufferState(b.to));
            }
        }
        barriers.record(cmd);
        const bool timed = timer && !pass.name.empty();
        if (timed)
            timer->begin(cmd, pass.name, *pass.cost);
        PassContext context{.cmd = cmd, .graph = *this};
        pushBindings(pass.bindings, context, mPool.context());
        pass.record(context);
        if (timed)
            timer->end(cmd);
        for (const Use& use : pass.uses) {
            mPool.setLastAccess(use.resource, use.access);
            // History: this frame's version, which the next frame's previous one will hold.
            if (writes(use.access) &&
                (mPool.persistent(use.resource) ||
                 (mPool.history(use.resource) && !mPool.isPrevious(use.resource))))
                mPool.setHoldsContents(use.resource);
        }
    }
}

} // namespace penumbra::render
