#pragma once
// Memory that a frame's transient images share (docs/architecture.md, "Transient memory"): two
// images whose passes do not overlap may take the same bytes. The plan places each image at an
// offset in a block of device memory so that images placed over the same bytes are never used
// by the same pass or by passes between each other's first and last.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <span>
#include <vector>

namespace penumbra::render {

// One transient image of a frame: the planned passes that use it, first to last (indices into
// the frame's order, both included), and what the device asks of its memory.
struct TransientNeed {
    size_t first = 0, last = 0;
    VkDeviceSize size = 0, alignment = 1;
    uint32_t memoryTypeBits = ~0u;
};

struct AliasPlan {
    struct Placement {
        size_t block = 0;
        VkDeviceSize offset = 0;
    };
    struct Block {
        VkDeviceSize size = 0;
        uint32_t memoryTypeBits = ~0u; // every need placed in it can live in these types
    };
    std::vector<Placement> placements; // one per need, in the needs' order
    std::vector<Block> blocks;
    VkDeviceSize separateBytes = 0; // the needs' sizes summed: the memory without sharing
    VkDeviceSize sharedBytes() const;
};

// Larger images first, each at the lowest offset of the block it grows least (a new block when
// no block's memory types suit it, or none has room under `maxBlockBytes`, the device's largest
// allocation: an image larger than that gets a block of its own); a block grows at most by an
// image and its alignment. A block that would save nothing is split into one block per image, so
// the total is never more than the separate one.
AliasPlan planAliasing(std::span<const TransientNeed> needs,
                       VkDeviceSize maxBlockBytes = ~VkDeviceSize{0});

// Whether needs a and b of `plan` take some of the same bytes (then their passes are disjoint).
bool sharesBytes(const AliasPlan& plan, std::span<const TransientNeed> needs, size_t a, size_t b);

} // namespace penumbra::render
