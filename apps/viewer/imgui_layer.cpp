#include "imgui_layer.h"

#include "penumbra/error.h"
#include "vk/check.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

namespace penumbra::viewer {
namespace {

void checkResult(VkResult result) {
    if (result != VK_SUCCESS)
        fatal(__FILE__, __LINE__, vk::resultName(result));
}

RenderPassHandle createRenderPass(VkDevice device, VkFormat format) {
    const VkAttachmentDescription color{.format = format,
                                        .samples = VK_SAMPLE_COUNT_1_BIT,
                                        .loadOp = VK_ATTACHMENT_LOAD_OP_LOAD,
                                        .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                        .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                        .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                        .initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                        .finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};
    const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkSubpassDescription subpass{.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                                       .colorAttachmentCount = 1,
                                       .pColorAttachments = &ref};
    // In: after the blit that filled the image. Out: before a screenshot's copy.
    const VkSubpassDependency dependencies[] = {
        {.srcSubpass = VK_SUBPASS_EXTERNAL,
         .dstSubpass = 0,
         .srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
         .dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
         .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
         .dstAccessMask =
             VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT},
        {.srcSubpass = 0,
         .dstSubpass = VK_SUBPASS_EXTERNAL,
         .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
         .dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT,
         .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
         .dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT}};
    const VkRenderPassCreateInfo info{.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                      .attachmentCount = 1,
                                      .pAttachments = &color,
                                      .subpassCount = 1,
                                      .pSubpasses = &subpass,
                                      .dependencyCount = 2,
                                      .pDependencies = dependencies};
    VkRenderPass pass = VK_NULL_HANDLE;
    VK_CREATE(vkCreateRenderPass(device, &info, nullptr, &pass));
    return {device, pass};
}

} // namespace

ImGuiLayer::ImGuiLayer(const vk::Context& ctx, const Window& window, const Swapchain& swapchain)
    : mCtx(ctx) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window.get(), true);
    try { // the destructor does not run for a constructor that throws: undo what was set up
        initVulkan(swapchain);
    } catch (...) {
        shutdown();
        throw;
    }
}

void ImGuiLayer::initVulkan(const Swapchain& swapchain) {
    const vk::Context& ctx = mCtx;

    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
    const VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT,
        .maxSets = 8,
        .poolSizeCount = 1,
        .pPoolSizes = sizes};
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CREATE(vkCreateDescriptorPool(ctx.device(), &poolInfo, nullptr, &pool));
    mPool = DescriptorPoolHandle(ctx.device(), pool);
    rebuild(swapchain);

    ImGui_ImplVulkan_InitInfo info{.Instance = ctx.instance(),
                                   .PhysicalDevice = ctx.physicalDevice(),
                                   .Device = ctx.device(),
                                   .QueueFamily = ctx.queueFamily(),
                                   .Queue = ctx.queue(),
                                   .PipelineCache = VK_NULL_HANDLE,
                                   .DescriptorPool = pool,
                                   .Subpass = 0,
                                   .MinImageCount = swapchain.minImageCount,
                                   .ImageCount = static_cast<uint32_t>(swapchain.images.size()),
                                   .MSAASamples = VK_SAMPLE_COUNT_1_BIT,
                                   .Allocator = nullptr,
                                   .CheckVkResultFn = checkResult};
    ImGui_ImplVulkan_Init(&info, mRenderPass.get());
    mVulkanBackend = true;
    ctx.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
    shutdown();
}

void ImGuiLayer::shutdown() noexcept {
    vkDeviceWaitIdle(mCtx.device());
    if (mVulkanBackend) {
        ImGui_ImplVulkan_DestroyFontUploadObjects(); // left by a font upload that failed
        ImGui_ImplVulkan_Shutdown();
    }
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void ImGuiLayer::rebuild(const Swapchain& swapchain) {
    if (swapchain.format != mFormat) {
        mRenderPass = createRenderPass(mCtx.device(), swapchain.format);
        mFormat = swapchain.format; // the backend's pipeline is made for the first; the format
                                    // of a window does not change in practice
    }
    mFramebuffers.clear();
    mViews.clear();
    mExtent = swapchain.extent;
    for (VkImage image : swapchain.images) {
        const VkImageViewCreateInfo viewInfo{
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = image,
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = swapchain.format,
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
        VkImageView view = VK_NULL_HANDLE;
        VK_CREATE(vkCreateImageView(mCtx.device(), &viewInfo, nullptr, &view));
        mViews.emplace_back(mCtx.device(), view);
        const VkFramebufferCreateInfo fbInfo{.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                             .renderPass = mRenderPass.get(),
                                             .attachmentCount = 1,
                                             .pAttachments = &view,
                                             .width = mExtent.width,
                                             .height = mExtent.height,
                                             .layers = 1};
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        VK_CREATE(vkCreateFramebuffer(mCtx.device(), &fbInfo, nullptr, &framebuffer));
        mFramebuffers.emplace_back(mCtx.device(), framebuffer);
    }
    if (ImGui::GetIO().BackendRendererUserData) // the backend is running: a new swapchain
        ImGui_ImplVulkan_SetMinImageCount(swapchain.minImageCount);
}

void ImGuiLayer::newFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::record(VkCommandBuffer cmd, uint32_t image, bool draw) {
    ImGui::Render();
    const VkRenderPassBeginInfo begin{.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                      .renderPass = mRenderPass.get(),
                                      .framebuffer = mFramebuffers[image].get(),
                                      .renderArea = {{0, 0}, mExtent}};
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    if (draw)
        ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

} // namespace penumbra::viewer
