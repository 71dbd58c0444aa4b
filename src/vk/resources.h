#pragma once
// Buffers, images and samplers with their memory. Each resource gets its own dedicated
// allocation: Penumbra holds a few dozen large resources per frame, where sub-allocation buys
// nothing. Allocation failures caused by the requested sizes are user errors (InputError).
#include "vk/context.h"
#include "vk/handles.h"

#include <cstdint>
#include <span>
#include <string>

namespace penumbra::vk {

enum class MemoryUse { DeviceLocal, Upload, Readback };

struct Buffer {
    BufferHandle buffer;
    MemoryHandle memory;
    void* mapped = nullptr; // host-visible buffers stay mapped
    VkDeviceSize size = 0;
    VkBuffer get() const { return buffer.get(); }
};

struct ImageDesc {
    std::string name; // for error messages
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0, layers = 1;
    VkImageUsageFlags usage = 0;
    bool arrayView = false; // a 2D-array view even for one layer (image2DArray in shaders)
    uint32_t mipLevels = 1; // the view covers them all
    uint32_t depth = 1;     // > 1: a 3D image (one layer) with a 3D view (a distance field)
    bool cube = false;      // layers a multiple of 6: a cube (6) or cube-array view, faces in
                            // Vulkan's order +x, -x, +y, -y, +z, -z
    // A compatible format a second view may read it in (createFormatView; the image is made
    // with VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT). UNDEFINED: none.
    VkFormat alsoViewedAs = VK_FORMAT_UNDEFINED;
};

struct Image {
    ImageHandle image;
    MemoryHandle memory;
    ImageViewHandle view; // 2D, or 2D array for several layers or ImageDesc::arrayView
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0, depth = 1, layers = 1, mipLevels = 1;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    VkImage get() const { return image.get(); }
    explicit operator bool() const { return static_cast<bool>(image); }
};

// Every device memory allocation Penumbra holds now, in this process (all devices): how a soak
// test sees a leak.
struct LiveDeviceMemory {
    uint64_t allocations = 0, bytes = 0;
};
LiveDeviceMemory liveDeviceMemory();

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
                    const std::string& name);
Image createImage(const Context& ctx, const ImageDesc& desc);
// An image in memory the caller holds (images that share memory, render/frame_memory.h): made
// without memory (`needs`: what it asks of it), then bound at `offset` in `memory` with its view.
// `wantsDedicated` (optional): whether the driver requires or prefers memory for it alone
// (VkMemoryDedicatedRequirements); createImage then allocates it so.
Image createUnboundImage(const Context& ctx, const ImageDesc& desc, VkMemoryRequirements& needs,
                         bool* wantsDedicated = nullptr);
// Whether the driver requires memory of its own for an image of this description
// (requiresDedicatedAllocation), asked without making it (vkGetDeviceImageMemoryRequirements):
// such an image never shares memory with others.
bool requiresDedicatedMemory(const Context& ctx, const ImageDesc& desc);
void bindImage(const Context& ctx, Image& image, const ImageDesc& desc, VkDeviceMemory memory,
               VkDeviceSize offset);
MemoryHandle allocateDeviceLocal(const Context& ctx, const VkMemoryRequirements& needs,
                                 const std::string& name);
// A view of a one-layer 2D image, every mip level, in `format`: ImageDesc::alsoViewedAs (an sRGB
// texture's bytes read as they are, UNORM).
ImageViewHandle createFormatView(const Context& ctx, const Image& image, VkFormat format);
// A view of one mip level of one layer of an array image (for rendering into it, writing it as
// a storage image or sampling it as 2D).
ImageViewHandle createLayerView(const Context& ctx, const Image& image, uint32_t layer,
                                uint32_t level = 0);

// A sampler, whole: filters, mips, anisotropy, addressing in three dimensions, comparison.
struct SamplerDesc {
    VkFilter magFilter = VK_FILTER_NEAREST, minFilter = VK_FILTER_NEAREST;
    VkSamplerMipmapMode mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    float maxLod = 0.0f;     // VK_LOD_CLAMP_NONE: every mip level
    float anisotropy = 0.0f; // > 1: anisotropic filtering, clamped to the device's limit (none
                             // where the device has no anisotropic filtering)
    VkSamplerAddressMode addressU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSamplerAddressMode addressV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSamplerAddressMode addressW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    bool compare = false; // depth comparison (sampler2DShadow), VK_COMPARE_OP_LESS_OR_EQUAL
    VkBorderColor border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
};
SamplerHandle createSampler(const Context& ctx, const SamplerDesc& desc);

// Copies `bytes` into a device-local buffer through a staging buffer (blocking).
Buffer uploadBuffer(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                    const std::string& name);

size_t formatBytes(VkFormat format);

} // namespace penumbra::vk
