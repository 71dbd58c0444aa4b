#pragma once
// What the resource pool keeps of each resource (render/resource_pool.h): private to the pool's
// own files (resource_pool.cpp, pool_aliasing.cpp).
#include "render/resource_pool.h"

#include <optional>
#include <variant>
#include <vector>

namespace penumbra::render {

struct ResourcePool::Entry {
    std::string name;
    bool pending = false;                                     // declared, not made yet (realize)
    std::variant<std::monostate, ImageDecl, BufferDecl> decl; // monostate: imported
    FrameSizes sizes;     // what the declaration resolved against
    vk::Image ownedImage; // the pool's
    vk::Buffer ownedBuffer;
    PooledImage image; // points at ownedImage, or at the imported image
    VkBuffer buffer = VK_NULL_HANDLE;
    std::optional<Access> last;
    bool holds = false;    // persistent: written under the current key; history: see swap
    bool declared = false; // in this frame
    // History: this frame's version knows last frame's (ids hold for a frame) and the frame in
    // which the two last swapped.
    ResourceId previous = 0;
    bool isPrevious = false;
    uint64_t swappedIn = 0;
    // A transient image placed in memory it may share (pool_aliasing.cpp), and the entries
    // placed over some of the same bytes.
    bool aliased = false;
    std::vector<const Entry*> sharesWith;
    // Whether the driver wants the image in memory of its own (needsOwnMemory), once asked.
    std::optional<bool> ownMemory;
};

} // namespace penumbra::render
