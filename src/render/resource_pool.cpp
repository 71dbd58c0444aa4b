#include "render/resource_pool.h"

#include "render/pool_entry.h"

#include "penumbra/error.h"
#include "vk/check.h"

#include <algorithm>
#include <utility>
#include <variant>

namespace penumbra::render {

namespace {

// The extent and layers a declaration resolves to.
struct Resolved {
    uint32_t width, height, depth, layers;
};

Resolved resolve(const ImageDecl& d, const FrameSizes& s) {
    switch (d.size) {
    case SizeClass::ShadowView:
        return {std::max(s.shadowMapSize >> d.shrink, 1u),
                std::max(s.shadowMapSize >> d.shrink, 1u), 1, std::max(s.shadowViews, 1u)};
    case SizeClass::Screen:
        return {s.width, s.height, 1, d.perLight ? std::max(s.shadowLights, 1u) : 1u};
    case SizeClass::Scene:
    case SizeClass::Fixed:
        break;
    }
    return {d.width, d.height, d.depth, d.layers};
}

uint32_t mipLevels(uint32_t size) {
    uint32_t levels = 1;
    while ((size >> levels) > 0)
        ++levels;
    return levels;
}

// Whether two declarations of the same shape, resolved against their frames' sizes, make
// resources of the same size.
bool sameExtent(const ImageDecl&, const ImageDecl& d, const FrameSizes& a, const FrameSizes& b) {
    const Resolved x = resolve(d, a), y = resolve(d, b);
    return x.width == y.width && x.height == y.height && x.depth == y.depth && x.layers == y.layers;
}

// The same resource but, perhaps, for its invalidation key.
template <class Decl>
bool sameShape(Decl a, const Decl& b) {
    a.key = b.key;
    return a == b;
}

VkDeviceSize bufferBytes(const BufferDecl& d, const FrameSizes& s) {
    switch (d.size) {
    case SizeClass::ShadowView:
        return d.bytes * std::max(s.shadowViews, 1u);
    case SizeClass::Screen:
        return d.bytes * s.width * s.height;
    case SizeClass::Scene:
    case SizeClass::Fixed:
        break;
    }
    return d.bytes;
}

bool sameExtent(const BufferDecl& old, const BufferDecl& d, const FrameSizes& a,
                const FrameSizes& b) {
    return bufferBytes(old, a) == bufferBytes(d, b);
}

} // namespace

ResourcePool::ResourcePool(const vk::Context& ctx)
    : needsOwnMemory(
          [&ctx](const vk::ImageDesc& desc) { return vk::requiresDedicatedMemory(ctx, desc); }),
      mCtx(ctx) {}

// Keeps entry `e` for this frame's `decl`: a persistent resource whose key changed no longer
// holds what was written under the old one.
template <class Decl>
void ResourcePool::keep(Entry& e, const Decl& decl, uint64_t oldKey) {
    PENUMBRA_CHECK(!e.declared || oldKey == decl.key,
                   "ResourcePool: " + decl.name + " declared twice with different keys");
    if (oldKey != decl.key)
        e.holds = false;
    e.decl = decl;
    e.declared = true;
}
ResourcePool::~ResourcePool() = default;

ResourcePool::Entry& ResourcePool::entry(ResourceId id) const {
    PENUMBRA_CHECK(id < mEntries.size() && mEntries[id],
                   "ResourcePool: not a resource of this frame");
    return *mEntries[id];
}

void ResourcePool::waitIdle() {
    VK_CHECK(vkDeviceWaitIdle(mCtx.device())); // a frame in flight may still use it
}

void ResourcePool::releasePerFrame() {
    waitIdle();
    for (auto& e : mEntries) {
        if (!e)
            continue;
        const auto* image = std::get_if<ImageDecl>(&e->decl);
        const auto* buffer = std::get_if<BufferDecl>(&e->decl);
        if ((image && image->lifetime == Lifetime::PerFrame) ||
            (buffer && buffer->lifetime == Lifetime::PerFrame))
            e.reset();
    }
    mPlacedFor.clear(); // placed anew with the next frame's transients
    mShared.clear();    // after the images placed in it
    mTransient = {};
}

void ResourcePool::beginFrame() {
    // Imports are the caller's, for one frame; ids are a frame's: the list closes up.
    std::erase_if(mEntries, [](const std::unique_ptr<Entry>& e) {
        return !e || std::holds_alternative<std::monostate>(e->decl);
    });
    for (auto& e : mEntries)
        e->declared = false;
    ++mFrame;
    // A cut asked for during the last frame applies to this one, whole.
    mCutThisFrame = std::exchange(mCutPending, false);
}

// The entry a declaration names, kept when it declares the same resource at the same size,
// else a new one (made by realize; the old one, renamed, is freed there as undeclared).
template <class Decl>
ResourceId ResourcePool::acquireAs(const Decl& decl, const FrameSizes& sizes) {
    for (ResourceId id = 0; id < mEntries.size(); ++id) {
        if (!mEntries[id] || mEntries[id]->name != decl.name)
            continue;
        Entry& e = *mEntries[id];
        const auto* old = std::get_if<Decl>(&e.decl);
        if (old && sameShape(*old, decl) && sameExtent(*old, decl, e.sizes, sizes)) {
            keep(e, decl, old->key);
            e.sizes = sizes;
            return id;
        }
        PENUMBRA_CHECK(!e.declared, "ResourcePool: " + decl.name + " declared twice differently");
        e.name.clear();
        break;
    }
    auto e = std::make_unique<Entry>();
    e->name = decl.name;
    e->decl = decl;
    e->sizes = sizes;
    e->declared = true;
    e->pending = true;
    mEntries.push_back(std::move(e));
    return static_cast<ResourceId>(mEntries.size() - 1);
}

// A history resource's two versions, both kept or both new. Kept, they swap: last frame's
// version becomes this frame's previous one, and it holds what last frame wrote when that frame
// wrote it under the same key (keep() clears `holds` for a new key) and no cut came between.
template <class Decl>
ResourceId ResourcePool::acquireHistory(const Decl& decl, const FrameSizes& sizes) {
    Decl last = decl;
    last.name += kPreviousSuffix;
    const ResourceId id = acquireAs(decl, sizes);
    const ResourceId previousId = acquireAs(last, sizes);
    Entry& current = *mEntries[id];
    Entry& previous = *mEntries[previousId];
    current.previous = previousId;
    previous.isPrevious = true;
    if (current.swappedIn == mFrame) // declared twice this frame: swapped once
        return id;
    current.swappedIn = mFrame;
    const bool kept = !current.pending && !previous.pending;
    if (kept) {
        std::swap(current.ownedImage, previous.ownedImage);
        std::swap(current.image.layers, previous.image.layers);
        std::swap(current.image.levels, previous.image.levels);
        std::swap(current.ownedBuffer, previous.ownedBuffer);
        std::swap(current.buffer, previous.buffer);
        std::swap(current.last, previous.last);
    }
    previous.holds = kept && current.holds && !mCutThisFrame;
    current.holds = false; // until this frame writes it
    return id;
}

ResourceId ResourcePool::acquire(const ImageDecl& decl, const FrameSizes& sizes) {
    return decl.lifetime == Lifetime::History ? acquireHistory(decl, sizes)
                                              : acquireAs(decl, sizes);
}

ResourceId ResourcePool::acquire(const BufferDecl& decl, const FrameSizes& sizes) {
    return decl.lifetime == Lifetime::History ? acquireHistory(decl, sizes)
                                              : acquireAs(decl, sizes);
}

vk::ImageDesc ResourcePool::imageDesc(const Entry& e) {
    const ImageDecl& decl = std::get<ImageDecl>(e.decl);
    const Resolved r = resolve(decl, e.sizes);
    return {.name = decl.size == SizeClass::ShadowView ? "--shadow-map-size" : decl.name,
            .format = decl.format,
            .width = r.width,
            .height = r.height,
            .layers = r.layers,
            // Last frame's version is cleared when it holds nothing (FrameGraph::plan).
            .usage = decl.usage | (decl.lifetime == Lifetime::History
                                       ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_DST_BIT}
                                       : VkImageUsageFlags{0}),
            .arrayView = decl.arrayView && r.depth == 1,
            .mipLevels = decl.mipmapped ? mipLevels(std::max(r.width, r.height)) : 1u,
            .depth = r.depth};
}

