#pragma once
// VK_CHECK: a Vulkan call that fails here is a programmer or driver error, not bad input, so it
// aborts with the file, line and VkResult (error tier 2, docs/architecture.md).
// VK_CREATE: an object creation or allocation. Running out of host or device memory there is
// what the device does to us, not a bug: it throws a DeviceError (one error line); any other
// failure aborts as VK_CHECK does. PENUMBRA_FAULT=creation:N fails the Nth one (fault_injection.h).
#include <vulkan/vulkan.h>

namespace penumbra::vk {

const char* resultName(VkResult result);
[[noreturn]] void failedCall(const char* file, int line, const char* call, VkResult result);
// VK_ERROR_OUT_OF_HOST_MEMORY when the fault seam fails this creation, else VK_SUCCESS.
VkResult injectedCreationFault();
// Throws DeviceError for out-of-memory results, else aborts through failedCall.
[[noreturn]] void failedCreation(const char* file, int line, const char* call, VkResult result);

} // namespace penumbra::vk

#define VK_CHECK(call)                                                                             \
    do {                                                                                           \
        VkResult vkCheckResult_ = (call);                                                          \
        if (vkCheckResult_ != VK_SUCCESS)                                                          \
            ::penumbra::vk::failedCall(__FILE__, __LINE__, #call, vkCheckResult_);                 \
    } while (0)

#define VK_CREATE(call)                                                                            \
    do {                                                                                           \
        VkResult vkCreateResult_ = ::penumbra::vk::injectedCreationFault();                        \
        if (vkCreateResult_ == VK_SUCCESS)                                                         \
            vkCreateResult_ = (call);                                                              \
        if (vkCreateResult_ != VK_SUCCESS)                                                         \
            ::penumbra::vk::failedCreation(__FILE__, __LINE__, #call, vkCreateResult_);            \
    } while (0)
