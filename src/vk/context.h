#pragma once
// Context: the Vulkan instance (with the validation layer and a debug messenger that counts its
// messages when asked), the chosen physical device, one graphics+compute queue, and one-shot
// command submission. Everything else in src/vk borrows the VkDevice from here.
#include "penumbra/renderer.h"
#include "vk/handles.h"

#include <vulkan/vulkan.h>

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace penumbra::vk {

// Counts validation-layer messages; owned by Instance, read by tests and the CLI.
struct ValidationCounters {
    std::atomic<uint32_t> errors{0};
    std::atomic<uint32_t> warnings{0};
};

class Instance {
public:
    // `windowExtensions`: what a window system needs to present (the viewer's; may be empty).
    Instance(bool validation, const std::vector<std::string>& windowExtensions);
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    VkInstance get() const { return mInstance; }
    bool validation() const { return mMessenger != VK_NULL_HANDLE; }
    const ValidationCounters& counters() const { return *mCounters; }
    std::vector<VkPhysicalDevice> physicalDevices() const;
    // With `options.canPresent`, a device that cannot present to the window is unsuitable.
    DeviceInfo describe(VkPhysicalDevice device, uint32_t index,
                        const DeviceOptions& options = {}) const;

private:
    VkInstance mInstance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT mMessenger = VK_NULL_HANDLE;
    std::unique_ptr<ValidationCounters> mCounters = std::make_unique<ValidationCounters>();
};

class Context {
public:
    // Throws InputError("--device", ...) when the requested device is missing or unsuitable.
    explicit Context(const DeviceOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return mInstance.get(); }
    VkDevice device() const { return mDevice; }
    VkPhysicalDevice physicalDevice() const { return mPhysical; }
    VkQueue queue() const { return mQueue; }
    uint32_t queueFamily() const { return mQueueFamily; }
    const VkPhysicalDeviceLimits& limits() const { return mProperties.limits; }
    // Descriptors one push descriptor set may hold (VK_KHR_push_descriptor; at least 32).
    uint32_t maxPushDescriptors() const { return mMaxPushDescriptors; }
    // The largest single allocation the device promises (Vulkan 1.1; at least 2^30 bytes).
    VkDeviceSize maxMemoryAllocationSize() const { return mMaxMemoryAllocationSize; }
    const DeviceInfo& info() const { return mInfo; }
    uint32_t validationErrors() const { return mInstance.counters().errors.load(); }
    uint32_t validationWarnings() const { return mInstance.counters().warnings.load(); }

    // A memory type in `typeBits` with all `required` flags, preferring `preferred` ones.
    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                        VkMemoryPropertyFlags preferred = 0) const;
    uint64_t deviceLocalHeapBytes() const;
    // The memory types (a bit each) that have every `required` flag.
    uint32_t memoryTypesWith(VkMemoryPropertyFlags required) const;

    // Records into a fresh primary command buffer, submits it and waits for completion.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
    // The result of a submit, wait, acquire or present: a lost device or memory running out is
    // what the device does to us, a DeviceError naming the device (one error line); any other
    // failure aborts as VK_CHECK does.
    void checkWork(VkResult result, const char* call) const;
    // VK_ERROR_DEVICE_LOST when PENUMBRA_FAULT fails this submission, else vkQueueSubmit2's result.
    VkResult submit(const VkSubmitInfo2& info, VkFence fence) const;

    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

private:
    Instance mInstance;
    VkPhysicalDevice mPhysical = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties mProperties{};
    uint32_t mMaxPushDescriptors = 0;
    VkDeviceSize mMaxMemoryAllocationSize = 0;
    VkPhysicalDeviceMemoryProperties mMemory{};
    DeviceInfo mInfo;
    VkDevice mDevice = VK_NULL_HANDLE;
    VkQueue mQueue = VK_NULL_HANDLE;
    uint32_t mQueueFamily = 0;
    CommandPoolHandle mCommandPool;
};

} // namespace penumbra::vk
