#pragma once
// The frame graph's resources (render/frame_graph.h), kept across frames. A resource is declared
// by kind (an image or a buffer), size class and lifetime; the pool keeps it while later frames
// declare it the same way, and when a frame has declared all it uses (realize) frees what it did
// not declare, then makes what is new: a render that changes technique never holds both sets of
// maps. Before it destroys anything it waits for the device (a frame in flight may still use
// it). It also remembers how each resource was last used, so that the next frame's barriers
// start from there.
#include "vk/resources.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace penumbra::render {

// What size classes resolve against.
struct FrameSizes {
    uint32_t width = 1, height = 1; // the camera's image
    uint32_t shadowMapSize = 1;     // texels a side of every shadow view
    uint32_t shadowViews = 0;       // shadow views of every light together
    uint32_t shadowLights = 0;      // lights with a shadow map (a visibility layer each)
};

// ShadowView: shadowMapSize^2, a layer per shadow view; Screen: width x height, one layer or a
// layer per shadow-casting light; Scene and Fixed: a size of their own (the scene's, or none).
enum class SizeClass { ShadowView, Screen, Scene, Fixed };
// PerFrame: its contents are rewritten every frame; Persistent: they survive across frames
// while the declaration's invalidation key stays the same; History: rewritten every frame, and
// last frame's version stays readable beside it (ResourcePool::previousOf) while the key, the
// size and the camera (invalidateHistory) stay the same. A history resource takes twice the
// memory: this frame's version and last frame's swap places when a frame declares it.
enum class Lifetime { PerFrame, Persistent, History };

struct ImageDecl {
    std::string name;
    SizeClass size;
    uint32_t shrink = 0; // ShadowView: shadowMapSize >> shrink a side (at least 1)
    VkFormat format;
    VkImageUsageFlags usage;
    bool perLight = false;          // Screen: a layer per shadow-casting light
    uint32_t width = 1, height = 1; // Scene and Fixed
    uint32_t depth = 1;             // Scene and Fixed: > 1, a 3D image
    uint32_t layers = 1;            // Scene and Fixed
    bool mipmapped = false;         // a full mip chain
    bool layerViews = false;        // a 2D view per layer (and per level when mipmapped)
    bool arrayView = true;          // the whole image as a 2D array (image2DArray, ...)
    Lifetime lifetime = Lifetime::PerFrame;
    uint64_t key = 0; // Persistent and History: what the contents depend on
    bool operator==(const ImageDecl&) const = default;
};

struct BufferDecl {
    std::string name;
    SizeClass size;
    VkDeviceSize bytes; // ShadowView: per view; Screen: per pixel; else in all
    VkBufferUsageFlags usage;
    vk::MemoryUse memory = vk::MemoryUse::DeviceLocal;
    Lifetime lifetime = Lifetime::PerFrame;
    uint64_t key = 0;
    bool operator==(const BufferDecl&) const = default;
};

// An image of the pool (or imported): the image with its whole view, and views of each layer
// (layers[l]) and of each layer's levels (levels[l * mipLevels + m]) when declared.
struct PooledImage {
    const vk::Image* image = nullptr;
    std::vector<vk::ImageViewHandle> layers, levels;
    const vk::Image& get() const { return *image; }
    VkImageView view() const { return image->view.get(); }
    VkImageView layer(uint32_t l) const { return layers[l].get(); }
    VkImageView level(uint32_t l, uint32_t mip) const {
        return levels[size_t{l} * image->mipLevels + mip].get();
    }
};

using ResourceId = uint32_t;

// How a pass uses a resource: the pipeline stage, access and (for images) layout it needs.
enum class Access {
    DepthAttachment,   // depth test and write
    ColorAttachment,   // colour write
    FragmentSampled,   // sampled in a fragment shader
    ComputeSampled,    // sampled in a compute shader
    ComputeWrite,      // a storage image or buffer written by a compute shader
    ComputeReadWrite,  // ... read and written
    TransferRead,      // copied from
    TransferWrite,     // copied to
    UniformRead,       // a uniform buffer read by any shader stage
    ComputeRead,       // a storage buffer or image read by a compute shader
    IndirectRead,      // indirect dispatch or draw arguments (and the rest of their buffer, read
                       // by the compute shaders they dispatch)
    HostRead,          // read by the host after the submission (a readback buffer)
    VertexRead,        // vertex attributes a draw reads (the vertex and positions buffers)
    VertexStorageRead, // a storage buffer read by a vertex shader (the previous positions)
};
bool writes(Access access);
bool reads(Access access); // what it finds (attachments are cleared on load: they do not)

class ResourcePool {
public:
    explicit ResourcePool(const vk::Context& ctx);
    const vk::Context& context() const { return mCtx; }
    ~ResourcePool();
    ResourcePool(const ResourcePool&) = delete;
    ResourcePool& operator=(const ResourcePool&) = delete;

