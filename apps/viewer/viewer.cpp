// The viewer's frame loop. Per frame: wait for the slot's previous frame (its GPU times), acquire
// a swapchain image, build the interface, record technique A's frame (and B's for A/B), the
// display pass, the blit into the swapchain image, the interface's render pass and, for
// --screenshot, a copy of the finished image; submit, present. Changes that remake targets or the
// swapchain wait for the device to go idle; everything else overlaps two frames.
#include "viewer.h"

#include "core/image_io.h"
#include "core/output_dir.h"
#include "display.h"
#include "frame_slot.h"
#include "imgui_layer.h"
#include "penumbra/error.h"
#include "render/renderer_impl.h"
#include "truth_job.h"
#include "viewer_session.h"
#include "vk/check.h"
#include "vk/sync.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace penumbra::viewer {
namespace {

// The window's input for the camera, unless the interface has it.
CameraInput readInput(GLFWwindow* window, float seconds) {
    const ImGuiIO& io = ImGui::GetIO();
    CameraInput in{.seconds = seconds};
    if (!io.WantCaptureMouse) {
        const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);
        const bool valid = io.MouseDelta.x > -1e5f; // no previous position: -FLT_MAX
        if (valid && ImGui::IsMouseDown(ImGuiMouseButton_Left))
            in.dragLeft = delta;
        if (valid && ImGui::IsMouseDown(ImGuiMouseButton_Right))
            in.dragRight = delta;
        in.wheel = io.MouseWheel;
    }
    if (!io.WantCaptureKeyboard) {
        auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
        in.move = {key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
                   key(GLFW_KEY_W) - key(GLFW_KEY_S)};
        in.fast = key(GLFW_KEY_LEFT_SHIFT) > 0.0f || key(GLFW_KEY_RIGHT_SHIFT) > 0.0f;
    }
    return in;
}

void submit(const vk::Context& ctx, const FrameSlot& slot, VkSemaphore rendered) {
    const VkSemaphoreSubmitInfo wait{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                     .semaphore = slot.acquired.get(),
                                     .stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT};
    const VkSemaphoreSubmitInfo signal{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                       .semaphore = rendered,
                                       .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    const VkCommandBufferSubmitInfo cmdInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                            .commandBuffer = slot.cmd};
    const VkSubmitInfo2 info{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                             .waitSemaphoreInfoCount = 1,
                             .pWaitSemaphoreInfos = &wait,
                             .commandBufferInfoCount = 1,
                             .pCommandBufferInfos = &cmdInfo,
                             .signalSemaphoreInfoCount = 1,
                             .pSignalSemaphoreInfos = &signal};
    const VkFence fence = slot.done.get();
    VK_CHECK(vkResetFences(ctx.device(), 1, &fence));
    ctx.checkWork(ctx.submit(info, fence), "vkQueueSubmit2");
}

// The swapchain image's states around the blit, the interface's render pass and a capture.
// Acquiring waits at the blit (the submit's semaphore wait), so the first barrier chains to it.
constexpr vk::ImageState kAcquired{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE,
                                   VK_IMAGE_LAYOUT_UNDEFINED};
// After the render pass: its outgoing dependency made the writes visible to transfers.
constexpr vk::ImageState kPresentable{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                                      VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};
constexpr vk::ImageState kPresent{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};

// The display image into swapchain image `target` (left in TRANSFER_DST for the interface).
void recordBlit(VkCommandBuffer cmd, const vk::Image& from, VkImage target, VkExtent2D extent) {
    vk::colorImageBarrier(cmd, target, kAcquired, vk::kBlitWrite);
    const VkImageBlit region{
        .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .srcOffsets = {{0, 0, 0},
                       {static_cast<int32_t>(from.width), static_cast<int32_t>(from.height), 1}},
        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
        .dstOffsets = {
            {0, 0, 0},
            {static_cast<int32_t>(extent.width), static_cast<int32_t>(extent.height), 1}}};
    vkCmdBlitImage(cmd, from.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_NEAREST);
}