void ResourcePool::make(Entry& e) {
    e.ownedImage = vk::createImage(mCtx, imageDesc(e));
    makeViews(e);
}

void ResourcePool::makeViews(Entry& e) {
    const ImageDecl& decl = std::get<ImageDecl>(e.decl);
    e.image.image = &e.ownedImage;
    e.image.layers.clear();
    e.image.levels.clear();
    if (decl.layerViews) {
        const vk::Image& image = e.ownedImage;
        for (uint32_t l = 0; l < image.layers; ++l)
            e.image.layers.push_back(vk::createLayerView(mCtx, image, l));
        if (image.mipLevels > 1)
            for (uint32_t l = 0; l < image.layers; ++l)
                for (uint32_t m = 0; m < image.mipLevels; ++m)
                    e.image.levels.push_back(vk::createLayerView(mCtx, image, l, m));
    }
}

ResourceId ResourcePool::importImage(std::string name, const vk::Image& image, Access current) {
    auto e = std::make_unique<Entry>();
    e->name = std::move(name);
    e->image.image = &image;
    e->last = current;
    e->declared = true;
    mEntries.push_back(std::move(e));
    return static_cast<ResourceId>(mEntries.size() - 1);
}

ResourceId ResourcePool::importBuffer(std::string name, VkBuffer buffer) {
    auto e = std::make_unique<Entry>();
    e->name = std::move(name);
    e->buffer = buffer;
    e->declared = true;
    mEntries.push_back(std::move(e));
    return static_cast<ResourceId>(mEntries.size() - 1);
}

