#pragma once
// VK_CHECK: a Vulkan call that fails here is a programmer or driver error, not bad input, so it
// aborts with the file, line and VkResult (design.md §4, error tier 2).
#include <vulkan/vulkan.h>

namespace penumbra::vk {

const char* resultName(VkResult result);
[[noreturn]] void failedCall(const char* file, int line, const char* call, VkResult result);

} // namespace penumbra::vk

#define VK_CHECK(call)                                                                             \
    do {                                                                                           \
        VkResult vkCheckResult_ = (call);                                                          \
        if (vkCheckResult_ != VK_SUCCESS)                                                          \
            ::penumbra::vk::failedCall(__FILE__, __LINE__, #call, vkCheckResult_);                 \
    } while (0)