    // A frame's declarations: each returns the resource's id for this frame (ids hold until
    // the next frame begins). A name declared twice in one frame must be declared the same way.
    void beginFrame();
    ResourceId acquire(const ImageDecl& decl, const FrameSizes& sizes);
    ResourceId acquire(const BufferDecl& decl, const FrameSizes& sizes);
    // An image the caller owns, in the state `current` (its barriers start from there).
    ResourceId importImage(std::string name, const vk::Image& image, Access current);
    ResourceId importBuffer(std::string name, VkBuffer buffer);
    // Frees the pool's resources this frame did not declare (after the device is idle), then
    // makes the ones it declared anew. Before it, the frame's images and buffers do not exist.
    // `spans[id]`: the passes of the frame's order that use resource `id`, first to last, and
    // whether the graph lets it share memory; per-frame images it lets share are placed so that
    // those whose passes do not overlap take the same bytes (render/frame_memory.h).
    struct UseSpan {
        size_t first = 0, last = 0;
        bool shareable = false; // used by a kept pass, and by no pass that hands it out
    };
    void realize(std::span<const UseSpan> spans = {});
    // Frees every per-frame resource and the memory transients share (after the device is
    // idle): the next frame makes them again. Persistent and history resources, which a later
    // frame reads, stay. Between frames only.
    void releasePerFrame();
    // The resources placed over some of the bytes of `id` this frame (transient images only):
    // their last uses come before its first in every frame.
    std::vector<ResourceId> sharesMemoryWith(ResourceId id) const;
    // What the transient images that share memory would take each in memory of its own, and
    // take together: the saving the frame's memory plan makes.
    struct TransientBytes {
        uint64_t separate = 0, shared = 0;
    };
    TransientBytes transientBytes() const { return mTransient; }
    // Whether an image must have memory of its own: by default what the driver says
    // (vk::requiresDedicatedMemory); a test stands in for a driver that asks it. Such a transient
    // is never placed in shared memory.
    std::function<bool(const vk::ImageDesc&)> needsOwnMemory;

    const PooledImage& image(ResourceId id) const;
    VkBuffer buffer(ResourceId id) const;
    std::string_view name(ResourceId id) const;
    bool isImage(ResourceId id) const;
    // An image's format as declared or imported (VK_FORMAT_UNDEFINED for a buffer).
    VkFormat formatOf(ResourceId id) const;
    bool isImported(ResourceId id) const;
    bool persistent(ResourceId id) const;
    // A history resource's versions: this frame's, and last frame's (previousOf; its name ends
    // in kPreviousSuffix), valid for the frame. previousOf is fatal for any other resource.
    bool history(ResourceId id) const;
    bool isPrevious(ResourceId id) const;
    ResourceId previousOf(ResourceId id) const;
    // The next frame's history holds nothing (a camera cut): every last frame's version is
    // cleared before it is read. A new size or key does the same for one resource. Called
    // during a frame, it applies to the next one, never to half of this one's declarations.
    void invalidateHistory() { mCutPending = true; }
    // A buffer the host maps (uploads, readbacks): what it holds outlives the submission.
    bool hostVisible(ResourceId id) const;
    // The last use's access (nullopt: not used since it was made, or its contents dropped).
    std::optional<Access> lastAccess(ResourceId id) const;
    void setLastAccess(ResourceId id, std::optional<Access> access);
    // Persistent resources: whether they hold what a producer wrote under their current key;
    // last frame's version of a history resource: whether it holds what last frame wrote.
    bool holdsContents(ResourceId id) const;
    void setHoldsContents(ResourceId id);
    // By name, after a frame (readback, the viewer): null when this frame did not declare it.
    const PooledImage* findImage(std::string_view name) const;
    VkBuffer findBuffer(std::string_view name) const;
    // A host-visible buffer's mapped memory, by name (null unless declared and mapped).
    void* mapped(std::string_view name) const;

    // What an image or buffer of this declaration takes in device memory (texel and mip sums,
    // both versions of a history; the device's own padding aside): what Renderer::check counts.
    static uint64_t bytesOf(const ImageDecl& decl, const FrameSizes& sizes);
    static uint64_t bytesOf(const BufferDecl& decl, const FrameSizes& sizes);
    // One past the largest id of this frame.
    size_t idBound() const { return mEntries.size(); }
    // Resources made (not kept) since the pool was created: what tests of the cache read.
    uint64_t creations() const { return mCreations; }

private:
    struct Entry;
    Entry& entry(ResourceId id) const;
    template <class Decl>
    void keep(Entry& e, const Decl& decl, uint64_t oldKey);
    template <class Decl>
    ResourceId acquireAs(const Decl& decl, const FrameSizes& sizes);
    template <class Decl>
    ResourceId acquireHistory(const Decl& decl, const FrameSizes& sizes);
    std::optional<Lifetime> lifetimeOf(ResourceId id) const;
    static vk::ImageDesc imageDesc(const Entry& e);
    void make(Entry& e);
    void makeViews(Entry& e);
    void placeTransients(std::span<const UseSpan> spans);
    void waitIdle();
    const vk::Context& mCtx;
    // The memory transient images share: freed after the images placed in it.
    std::vector<vk::MemoryHandle> mShared;
    std::vector<std::unique_ptr<Entry>> mEntries;
    // What the transients were placed for: each entry with its span; placed again on a change.
    std::vector<std::tuple<const Entry*, size_t, size_t>> mPlacedFor;
    TransientBytes mTransient;
    uint64_t mCreations = 0;
    uint64_t mFrame = 0;        // frames begun: a history swaps once in each
    bool mCutPending = false;   // invalidateHistory since the last beginFrame
    bool mCutThisFrame = false; // latched by beginFrame: this frame's history holds nothing
};

// What last frame's version of a history resource is called: its name and this.
inline constexpr std::string_view kPreviousSuffix = " (previous)";

} // namespace penumbra::render
