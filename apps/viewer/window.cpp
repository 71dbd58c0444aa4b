#include "window.h"

#include "penumbra/error.h"
#include "vk/check.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

namespace penumbra::viewer {
namespace {

std::string lastGlfwError() {
    const char* text = nullptr;
    glfwGetError(&text);
    return text ? text : "unknown GLFW error";
}

} // namespace

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
    glfwSetErrorCallback(nullptr);
    if (!glfwInit()) {
        const char* display = std::getenv("DISPLAY");
        throw InputError("display",
                         fmt::format("cannot open a window ({}){}", lastGlfwError(),
                                     display && *display ? ""
                                                         : "; DISPLAY is not set: run it in an "
                                                           "X session or under xvfb-run"));
    }
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw InputError("display", "GLFW finds no Vulkan loader that can present to a window");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    mWindow = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(),
                               nullptr, nullptr);
    if (!mWindow) {
        const std::string error = lastGlfwError();
        glfwTerminate();
        throw InputError("display",
                         fmt::format("cannot create a {}x{} window ({})", width, height, error));
    }
}

Window::~Window() {
    glfwDestroyWindow(mWindow);
    glfwTerminate();
}

std::vector<std::string> Window::instanceExtensions() {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names)
        throw InputError("display", "no Vulkan surface extension for this display");
    return {names, names + count};
}

bool Window::canPresent(VkInstance instance, VkPhysicalDevice device, uint32_t family) {
    return glfwGetPhysicalDevicePresentationSupport(instance, device, family) == GLFW_TRUE;
}

VkExtent2D Window::framebufferSize() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(mWindow, &w, &h);
    return {static_cast<uint32_t>(std::max(w, 0)), static_cast<uint32_t>(std::max(h, 0))};
}

bool Window::shouldClose() const {
    return glfwWindowShouldClose(mWindow);
}

Surface::Surface(const vk::Context& ctx, const Window& window) : mInstance(ctx.instance()) {
    const VkResult result = glfwCreateWindowSurface(mInstance, window.get(), nullptr, &mSurface);
    if (result != VK_SUCCESS)
        throw InputError("display", fmt::format("cannot make a Vulkan surface for the window "
                                                "({})",
                                                vk::resultName(result)));
    VkBool32 supported = VK_FALSE;
    VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), mSurface,
                                                  &supported));
    if (!supported) {
        vkDestroySurfaceKHR(mInstance, mSurface, nullptr);
        throw InputError("display",
                         fmt::format("{} cannot present to this window", ctx.info().name));
    }
}

Surface::~Surface() {
    vkDestroySurfaceKHR(mInstance, mSurface, nullptr);
}

SemaphoreHandle createSemaphore(const vk::Context& ctx) {
    const VkSemaphoreCreateInfo info{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VK_CREATE(vkCreateSemaphore(ctx.device(), &info, nullptr, &semaphore));
    return {ctx.device(), semaphore};
}

Swapchain createSwapchain(const vk::Context& ctx, VkSurfaceKHR surface, VkExtent2D extent,
                          bool vsync, VkSwapchainKHR old) {
    const VkPhysicalDevice physical = ctx.physicalDevice();
    VkSurfaceCapabilitiesKHR caps{};
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps));
    uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data()));
    Swapchain s{.vsync = vsync};
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const VkSurfaceFormatKHR& f : formats)
            if (s.format == VK_FORMAT_UNDEFINED && f.format == wanted &&
                f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
                s.format = wanted;
    if (s.format == VK_FORMAT_UNDEFINED)
        throw InputError("display", "the window offers no 8-bit BGRA or RGBA colour format");
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT; // blit in, screenshot out
    if ((caps.supportedUsageFlags & usage) != usage)
        throw InputError("display", "the window's images cannot be copied to and from");

    VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR; // vsync; always supported
    if (!vsync) {
        VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr));
        std::vector<VkPresentModeKHR> modes(count);
        VK_CHECK(
            vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data()));
        for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (mode == VK_PRESENT_MODE_FIFO_KHR &&
                std::find(modes.begin(), modes.end(), wanted) != modes.end())
                mode = wanted;
    }
    s.extent = caps.currentExtent.width != UINT32_MAX
                   ? caps.currentExtent
                   : VkExtent2D{std::clamp(extent.width, caps.minImageExtent.width,
                                           caps.maxImageExtent.width),
                                std::clamp(extent.height, caps.minImageExtent.height,
                                           caps.maxImageExtent.height)};
    VkCompositeAlphaFlagBitsKHR alpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    for (VkCompositeAlphaFlagBitsKHR a :
         {VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR, VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
          VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
        if (!(caps.supportedCompositeAlpha & alpha) && (caps.supportedCompositeAlpha & a))
            alpha = a;
    s.minImageCount = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0)
        s.minImageCount = std::min(s.minImageCount, caps.maxImageCount);
    const VkSwapchainCreateInfoKHR info{.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
                                        .surface = surface,
                                        .minImageCount = s.minImageCount,
                                        .imageFormat = s.format,
                                        .imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR,
                                        .imageExtent = s.extent,
                                        .imageArrayLayers = 1,
                                        .imageUsage = usage,
                                        .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
                                        .preTransform = caps.currentTransform,
                                        .compositeAlpha = alpha,
                                        .presentMode = mode,
                                        .clipped = VK_TRUE,
                                        .oldSwapchain = old};
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    VK_CREATE(vkCreateSwapchainKHR(ctx.device(), &info, nullptr, &handle));
    s.handle = SwapchainHandle(ctx.device(), handle);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device(), handle, &count, nullptr));
    s.images.resize(count);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device(), handle, &count, s.images.data()));
    for (uint32_t i = 0; i < count; ++i)
        s.rendered.push_back(createSemaphore(ctx));
    return s;
}

} // namespace penumbra::viewer
