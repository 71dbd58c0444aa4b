#pragma once
// Move-only owners for Vulkan handles created from a VkDevice. One template instead of a
// hand-written destroy list: each alias names the vkDestroy* function that releases it.
#include <vulkan/vulkan.h>

#include <utility>

namespace penumbra::vk {

// vkFreeMemory, and the allocation leaves the count of live device memory (resources.cpp).
void freeTrackedMemory(VkDevice device, VkDeviceMemory memory,
                       const VkAllocationCallbacks* callbacks);

template <typename T, auto Destroy>
class DeviceHandle {
public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, T handle) : mDevice(device), mHandle(handle) {}
    DeviceHandle(DeviceHandle&& other) noexcept
        : mDevice(other.mDevice), mHandle(std::exchange(other.mHandle, VK_NULL_HANDLE)) {}
    DeviceHandle& operator=(DeviceHandle&& other) noexcept {
        if (this != &other) {
            reset();
            mDevice = other.mDevice;
            mHandle = std::exchange(other.mHandle, VK_NULL_HANDLE);
        }
        return *this;
    }
    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    ~DeviceHandle() { reset(); }

    T get() const { return mHandle; }
    explicit operator bool() const { return mHandle != VK_NULL_HANDLE; }
    void reset() {
        if (mHandle != VK_NULL_HANDLE)
            Destroy(mDevice, std::exchange(mHandle, VK_NULL_HANDLE), nullptr);
    }

private:
    VkDevice mDevice = VK_NULL_HANDLE;
    T mHandle = VK_NULL_HANDLE;
};

using BufferHandle = DeviceHandle<VkBuffer, vkDestroyBuffer>;
using ImageHandle = DeviceHandle<VkImage, vkDestroyImage>;
using ImageViewHandle = DeviceHandle<VkImageView, vkDestroyImageView>;
using MemoryHandle = DeviceHandle<VkDeviceMemory, freeTrackedMemory>;
using SamplerHandle = DeviceHandle<VkSampler, vkDestroySampler>;
using ShaderModuleHandle = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using PipelineHandle = DeviceHandle<VkPipeline, vkDestroyPipeline>;
using PipelineLayoutHandle = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;
using DescriptorSetLayoutHandle = DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using CommandPoolHandle = DeviceHandle<VkCommandPool, vkDestroyCommandPool>;
using QueryPoolHandle = DeviceHandle<VkQueryPool, vkDestroyQueryPool>;
using FenceHandle = DeviceHandle<VkFence, vkDestroyFence>;

} // namespace penumbra::vk