// The finished swapchain image (PRESENT_SRC after the interface's pass) into `buffer`.
void recordCapture(VkCommandBuffer cmd, VkImage image, VkExtent2D extent, VkBuffer buffer) {
    vk::colorImageBarrier(cmd, image, kPresentable, vk::kTransferRead);
    const VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                   .imageExtent = {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    vk::colorImageBarrier(cmd, image, vk::kTransferRead, kPresent);
    vk::bufferBarrier(cmd, buffer, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

} // namespace

void runViewer(const Scene& scene, const ViewerOptions& options) {
    // A screenshot path that cannot be written fails before the window opens.
    std::optional<StagedOutputDir> screenshotDir;
    if (!options.screenshot.empty()) {
        const std::filesystem::path path(options.screenshot);
        if (path.filename().empty())
            throw InputError(options.screenshot, "--screenshot needs a file name");
        screenshotDir.emplace(path.has_parent_path() ? path.parent_path() : ".");
    }
    Window window(options.render.width, options.render.height, "penumbra view: " + scene.name);
    Renderer renderer({.deviceIndex = options.device,
                       .validation = options.validation,
                       .instanceExtensions = Window::instanceExtensions(),
                       .canPresent = [](VkInstance_T* i, VkPhysicalDevice_T* d, uint32_t f) {
                           return Window::canPresent(i, d, f);
                       }});
    const vk::Context& ctx = renderer.context();
    Surface surface(ctx, window);
    Swapchain swapchain =
        createSwapchain(ctx, surface.get(), window.framebufferSize(), options.vsync);
    std::fprintf(stderr, "penumbra: viewing %s on %s (%s), window %ux%u\n", scene.name.c_str(),
                 renderer.device().name.c_str(), renderer.device().driverName.c_str(),
                 swapchain.extent.width, swapchain.extent.height);

    ViewerSession session(renderer, scene, options, swapchain.extent);
    DisplayPass display(ctx);
    display.resize(swapchain.extent.width, swapchain.extent.height);
    ImGuiLayer ui(ctx, window, swapchain);
    std::array<FrameSlot, 2> slots{FrameSlot(ctx), FrameSlot(ctx)};
    vk::Buffer capture; // the last frame's swapchain image, for --screenshot
    // Declared last, so destroyed first: when a frame throws (the device lost, memory out), the
    // frames before it may still be running, and what they use must outlive them.
    const struct IdleOnExit {
        VkDevice device;
        ~IdleOnExit() { vkDeviceWaitIdle(device); }
    } idleOnExit{ctx.device()};

    auto remakeSwapchain = [&] {
        VK_CHECK(vkDeviceWaitIdle(ctx.device()));
        Swapchain next = createSwapchain(ctx, surface.get(), window.framebufferSize(),
                                         session.state().vsync, swapchain.handle.get());
        swapchain = std::move(next);
        ui.rebuild(swapchain);
        display.resize(swapchain.extent.width, swapchain.extent.height);
        session.resize(swapchain.extent);
    };

    double lastTime = glfwGetTime();
    bool tabWasDown = false;
    bool spaceWasDown = false;
    for (uint64_t frame = 0; !window.shouldClose(); ++frame) {
        glfwPollEvents();
        const VkExtent2D size = window.framebufferSize();
        if (size.width == 0 || size.height == 0) { // minimised: nothing to draw into
            glfwWaitEvents();
            --frame;
            continue;
        }
        FrameSlot& slot = slots[frame % slots.size()];
        slot.wait(ctx);
        if (slot.pending) { // its GPU times are ready
            session.recordTimes(slot);
            slot.pending = false;
        }
        if (size.width != swapchain.extent.width || size.height != swapchain.extent.height ||
            session.state().vsync != swapchain.vsync) {
            remakeSwapchain();
            --frame;
            continue;
        }
        uint32_t image = 0;
        const VkResult acquired =
            vkAcquireNextImageKHR(ctx.device(), swapchain.handle.get(), UINT64_MAX,
                                  slot.acquired.get(), VK_NULL_HANDLE, &image);
        if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
            remakeSwapchain();
            --frame;
            continue;
        }
        if (acquired != VK_SUBOPTIMAL_KHR)
            ctx.checkWork(acquired, "vkAcquireNextImageKHR");

        const double now = glfwGetTime();
        const auto seconds = static_cast<float>(now - lastTime);
        lastTime = now;
        const bool tabDown = glfwGetKey(window.get(), GLFW_KEY_TAB) == GLFW_PRESS;
        ui.newFrame();
        if (tabDown && !tabWasDown && !ImGui::GetIO().WantTextInput)
            session.state().hideUi = !session.state().hideUi;
        tabWasDown = tabDown;
        const bool spaceDown = glfwGetKey(window.get(), GLFW_KEY_SPACE) == GLFW_PRESS;
        if (spaceDown && !spaceWasDown && !ImGui::GetIO().WantTextInput)
            session.state().playing = !session.state().playing;
        spaceWasDown = spaceDown;
        if (glfwGetKey(window.get(), GLFW_KEY_ESCAPE) == GLFW_PRESS)
            glfwSetWindowShouldClose(window.get(), GLFW_TRUE);
        if (!session.state().hideUi)
            session.drawInterface();
        session.update(readInput(window.get(), seconds), seconds, display);

        const bool last = options.frames > 0 && frame + 1 >= options.frames;
        const VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                             .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        VK_CHECK(vkResetCommandBuffer(slot.cmd, 0));
        VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
        session.record(slot, frame, display);
        recordBlit(slot.cmd, display.output(), swapchain.images[image], swapchain.extent);
        ui.record(slot.cmd, image, !session.state().hideUi);
        if (last && screenshotDir) {
            capture = vk::createBuffer(
                ctx, VkDeviceSize{swapchain.extent.width} * swapchain.extent.height * 4,
                VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "screenshot");
            recordCapture(slot.cmd, swapchain.images[image], swapchain.extent, capture.get());
        }
        VK_CHECK(vkEndCommandBuffer(slot.cmd));
        submit(ctx, slot, swapchain.rendered[image].get());
        slot.pending = true;

        const VkSwapchainKHR handle = swapchain.handle.get();
        const VkSemaphore rendered = swapchain.rendered[image].get();
        const VkPresentInfoKHR present{.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                                       .waitSemaphoreCount = 1,
                                       .pWaitSemaphores = &rendered,
                                       .swapchainCount = 1,
                                       .pSwapchains = &handle,
                                       .pImageIndices = &image};
        const VkResult presented = vkQueuePresentKHR(ctx.queue(), &present);
        if (presented != VK_ERROR_OUT_OF_DATE_KHR && presented != VK_SUBOPTIMAL_KHR)
            ctx.checkWork(presented, "vkQueuePresentKHR");
        if (last)
            break;
    }
    ctx.checkWork(vkDeviceWaitIdle(ctx.device()), "vkDeviceWaitIdle");
    for (FrameSlot& slot : slots)
        if (slot.pending) // the last frames' GPU times
            session.recordTimes(slot), slot.pending = false;
    if (options.frames > 0)
        session.printTimes();
    if (renderer.validationErrors() > 0)
        throw std::runtime_error(fmt::format("vulkan validation: {} error(s), see messages "
                                             "above{}",
                                             renderer.validationErrors(),
                                             screenshotDir ? "; no screenshot written" : ""));
    if (screenshotDir && capture.mapped) {
        const VkExtent2D e = swapchain.extent;
        std::vector<uint8_t> rgba(size_t{e.width} * e.height * 4);
        std::memcpy(rgba.data(), capture.mapped, rgba.size());
        const bool bgra = swapchain.format == VK_FORMAT_B8G8R8A8_UNORM;
        for (size_t i = 0; i < rgba.size(); i += 4) {
            if (bgra)
                std::swap(rgba[i], rgba[i + 2]);
            rgba[i + 3] = 255;
        }
        const std::string name = std::filesystem::path(options.screenshot).filename().string();
        screenshotDir->write(name, encodePng(e.width, e.height, 4, rgba));
        screenshotDir->commit();
        std::printf("wrote %s (%ux%u, frame %u)\n", options.screenshot.c_str(), e.width, e.height,
                    options.frames);
    }
}

} // namespace penumbra::viewer