void ResourcePool::realize(std::span<const UseSpan> spans) {
    auto unused = [](const std::unique_ptr<Entry>& e) {
        return e && !e->declared && !std::holds_alternative<std::monostate>(e->decl);
    };
    if (std::any_of(mEntries.begin(), mEntries.end(), unused)) {
        waitIdle();
        for (auto& e : mEntries) // freed, their ids kept for the frame
            if (unused(e))
                e.reset();
    }
    placeTransients(spans);
    for (auto& e : mEntries) {
        if (!e || !e->pending)
            continue;
        if (std::holds_alternative<ImageDecl>(e->decl)) {
            make(*e);
        } else {
            const BufferDecl& decl = std::get<BufferDecl>(e->decl);
            const VkBufferUsageFlags clearable =
                decl.lifetime == Lifetime::History
                    ? VkBufferUsageFlags{VK_BUFFER_USAGE_TRANSFER_DST_BIT}
                    : VkBufferUsageFlags{0};
            e->ownedBuffer =
                vk::createBuffer(mCtx, std::max<VkDeviceSize>(bufferBytes(decl, e->sizes), 16),
                                 decl.usage | clearable, decl.memory, decl.name);
            e->buffer = e->ownedBuffer.get();
        }
        e->pending = false;
        ++mCreations;
    }
}

const PooledImage& ResourcePool::image(ResourceId id) const {
    const Entry& e = entry(id);
    PENUMBRA_CHECK(!e.pending, "ResourcePool: " + e.name + " used before realize");
    PENUMBRA_CHECK(e.image.image != nullptr, "ResourcePool: " + e.name + " is not an image");
    return e.image;
}

VkBuffer ResourcePool::buffer(ResourceId id) const {
    const Entry& e = entry(id);
    PENUMBRA_CHECK(!e.pending, "ResourcePool: " + e.name + " used before realize");
    PENUMBRA_CHECK(e.buffer != VK_NULL_HANDLE, "ResourcePool: " + e.name + " is not a buffer");
    return e.buffer;
}

