#pragma once
// The viewer's window: GLFW with no client API, its Vulkan surface, and a swapchain over it that
// is remade when the window's size changes. A failure to open a display is an InputError
// ("display", ...): the CLI prints it as `error: display: ...`.
#include "vk/context.h"
#include "vk/handles.h"

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

struct GLFWwindow;

namespace penumbra::viewer {

// glfwInit / glfwTerminate, and one window.
class Window {
public:
    Window(uint32_t width, uint32_t height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* get() const { return mWindow; }
    // The instance extensions GLFW needs to make a surface on this display.
    static std::vector<std::string> instanceExtensions();
    // Whether `family` of `device` can present on this display.
    static bool canPresent(VkInstance instance, VkPhysicalDevice device, uint32_t family);
    // The framebuffer's size in pixels (0 x 0 while minimised).
    VkExtent2D framebufferSize() const;
    bool shouldClose() const;

private:
    GLFWwindow* mWindow = nullptr;
};

class Surface {
public:
    Surface(const vk::Context& ctx, const Window& window);
    ~Surface();
    Surface(const Surface&) = delete;
    Surface& operator=(const Surface&) = delete;
    VkSurfaceKHR get() const { return mSurface; }

private:
    VkInstance mInstance = VK_NULL_HANDLE;
    VkSurfaceKHR mSurface = VK_NULL_HANDLE;
};

using SwapchainHandle = vk::DeviceHandle<VkSwapchainKHR, vkDestroySwapchainKHR>;
using SemaphoreHandle = vk::DeviceHandle<VkSemaphore, vkDestroySemaphore>;

// The swapchain, its images, and a semaphore per image signalled when its frame is drawn.
// Colour format B8G8R8A8_UNORM or R8G8B8A8_UNORM: the frame's values are already sRGB-encoded.
struct Swapchain {
    SwapchainHandle handle;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    std::vector<VkImage> images;
    std::vector<SemaphoreHandle> rendered;
    bool vsync = true;
    uint32_t minImageCount = 2;
};

// Makes a swapchain for `extent` (clamped to what the surface allows), replacing `old`.
Swapchain createSwapchain(const vk::Context& ctx, VkSurfaceKHR surface, VkExtent2D extent,
                          bool vsync, VkSwapchainKHR old = VK_NULL_HANDLE);
SemaphoreHandle createSemaphore(const vk::Context& ctx);

} // namespace penumbra::viewer
