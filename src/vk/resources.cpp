#include "vk/resources.h"

#include "core/fault_injection.h"
#include "penumbra/error.h"
#include "vk/check.h"

#include <fmt/format.h>

#include <cstring>
#include <mutex>
#include <unordered_map>

namespace penumbra::vk {
namespace {

struct LiveAllocations {
    std::mutex mutex;
    std::unordered_map<VkDeviceMemory, VkDeviceSize> sizes;
};

LiveAllocations& liveAllocations() {
    static LiveAllocations live;
    return live;
}

// `dedicatedTo`: the image the memory is for alone (VkMemoryDedicatedAllocateInfo), or none.
MemoryHandle allocate(const Context& ctx, const VkMemoryRequirements& req, MemoryUse use,
                      const std::string& name, VkImage dedicatedTo = VK_NULL_HANDLE) {
    VkMemoryPropertyFlags required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, preferred = 0;
    if (use == MemoryUse::Upload)
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (use == MemoryUse::Readback) {
        required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    }
    const VkMemoryDedicatedAllocateInfo dedicated{
        .sType = VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO, .image = dedicatedTo};
    const VkMemoryAllocateInfo info{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                    .pNext = dedicatedTo != VK_NULL_HANDLE ? &dedicated : nullptr,
                                    .allocationSize = req.size,
                                    .memoryTypeIndex =
                                        ctx.memoryType(req.memoryTypeBits, required, preferred)};
    VkDeviceMemory memory = VK_NULL_HANDLE;
    const VkResult result = injectFault(FaultSite::Allocation)
                                ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                                : vkAllocateMemory(ctx.device(), &info, nullptr, &memory);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw InputError(name, fmt::format("out of memory allocating {:.1f} MiB ({})",
                                           static_cast<double>(req.size) / (1 << 20),
                                           resultName(result)));
    VK_CHECK(result);
    {
        LiveAllocations& live = liveAllocations();
        const std::lock_guard lock(live.mutex);
        live.sizes[memory] = req.size;
    }
    return MemoryHandle(ctx.device(), memory);
}

VkImageAspectFlags aspectOf(VkFormat format) {
    return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM
               ? VK_IMAGE_ASPECT_DEPTH_BIT
               : VK_IMAGE_ASPECT_COLOR_BIT;
}

ImageViewHandle createView(const Context& ctx, const Image& image, VkImageViewType type,
                           uint32_t baseLayer, uint32_t layerCount, uint32_t baseMip,
                           uint32_t mipCount, VkFormat format = VK_FORMAT_UNDEFINED) {
    const VkImageViewCreateInfo info{.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                     .image = image.get(),
                                     .viewType = type,
                                     .format =
                                         format != VK_FORMAT_UNDEFINED ? format : image.format,
                                     .subresourceRange = {.aspectMask = image.aspect,
                                                          .baseMipLevel = baseMip,
                                                          .levelCount = mipCount,
                                                          .baseArrayLayer = baseLayer,
                                                          .layerCount = layerCount}};
    VkImageView view = VK_NULL_HANDLE;
    VK_CREATE(vkCreateImageView(ctx.device(), &info, nullptr, &view));
    return ImageViewHandle(ctx.device(), view);
}

} // namespace

void freeTrackedMemory(VkDevice device, VkDeviceMemory memory,
                       const VkAllocationCallbacks* callbacks) {
    {
        LiveAllocations& live = liveAllocations();
        const std::lock_guard lock(live.mutex);
        live.sizes.erase(memory);
    }
    vkFreeMemory(device, memory, callbacks);
}

LiveDeviceMemory liveDeviceMemory() {
    LiveAllocations& live = liveAllocations();
    const std::lock_guard lock(live.mutex);
    LiveDeviceMemory use{.allocations = live.sizes.size()};
    for (const auto& [memory, size] : live.sizes)
        use.bytes += size;
    return use;
}

size_t formatBytes(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_D32_SFLOAT:
        return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_UNORM:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT:
        return 16;
    default:
        fatal(__FILE__, __LINE__, fmt::format("formatBytes: unhandled format {}", int(format)));
    }
}

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
                    const std::string& name) {
    PENUMBRA_CHECK(size > 0, "empty buffer " + name);
    const VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                  .size = size,
                                  .usage = usage,
                                  .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    VkBuffer raw = VK_NULL_HANDLE;
    VK_CREATE(vkCreateBuffer(ctx.device(), &info, nullptr, &raw));
    Buffer buffer{.buffer = BufferHandle(ctx.device(), raw), .size = size};
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(ctx.device(), raw, &req);
    buffer.memory = allocate(ctx, req, use, name);
    VK_CHECK(vkBindBufferMemory(ctx.device(), raw, buffer.memory.get(), 0));
    if (use != MemoryUse::DeviceLocal)
        VK_CHECK(
            vkMapMemory(ctx.device(), buffer.memory.get(), 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
    return buffer;
}

namespace {
VkImageCreateInfo imageCreateInfo(const ImageDesc& desc) {
    VkImageCreateFlags flags = 0;
    if (desc.cube)
        flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    if (desc.alsoViewedAs != VK_FORMAT_UNDEFINED)
        flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    return {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
            .flags = flags,
            .imageType = desc.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D,
            .format = desc.format,
            .extent = {desc.width, desc.height, desc.depth},
            .mipLevels = desc.mipLevels,
            .arrayLayers = desc.layers,
            .samples = VK_SAMPLE_COUNT_1_BIT,
            .tiling = VK_IMAGE_TILING_OPTIMAL,
            .usage = desc.usage,
            .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
}
} // namespace

bool requiresDedicatedMemory(const Context& ctx, const ImageDesc& desc) {
    const VkImageCreateInfo info = imageCreateInfo(desc);
    const VkDeviceImageMemoryRequirements query{
        .sType = VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS, .pCreateInfo = &info};
    VkMemoryDedicatedRequirements dedicated{.sType =
                                                VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
    VkMemoryRequirements2 needs{.sType = VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2,
                                .pNext = &dedicated};
    vkGetDeviceImageMemoryRequirements(ctx.device(), &query, &needs);
    return dedicated.requiresDedicatedAllocation == VK_TRUE;
}

Image createUnboundImage(const Context& ctx, const ImageDesc& desc, VkMemoryRequirements& needs,
                         bool* wantsDedicated) {
    // lavapipe creates images past maxImageDimension2D without complaint: check here.
    const uint32_t limit =
        desc.depth > 1 ? ctx.limits().maxImageDimension3D : ctx.limits().maxImageDimension2D;
    if (desc.width == 0 || desc.height == 0 || desc.width > limit || desc.height > limit ||
        desc.depth > limit)
        throw InputError(desc.name,
                         desc.depth > 1
                             ? fmt::format("{}x{}x{} is outside this device's 3D image size "
                                           "range 1..{}",
                                           desc.width, desc.height, desc.depth, limit)
                             : fmt::format("{}x{} is outside this device's image size range 1..{}",
                                           desc.width, desc.height, limit));
    PENUMBRA_CHECK(desc.depth == 1 || (desc.layers == 1 && !desc.cube), "3D images have one layer");
    PENUMBRA_CHECK(!desc.cube || (desc.layers % 6 == 0 && desc.width == desc.height),
                   "cube images have square faces, six layers per cube");
    Image image{.format = desc.format,
                .width = desc.width,
                .height = desc.height,
                .depth = desc.depth,
                .layers = desc.layers,
                .mipLevels = desc.mipLevels,
                .aspect = aspectOf(desc.format)};
    const VkImageCreateInfo info = imageCreateInfo(desc);
    VkImage raw = VK_NULL_HANDLE;
    VK_CREATE(vkCreateImage(ctx.device(), &info, nullptr, &raw));
    image.image = ImageHandle(ctx.device(), raw);
    const VkImageMemoryRequirementsInfo2 query{
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_REQUIREMENTS_INFO_2, .image = raw};
    VkMemoryDedicatedRequirements dedicated{.sType =
                                                VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
    VkMemoryRequirements2 asks{.sType = VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2,
                               .pNext = &dedicated};
    vkGetImageMemoryRequirements2(ctx.device(), &query, &asks);
    needs = asks.memoryRequirements;
    if (wantsDedicated)
        *wantsDedicated = dedicated.requiresDedicatedAllocation == VK_TRUE ||
                          dedicated.prefersDedicatedAllocation == VK_TRUE;
    return image;
}

void bindImage(const Context& ctx, Image& image, const ImageDesc& desc, VkDeviceMemory memory,
               VkDeviceSize offset) {
    VK_CHECK(vkBindImageMemory(ctx.device(), image.get(), memory, offset));
    const VkImageViewType viewType =
        desc.depth > 1 ? VK_IMAGE_VIEW_TYPE_3D
        : desc.cube    ? (desc.layers == 6 && !desc.arrayView ? VK_IMAGE_VIEW_TYPE_CUBE
                                                              : VK_IMAGE_VIEW_TYPE_CUBE_ARRAY)
        : desc.layers > 1 || desc.arrayView ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                            : VK_IMAGE_VIEW_TYPE_2D;
    image.view = createView(ctx, image, viewType, 0, desc.layers, 0, image.mipLevels);
}

Image createImage(const Context& ctx, const ImageDesc& desc) {
    VkMemoryRequirements needs{};
    bool dedicated = false; // the driver requires or prefers memory for this image alone
    Image image = createUnboundImage(ctx, desc, needs, &dedicated);
    image.memory = allocate(ctx, needs, MemoryUse::DeviceLocal, desc.name,
                            dedicated ? image.get() : VK_NULL_HANDLE);
    bindImage(ctx, image, desc, image.memory.get(), 0);
    return image;
}

MemoryHandle allocateDeviceLocal(const Context& ctx, const VkMemoryRequirements& needs,
                                 const std::string& name) {
    return allocate(ctx, needs, MemoryUse::DeviceLocal, name);
}

ImageViewHandle createFormatView(const Context& ctx, const Image& image, VkFormat format) {
    PENUMBRA_CHECK(image.layers == 1 && image.depth == 1, "a format view of a 2D image only");
    return createView(ctx, image, VK_IMAGE_VIEW_TYPE_2D, 0, 1, 0, image.mipLevels, format);
}

ImageViewHandle createLayerView(const Context& ctx, const Image& image, uint32_t layer,
                                uint32_t level) {
    PENUMBRA_CHECK(layer < image.layers, "layer out of range");
    PENUMBRA_CHECK(level < image.mipLevels, "mip level out of range");
    return createView(ctx, image, VK_IMAGE_VIEW_TYPE_2D, layer, 1, level, 1);
}

SamplerHandle createSampler(const Context& ctx, const SamplerDesc& desc) {
    const float limit = ctx.info().maxSamplerAnisotropy;
    const bool anisotropic = desc.anisotropy > 1.0f && limit > 1.0f;
    const VkSamplerCreateInfo info{.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                                   .magFilter = desc.magFilter,
                                   .minFilter = desc.minFilter,
                                   .mipmapMode = desc.mipmapMode,
                                   .addressModeU = desc.addressU,
                                   .addressModeV = desc.addressV,
                                   .addressModeW = desc.addressW,
                                   .anisotropyEnable = anisotropic ? VK_TRUE : VK_FALSE,
                                   .maxAnisotropy =
                                       anisotropic ? std::min(desc.anisotropy, limit) : 1.0f,
                                   .compareEnable = desc.compare ? VK_TRUE : VK_FALSE,
                                   .compareOp = VK_COMPARE_OP_LESS_OR_EQUAL,
                                   .maxLod = desc.maxLod,
                                   .borderColor = desc.border};
    VkSampler sampler = VK_NULL_HANDLE;
    VK_CREATE(vkCreateSampler(ctx.device(), &info, nullptr, &sampler));
    return SamplerHandle(ctx.device(), sampler);
}

Buffer uploadBuffer(const Context& ctx, std::span<const std::byte> bytes, VkBufferUsageFlags usage,
                    const std::string& name) {
    Buffer staging = createBuffer(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  MemoryUse::Upload, name + " (staging)");
    std::memcpy(staging.mapped, bytes.data(), bytes.size());
    Buffer buffer = createBuffer(ctx, bytes.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                 MemoryUse::DeviceLocal, name);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy region{.size = bytes.size()};
        vkCmdCopyBuffer(cmd, staging.get(), buffer.get(), 1, &region);
    });
    return buffer;
}

} // namespace penumbra::vk