std::string_view ResourcePool::name(ResourceId id) const {
    return entry(id).name;
}

bool ResourcePool::isImage(ResourceId id) const {
    const Entry& e = entry(id);
    return e.image.image != nullptr || std::holds_alternative<ImageDecl>(e.decl);
}

VkFormat ResourcePool::formatOf(ResourceId id) const {
    const Entry& e = entry(id);
    if (const auto* decl = std::get_if<ImageDecl>(&e.decl))
        return decl->format;
    // Imported, or a buffer (no image).
    return e.image.image ? e.image.image->format : VK_FORMAT_UNDEFINED;
}

bool ResourcePool::isImported(ResourceId id) const {
    return std::holds_alternative<std::monostate>(entry(id).decl);
}

// A declared resource's lifetime; none for an imported one.
std::optional<Lifetime> ResourcePool::lifetimeOf(ResourceId id) const {
    const Entry& e = entry(id);
    if (const auto* i = std::get_if<ImageDecl>(&e.decl))
        return i->lifetime;
    if (const auto* b = std::get_if<BufferDecl>(&e.decl))
        return b->lifetime;
    return std::nullopt;
}

bool ResourcePool::persistent(ResourceId id) const {
    const std::optional<Lifetime> lifetime = lifetimeOf(id);
    return !lifetime || *lifetime == Lifetime::Persistent; // imported: the caller's contents
}

bool ResourcePool::history(ResourceId id) const {
    return lifetimeOf(id) == Lifetime::History;
}

bool ResourcePool::isPrevious(ResourceId id) const {
    return entry(id).isPrevious;
}

ResourceId ResourcePool::previousOf(ResourceId id) const {
    const Entry& e = entry(id);
    PENUMBRA_CHECK(history(id) && !e.isPrevious,
                   "ResourcePool: " + e.name + " is not declared with history");
    return e.previous;
}

bool ResourcePool::hostVisible(ResourceId id) const {
    const auto* b = std::get_if<BufferDecl>(&entry(id).decl);
    return b != nullptr && b->memory != vk::MemoryUse::DeviceLocal;
}

std::optional<Access> ResourcePool::lastAccess(ResourceId id) const {
    return entry(id).last;
}

void ResourcePool::setLastAccess(ResourceId id, std::optional<Access> access) {
    entry(id).last = access;
}

bool ResourcePool::holdsContents(ResourceId id) const {
    return entry(id).holds;
}

void ResourcePool::setHoldsContents(ResourceId id) {
    entry(id).holds = true;
}

const PooledImage* ResourcePool::findImage(std::string_view name) const {
    for (const auto& e : mEntries)
        if (e && e->declared && e->name == name && e->image.image)
            return &e->image;
    return nullptr;
}

VkBuffer ResourcePool::findBuffer(std::string_view name) const {
    for (const auto& e : mEntries)
        if (e && e->declared && e->name == name && e->buffer)
            return e->buffer;
    return VK_NULL_HANDLE;
}

void* ResourcePool::mapped(std::string_view name) const {
    for (const auto& e : mEntries)
        if (e && e->declared && e->name == name)
            return e->ownedBuffer.mapped;
    return nullptr;
}

uint64_t ResourcePool::bytesOf(const ImageDecl& decl, const FrameSizes& sizes) {
    const Resolved r = resolve(decl, sizes);
    uint64_t texels = 0;
    const uint32_t levels = decl.mipmapped ? mipLevels(std::max(r.width, r.height)) : 1u;
    for (uint32_t m = 0; m < levels; ++m)
        texels += uint64_t{std::max(r.width >> m, 1u)} * std::max(r.height >> m, 1u) * r.depth;
    const uint64_t versions = decl.lifetime == Lifetime::History ? 2 : 1;
    return texels * r.layers * vk::formatBytes(decl.format) * versions;
}

uint64_t ResourcePool::bytesOf(const BufferDecl& decl, const FrameSizes& sizes) {
    return bufferBytes(decl, sizes) * (decl.lifetime == Lifetime::History ? 2 : 1);
}

} // namespace penumbra::render
