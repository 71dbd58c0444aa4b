#pragma once
// The frame as a small render graph (after Granite's render graph [Arntzen 2017], much smaller:
// one queue, one renderer). Passes declare their phase and the resources they read and write;
// the graph orders them and places every barrier. Resources are declared by kind (image or
// buffer), size class and lifetime and live in a ResourcePool that outlasts the frame: a
// per-frame resource is kept while its declaration stays the same (its contents are not), a
// persistent one keeps its contents too while its invalidation key does (what a cache needs).
//
// Order: by phase; within a phase, by what the passes read and write, whatever order they were
// added in (ties keep the declaration order). Per resource, in declaration order: a write comes
// after the write declared before it and after the reads of what that one wrote; a read comes
// after the write declared before it, or, declared before any write of its phase, after the
// first write (it reads what this frame writes). Passes of one phase that read what each other
// write are a cycle (fatal); a read of what only a later phase writes is fatal too (plan()).
// Phases run in this order:
//   Geometry     what places the scene's vertices before anything draws them (skinning)
//   LightSpace   shadow maps and what is filtered from them (before the G-buffer)
//   GBuffer      the camera's G-buffer
//   ScreenSpace  passes after the G-buffer that per-light evaluation reads (and, for a cache
//                such as virtual shadow maps, light-space work they decide)
//   PerLight     each light's evaluation: its base technique, then its layers
//   Composite    shading from every light's visibility
//   Readback     copies for the host (not timed)
// History: a resource declared with Lifetime::History has last frame's version beside this
// frame's (previous()); this frame's outlives the frame (the next one reads it), and last
// frame's is cleared before it is read when it holds nothing.
// Culling: a pass is recorded only when its work reaches something that outlives the frame (a
// persistent, imported or host-visible resource, a host read) through reads of what it writes;
// the rest are culled (a screen pass whose only reader the options turned off). Its reads and
// writes are checked every frame (plan()).
// Barriers: before each pass, every resource it uses goes from the state its last use left it in
// (kept in the pool across frames and submissions) to the one this use needs; two reads in the
// same state need none. A per-frame resource's first use in a frame that only writes it starts
// from "undefined" (its old contents are not kept).
#include "render/pass_bindings.h"
#include "render/resource_pool.h"
#include "vk/sync.h"
#include "vk/timestamps.h"

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::render {

enum class Phase { Geometry, LightSpace, GBuffer, ScreenSpace, PerLight, Composite, Readback };
std::string_view phaseName(Phase phase);

struct Use {
    ResourceId resource;
    Access access;
};

class FrameGraph;

// What a pass records with: the command buffer, and its resources by id.
struct PassContext {
    VkCommandBuffer cmd;
    FrameGraph& graph;
    const PooledImage& image(ResourceId id) const;
    VkBuffer buffer(ResourceId id) const;
};

struct PassDecl {
    std::string name; // its GPU timestamp scope (passes with one name add up); "" untimed
    // What its time counts towards: declared by every timed pass and by no untimed one (the
    // plan checks), the same for every pass of one name (the timer checks).
    std::optional<CostGroup> cost;
    Phase phase;
    std::vector<Use> uses; // besides those its bindings make
    // Its descriptors, declared once (render/pass_bindings.h): the graph adds the uses they make
    // and pushes them before `record` runs, which then binds its pipeline and dispatches or draws.
    PassBindings bindings = {};
    std::function<void(PassContext&)> record;
};

// A pass as the graph will record it: its barriers first (resource, from, to).
struct PlannedBarrier {
    ResourceId resource;
    Access from; // meaningful when !fromUndefined and the resource was used before
    Access to;
    bool fromUndefined;
    // A transient's first use in a frame: the last uses of the resources whose memory it
    // shares, which it waits for as well.
    std::vector<Access> after = {};
};
// What an image barrier waits for: the resource's own last use (none when its contents are
// dropped: the layout is then undefined) and the last uses of those whose memory it shares.
vk::ImageState imageSource(const PlannedBarrier& b);

struct PlannedPass {
    size_t pass; // index into the declared passes
    std::vector<PlannedBarrier> barriers;
};

class FrameGraph {
public:
    FrameGraph(ResourcePool& pool, const FrameSizes& sizes);

    // Resources: declared to the pool for this frame (made, or kept, when the frame is planned:
    // their images and buffers exist from then on); `import` names one the caller owns.
    ResourceId declare(const ImageDecl& decl);
    ResourceId declare(const BufferDecl& decl);
    ResourceId importImage(std::string name, const vk::Image& image, Access current);
    ResourceId importBuffer(std::string name, VkBuffer buffer);
    // Whether a persistent resource holds what its producer wrote under the same key (a producer
    // may skip its pass then).
    bool holdsContents(ResourceId id) const;
    // A resource declared with Lifetime::History: last frame's version, which passes read (never
    // write), and whether it holds what last frame wrote. When it does not (the first frame, a
    // new size or key, a cut: ResourcePool::invalidateHistory, or a frame that did not write
    // it), the graph clears it to zeros before its first reader, so a pass may read it either
    // way; one that blends with it should weigh it by historyValid.
    ResourceId previous(ResourceId id) const;
    bool historyValid(ResourceId id) const;

    void addPass(PassDecl pass);
    // A frame's result (its colour, its visibility): read after the frame whether or not a pass
    // reads it (a benchmark's frame has no readback), so what writes it is never culled.
    void markOutput(ResourceId id);
    // A stand-in: bound because a descriptor must hold something, and read by passes whose
    // shader may not touch it (a placeholder, the viewer's intermediates when no layer ran), so
    // a read of it needs no writer.
    void markBoundOnly(ResourceId id);

    // The order and barriers the frame will have (the tests read it), without the culled passes.
    // Fatal, every frame: a pass that reads what no earlier pass of this frame wrote (a
    // persistent resource whose key kept its contents, and an imported one, excepted), or what
    // only a later one writes (a cycle); a write of a per-frame resource no later pass reads.
    const std::vector<PlannedPass>& plan();
    // Passes plan() left out: nothing kept reads what they write, and their work does not
    // leave the frame (no write to a persistent, imported, host-visible or output resource).
    // In plan order.
    const std::vector<size_t>& culled() const { return mCulled; }
    // Records every pass in plan order, each timed under its name by `timer` (if any). The pool
    // then knows the state each resource was left in, and that persistent ones hold contents.
    void record(VkCommandBuffer cmd, vk::GpuTimer* timer);

    const PooledImage& image(ResourceId id) const;
    VkBuffer buffer(ResourceId id) const;
    const std::vector<PassDecl>& passes() const { return mPasses; }
    const FrameSizes& sizes() const { return mSizes; }

private:
    std::vector<size_t> dependencyOrder() const; // frame_order.cpp
    void clearStaleHistory();
    std::vector<size_t> cull(const std::vector<size_t>& order);
    void checkReadsAndWrites(const std::vector<size_t>& order) const;
    bool outlivesFrame(ResourceId id) const;
    std::vector<ResourcePool::UseSpan> useSpans(const std::vector<size_t>& order) const;
    size_t resourceCount() const; // every id of this frame is below it
    // What markOutput and markBoundOnly said of a resource, by id.
    struct Marks {
        bool output = false, boundOnly = false;
    };
    Marks& mark(ResourceId id);

    ResourcePool& mPool;
    FrameSizes mSizes;
    std::vector<PassDecl> mPasses;
    std::vector<PlannedPass> mPlan;
    std::vector<size_t> mCulled;
    std::vector<Marks> mMarks;
    bool mPlanned = false;
};

} // namespace penumbra::render
