#include "vk/context.h"

#include "core/fault_injection.h"
#include "penumbra/error.h"
#include "vk/check.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <utility>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cstring>
#include <string>

namespace penumbra::vk {
namespace {

// A software device (lavapipe) rasterises in this process: its draw module allocates each draw's
// vertex buffers and frees them after, and glibc gives the top of the heap back to the kernel
// past 128 KiB (M_TRIM_THRESHOLD), so every draw faults its pages in anew. On a 100k-triangle
// scene that was two thirds of the shadow and G-buffer passes (perf: exc_page_fault under the
// vertex shader and sysmalloc). Keeping up to 512 MiB of freed memory ends it; once a process.
void keepFreedMemory() {
#if defined(__GLIBC__)
    static std::once_flag once;
    std::call_once(once, [] { mallopt(M_TRIM_THRESHOLD, 512 << 20); });
#endif
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    auto* counters = static_cast<ValidationCounters*>(user);
    const char* label = "warning";
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        counters->errors.fetch_add(1);
        label = "error";
    } else {
        counters->warnings.fetch_add(1);
    }
    std::fprintf(stderr, "vulkan validation %s: %s\n", label, data->pMessage);
    return VK_FALSE;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, exts.data());
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

// The one queue family that does graphics, compute and timestamps (and presents, when
// `canPresent` is given); UINT32_MAX if none.
uint32_t findQueueFamily(VkInstance instance, VkPhysicalDevice device,
                         const DeviceOptions& options) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0 &&
            (!options.canPresent || options.canPresent(instance, device, i)))
            return i;
    }
    return UINT32_MAX;
}

const char* typeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return "CPU (software)";
    default:
        return "other";
    }
}

int typeRank(const std::string& type) {
    static const char* order[] = {"discrete GPU", "integrated GPU", "virtual GPU",
                                  "CPU (software)"};
    for (int i = 0; i < 4; ++i)
        if (type == order[i])
            return i;
    return 4;
}

} // namespace

Instance::Instance(bool validation, const std::vector<std::string>& windowExtensions) {
    if (validation && !hasLayer(kValidationLayer))
        throw InputError("--validation", "the Khronos validation layer is not installed "
                                         "(Debian package vulkan-validationlayers)");
    const VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                                .pApplicationName = "penumbra",
                                .applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                                .pEngineName = "penumbra",
                                .apiVersion = VK_API_VERSION_1_3};
    std::vector<const char*> layers, extensions;
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    for (const std::string& name : windowExtensions)
        extensions.push_back(name.c_str());
    const VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = onDebugMessage,
        .pUserData = mCounters.get()};
    // Synchronization validation catches missing barriers, which lavapipe would forgive.
    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    const VkValidationFeaturesEXT features{.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                           .pNext = &messengerInfo,
                                           .enabledValidationFeatureCount = 1,
                                           .pEnabledValidationFeatures = enables};
    const VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                    .pNext = validation ? &features : nullptr,
                                    .pApplicationInfo = &app,
                                    .enabledLayerCount = static_cast<uint32_t>(layers.size()),
                                    .ppEnabledLayerNames = layers.data(),
                                    .enabledExtensionCount =
                                        static_cast<uint32_t>(extensions.size()),
                                    .ppEnabledExtensionNames = extensions.data()};
    VkResult result = vkCreateInstance(&info, nullptr, &mInstance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
        throw InputError("vulkan", fmt::format("no Vulkan 1.3 driver found ({}); install "
                                               "mesa-vulkan-drivers for the software rasterizer",
                                               resultName(result)));
    VK_CHECK(result);
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(mInstance, "vkCreateDebugUtilsMessengerEXT"));
        PENUMBRA_CHECK(create != nullptr, "vkCreateDebugUtilsMessengerEXT missing");
        VK_CHECK(create(mInstance, &messengerInfo, nullptr, &mMessenger));
    }
}

