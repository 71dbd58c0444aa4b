#include "vk/check.h"

#include "core/fault_injection.h"
#include "penumbra/error.h"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace penumbra::vk {

const char* resultName(VkResult result) {
    switch (result) {
#define PENUMBRA_RESULT(r)                                                                         \
    case r:                                                                                        \
        return #r;
        PENUMBRA_RESULT(VK_SUCCESS)
        PENUMBRA_RESULT(VK_NOT_READY)
        PENUMBRA_RESULT(VK_TIMEOUT)
        PENUMBRA_RESULT(VK_INCOMPLETE)
        PENUMBRA_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        PENUMBRA_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        PENUMBRA_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        PENUMBRA_RESULT(VK_ERROR_DEVICE_LOST)
        PENUMBRA_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        PENUMBRA_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        PENUMBRA_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        PENUMBRA_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        PENUMBRA_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        PENUMBRA_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        PENUMBRA_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        PENUMBRA_RESULT(VK_ERROR_FRAGMENTED_POOL)
        PENUMBRA_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef PENUMBRA_RESULT
    default:
        return "VkResult(unknown)";
    }
}

void failedCall(const char* file, int line, const char* call, VkResult result) {
    std::fprintf(stderr, "penumbra: fatal: %s:%d: %s returned %s (%d)\n", file, line, call,
                 resultName(result), static_cast<int>(result));
    std::abort();
}

VkResult injectedCreationFault() {
    return injectFault(FaultSite::Creation) ? VK_ERROR_OUT_OF_HOST_MEMORY : VK_SUCCESS;
}

void failedCreation(const char* file, int line, const char* call, VkResult result) {
    if (result != VK_ERROR_OUT_OF_HOST_MEMORY && result != VK_ERROR_OUT_OF_DEVICE_MEMORY)
        failedCall(file, line, call, result);
    // "vkCreateImageView(device, ...)" -> "vkCreateImageView": what ran out, for the user.
    const std::string_view text(call);
    throw DeviceError(fmt::format("vulkan: out of memory in {} ({})",
                                  text.substr(0, text.find('(')), resultName(result)));
}

} // namespace penumbra::vk