Instance::~Instance() {
    if (mMessenger != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(mInstance, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(mInstance, mMessenger, nullptr);
    }
    vkDestroyInstance(mInstance, nullptr);
}

std::vector<VkPhysicalDevice> Instance::physicalDevices() const {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(mInstance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(mInstance, &count, devices.data()));
    return devices;
}

DeviceInfo Instance::describe(VkPhysicalDevice device, uint32_t index,
                              const DeviceOptions& options) const {
    VkPhysicalDeviceDriverProperties driver{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                      .pNext = &driver};
    vkGetPhysicalDeviceProperties2(device, &props);
    const auto& p = props.properties;
    DeviceInfo info{.index = index,
                    .name = p.deviceName,
                    .type = typeName(p.deviceType),
                    .driverName = driver.driverName,
                    .driverInfo = driver.driverInfo,
                    .apiVersion = fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(p.apiVersion),
                                              VK_API_VERSION_MINOR(p.apiVersion),
                                              VK_API_VERSION_PATCH(p.apiVersion)),
                    .maxImageDimension2D = p.limits.maxImageDimension2D,
                    .maxComputeWorkGroupInvocations = p.limits.maxComputeWorkGroupInvocations,
                    .maxStorageBufferRange = p.limits.maxStorageBufferRange,
                    .timestampPeriodNs = p.limits.timestampPeriod};
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(device, &memory);
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            info.deviceLocalBytes =
                std::max<uint64_t>(info.deviceLocalBytes, memory.memoryHeaps[i].size);

    VkPhysicalDeviceVulkan13Features f13{.sType =
                                             VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                       .pNext = &f13};
    vkGetPhysicalDeviceFeatures2(device, &features);
    VkFormatProperties depth{};
    vkGetPhysicalDeviceFormatProperties(device, VK_FORMAT_D32_SFLOAT, &depth);
    const VkFormatFeatureFlags depthNeeds =
        VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    // Optional: lavapipe 22.3 advertises linear filtering for no depth format.
    info.depthLinearFilter =
        (depth.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
    info.subTexelPrecisionBits = p.limits.subTexelPrecisionBits;
    info.maxSamplerAnisotropy =
        features.features.samplerAnisotropy ? p.limits.maxSamplerAnisotropy : 0.0f;
    info.imageCubeArray = features.features.imageCubeArray != 0;
    if (p.apiVersion < VK_API_VERSION_1_3)
        info.unsuitableReason = "Vulkan 1.3 is not supported";
    else if (!f13.dynamicRendering || !f13.synchronization2 || !f13.maintenance4)
        info.unsuitableReason = "dynamic rendering, synchronization2 or maintenance4 is missing";
    else if (!features.features.depthClamp)
        info.unsuitableReason = "depthClamp is not supported";
    else if (!features.features.shaderStorageImageExtendedFormats ||
             !features.features.shaderStorageImageWriteWithoutFormat)
        info.unsuitableReason =
            "shaderStorageImageExtendedFormats or shaderStorageImageWriteWithoutFormat is missing";
    else if (!hasDeviceExtension(device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        info.unsuitableReason = "VK_KHR_push_descriptor is not supported";
    else if (options.canPresent && !hasDeviceExtension(device, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        info.unsuitableReason = "VK_KHR_swapchain is not supported (it cannot present to a window)";
    else if (findQueueFamily(mInstance, device, options) == UINT32_MAX)
        info.unsuitableReason = options.canPresent
                                    ? "no queue does graphics, compute, timestamps and presents "
                                      "to the window"
                                    : "no queue does graphics, compute and timestamps";
    else if ((depth.optimalTilingFeatures & depthNeeds) != depthNeeds)
        info.unsuitableReason = "D32_SFLOAT cannot be rendered and sampled";
    info.suitable = info.unsuitableReason.empty();
    return info;
}

Context::Context(const DeviceOptions& options)
    : mInstance(options.validation, options.instanceExtensions) {
    const auto devices = mInstance.physicalDevices();
    if (devices.empty())
        throw InputError("vulkan", "no Vulkan device found");
    int chosen = -1;
    if (options.deviceIndex >= 0) {
        if (static_cast<size_t>(options.deviceIndex) >= devices.size())
            throw InputError("--device", fmt::format("{} is out of range: {} device(s) found (see "
                                                     "`penumbra info`)",
                                                     options.deviceIndex, devices.size()));
        const DeviceInfo info =
            mInstance.describe(devices[options.deviceIndex], options.deviceIndex, options);
        if (!info.suitable)
            throw InputError("--device",
                             fmt::format("{} ({}) cannot be used: {}", options.deviceIndex,
                                         info.name, info.unsuitableReason));
        chosen = options.deviceIndex;
    } else {
        int bestRank = 1 << 30;
        for (uint32_t i = 0; i < devices.size(); ++i) {
            const DeviceInfo info = mInstance.describe(devices[i], i, options);
            if (info.suitable && typeRank(info.type) < bestRank)
                bestRank = typeRank(info.type), chosen = static_cast<int>(i);
        }
        if (chosen < 0)
            throw InputError("vulkan", options.canPresent
                                           ? "no Vulkan device can present to the window and "
                                             "has what Penumbra needs; see `penumbra info`"
                                           : "no Vulkan device has what Penumbra needs (Vulkan "
                                             "1.3, dynamic rendering, push descriptors); see "
                                             "`penumbra info`");
    }
    mPhysical = devices[chosen];
    mInfo = mInstance.describe(mPhysical, static_cast<uint32_t>(chosen), options);
    VkPhysicalDeviceMaintenance3Properties maintenance3{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDevicePushDescriptorPropertiesKHR push{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR,
        .pNext = &maintenance3};
    VkPhysicalDeviceProperties2 properties{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                           .pNext = &push};
    vkGetPhysicalDeviceProperties2(mPhysical, &properties);
    mProperties = properties.properties;
    mMaxPushDescriptors = push.maxPushDescriptors;
    mMaxMemoryAllocationSize = maintenance3.maxMemoryAllocationSize;
    vkGetPhysicalDeviceMemoryProperties(mPhysical, &mMemory);
    if (mProperties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        keepFreedMemory();
    mQueueFamily = findQueueFamily(mInstance.get(), mPhysical, options);

    const float priority = 1.0f;
    const VkDeviceQueueCreateInfo queueInfo{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                            .queueFamilyIndex = mQueueFamily,
                                            .queueCount = 1,
                                            .pQueuePriorities = &priority};
    VkPhysicalDeviceVulkan13Features f13{.sType =
                                             VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                         .synchronization2 = VK_TRUE,
                                         .dynamicRendering = VK_TRUE,
                                         .maintenance4 = VK_TRUE}; // glslc's LocalSizeId
    VkPhysicalDeviceVulkan12Features f12{.sType =
                                             VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                         .pNext = &f13,
                                         .hostQueryReset = VK_TRUE};
    // Optional: clip distances (virtual maps' pages drawn on the device, whose render passes
    // refuse a device without them).
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(mPhysical, &supported);
    const VkPhysicalDeviceFeatures2 features{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
        .pNext = &f12,
        .features = {.imageCubeArray = mInfo.imageCubeArray ? VK_TRUE : VK_FALSE,
                     .depthClamp = VK_TRUE,
                     .depthBiasClamp = VK_TRUE,
                     .samplerAnisotropy = mInfo.maxSamplerAnisotropy > 0 ? VK_TRUE : VK_FALSE,
                     // rg32f / rg32ui post-pass outputs; a map whose format follows a parameter
                     // (msm.precision) is written without a format qualifier
                     .shaderStorageImageExtendedFormats = VK_TRUE,
                     .shaderStorageImageWriteWithoutFormat = VK_TRUE,
                     .shaderClipDistance = supported.shaderClipDistance}};
    std::vector<const char*> extensions{VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (options.canPresent)
        extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    const VkDeviceCreateInfo info{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                  .pNext = &features,
                                  .queueCreateInfoCount = 1,
                                  .pQueueCreateInfos = &queueInfo,
                                  .enabledExtensionCount = static_cast<uint32_t>(extensions.size()),
                                  .ppEnabledExtensionNames = extensions.data()};
    VK_CREATE(vkCreateDevice(mPhysical, &info, nullptr, &mDevice));
    vkGetDeviceQueue(mDevice, mQueueFamily, 0, &mQueue);
    cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(mDevice, "vkCmdPushDescriptorSetKHR"));
    PENUMBRA_CHECK(cmdPushDescriptorSet != nullptr, "vkCmdPushDescriptorSetKHR missing");

    const VkCommandPoolCreateInfo poolInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                           .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
                                           .queueFamilyIndex = mQueueFamily};
    VkCommandPool pool = VK_NULL_HANDLE;
    try { // the destructor does not run for a constructor that throws
        VK_CREATE(vkCreateCommandPool(mDevice, &poolInfo, nullptr, &pool));
    } catch (...) {
        vkDestroyDevice(std::exchange(mDevice, VK_NULL_HANDLE), nullptr);
        throw;
    }
    mCommandPool = CommandPoolHandle(mDevice, pool);
}

Context::~Context() {
    if (mDevice == VK_NULL_HANDLE)
        return;
    vkDeviceWaitIdle(mDevice);
    mCommandPool.reset(); // owned objects go before the device they came from
    vkDestroyDevice(mDevice, nullptr);
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                             VkMemoryPropertyFlags preferred) const {
    for (VkMemoryPropertyFlags want : {required | preferred, required})
        for (uint32_t i = 0; i < mMemory.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (mMemory.memoryTypes[i].propertyFlags & want) == want)
                return i;
    fatal(__FILE__, __LINE__, "no suitable Vulkan memory type");
}

uint32_t Context::memoryTypesWith(VkMemoryPropertyFlags required) const {
    uint32_t bits = 0;
    for (uint32_t i = 0; i < mMemory.memoryTypeCount; ++i)
        if ((mMemory.memoryTypes[i].propertyFlags & required) == required)
            bits |= 1u << i;
    return bits;
}

uint64_t Context::deviceLocalHeapBytes() const {
    return mInfo.deviceLocalBytes;
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
    const VkCommandBufferAllocateInfo allocInfo{.sType =
                                                    VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                                .commandPool = mCommandPool.get(),
                                                .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                                .commandBufferCount = 1};
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CREATE(vkAllocateCommandBuffers(mDevice, &allocInfo, &cmd));
    const VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                         .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    const VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence rawFence = VK_NULL_HANDLE;
    VK_CREATE(vkCreateFence(mDevice, &fenceInfo, nullptr, &rawFence));
    FenceHandle fence(mDevice, rawFence);
    const VkCommandBufferSubmitInfo cmdInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                            .commandBuffer = cmd};
    const VkSubmitInfo2 submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                               .commandBufferInfoCount = 1,
                               .pCommandBufferInfos = &cmdInfo};
    VkResult result = this->submit(submit, fence.get());
    if (result == VK_SUCCESS)
        result = vkWaitForFences(mDevice, 1, &rawFence, VK_TRUE, UINT64_MAX);
    // On failure the command buffer stays in the pool (freed with it): it may still be pending.
    checkWork(result, "vkQueueSubmit2");
    vkFreeCommandBuffers(mDevice, mCommandPool.get(), 1, &cmd);
}

VkResult Context::submit(const VkSubmitInfo2& info, VkFence fence) const {
    return injectFault(FaultSite::Submit) ? VK_ERROR_DEVICE_LOST
                                          : vkQueueSubmit2(mQueue, 1, &info, fence);
}

void Context::checkWork(VkResult result, const char* call) const {
    if (result == VK_ERROR_DEVICE_LOST || result == VK_ERROR_OUT_OF_DEVICE_MEMORY ||
        result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw DeviceError(fmt::format(
            "{}: the GPU work failed ({}){}", mInfo.name, resultName(result),
            result == VK_ERROR_DEVICE_LOST ? "; the driver reset or lost the device: run again, "
                                             "or pick another with --device"
                                           : ""));
    if (result != VK_SUCCESS)
        failedCall(__FILE__, __LINE__, call, result);
}

} // namespace penumbra::vk
