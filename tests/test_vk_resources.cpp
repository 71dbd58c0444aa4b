// The RAII Vulkan layer's images and samplers beyond what the frame uses today: 3D images (a
// distance field), cube and cube-array images (point lights' views), mip chains, anisotropic
// and comparison samplers. Made on their own device with validation on; any message fails.
#include "penumbra/error.h"
#include "vk/context.h"
#include "vk/pipelines.h"
#include "vk/resources.h"
#include "vk/sync.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

using namespace penumbra;

TEST(VkResources, ThreeDimensionalCubeAndMipmappedImagesAndEverySamplerKind) {
    const vk::Context ctx({.deviceIndex = -1, .validation = true});
    // A 3D image: its extent's depth is real (a copy in and out keeps all 8 slices).
    const uint32_t n = 8;
    const vk::Image volume = vk::createImage(ctx, {.name = "volume",
                                                   .format = VK_FORMAT_R32_SFLOAT,
                                                   .width = n,
                                                   .height = n,
                                                   .usage = VK_IMAGE_USAGE_SAMPLED_BIT |
                                                            VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                                            VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                                   .depth = n});
    EXPECT_EQ(volume.depth, n);
    std::vector<float> values(n * n * n);
    for (size_t i = 0; i < values.size(); ++i)
        values[i] = static_cast<float>(i) * 0.5f;
    const vk::Buffer in = vk::createBuffer(ctx, values.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                           vk::MemoryUse::Upload, "in");
    std::memcpy(in.mapped, values.data(), values.size() * 4);
    const vk::Buffer out = vk::createBuffer(
        ctx, values.size() * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback, "out");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferImageCopy region{
            .imageSubresource = {.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT, .layerCount = 1},
            .imageExtent = {n, n, n}};
        vk::imageBarrier(cmd, volume, vk::kUndefined, vk::kCopyWrite);
        vkCmdCopyBufferToImage(cmd, in.get(), volume.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                               &region);
        vk::imageBarrier(cmd, volume, vk::kCopyWrite, vk::kTransferRead);
        vkCmdCopyImageToBuffer(cmd, volume.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.get(),
                               1, &region);
        vk::bufferBarrier(cmd, out.get(), VK_PIPELINE_STAGE_2_COPY_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                          VK_ACCESS_2_HOST_READ_BIT);
    });
    EXPECT_EQ(0, std::memcmp(out.mapped, values.data(), values.size() * 4));

    // Cube faces as depth targets (one cube, and a cube array where the device has them), and a
    // mip chain whose barriers cover a range of levels and layers.
    const vk::Image cube = vk::createImage(
        ctx, {.name = "cube",
              .format = VK_FORMAT_D32_SFLOAT,
              .width = 64,
              .height = 64,
              .layers = 6,
              .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
              .cube = true});
    EXPECT_EQ(cube.layers, 6u);
    if (ctx.info().imageCubeArray) {
        const vk::Image cubes = vk::createImage(
            ctx, {.name = "cubes",
                  .format = VK_FORMAT_D32_SFLOAT,
                  .width = 32,
                  .height = 32,
                  .layers = 12,
                  .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                  .cube = true});
        const vk::ImageViewHandle face = vk::createLayerView(ctx, cubes, 7);
        EXPECT_TRUE(static_cast<bool>(face));
    }
    const vk::Image mips =
        vk::createImage(ctx, {.name = "mips",
                              .format = VK_FORMAT_R32G32_SFLOAT,
                              .width = 64,
                              .height = 64,
                              .layers = 3,
                              .usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT,
                              .arrayView = true,
                              .mipLevels = 7});
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vk::Barriers()
            .image(mips, vk::kUndefined, vk::kComputeWrite, {.baseLayer = 1, .layerCount = 2})
            .image(mips, vk::kUndefined, vk::kComputeWrite, {.layerCount = 1, .mipCount = 3})
            .image(mips, vk::kUndefined, vk::kComputeWrite,
                   {.baseLayer = 0, .layerCount = 1, .baseMip = 3})
            .record(cmd);
    });

    // Every sampler kind: trilinear with anisotropy (clamped to what the device has), 3D
    // addressing with a border, a comparison sampler.
    const vk::SamplerHandle trilinear =
        vk::createSampler(ctx, {.magFilter = VK_FILTER_LINEAR,
                                .minFilter = VK_FILTER_LINEAR,
                                .mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR,
                                .maxLod = VK_LOD_CLAMP_NONE,
                                .anisotropy = 64.0f,
                                .addressU = VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                .addressV = VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT});
    const vk::SamplerHandle volumeSampler =
        vk::createSampler(ctx, {.magFilter = VK_FILTER_LINEAR,
                                .minFilter = VK_FILTER_LINEAR,
                                .addressU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER,
                                .addressV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER,
                                .addressW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER,
                                .border = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK});
    const vk::SamplerHandle compare = vk::createSampler(ctx, {.compare = true});
    EXPECT_TRUE(trilinear && volumeSampler && compare);
    EXPECT_EQ(ctx.validationErrors() + ctx.validationWarnings(), 0u);
}

// A layout past a device's limits is refused by the limit's name, at the limit and not before;
// each descriptor kind counts against the limits the specification says it does.
TEST(VkResources, ALayoutPastTheDevicesDescriptorLimitsIsNamed) {
    VkPhysicalDeviceLimits limits{};
    limits.maxPerStageResources = 100;
    limits.maxPerStageDescriptorSamplers = 5;
    limits.maxPerStageDescriptorSampledImages = 6;
    limits.maxPerStageDescriptorStorageImages = 2;
    limits.maxPerStageDescriptorUniformBuffers = 1;
    limits.maxPerStageDescriptorStorageBuffers = 3;
    using B = vk::Binding;
    const auto problem = [&](std::vector<B> bindings, uint32_t push = 32) {
        return vk::bindingLimitProblem(bindings, limits, push);
    };
    const B combined4{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    EXPECT_EQ(problem({combined4, {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}}), "");
    EXPECT_EQ(problem({combined4, {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}}),
              "6 descriptors past the device's maxPerStageDescriptorSamplers (5)");
    EXPECT_EQ(problem({combined4, {1, VK_DESCRIPTOR_TYPE_SAMPLER, 2}}),
              "6 descriptors past the device's maxPerStageDescriptorSamplers (5)");
    EXPECT_EQ(problem({combined4, {1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 2}}), "");
    EXPECT_EQ(problem({combined4, {1, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 3}}),
              "7 descriptors past the device's maxPerStageDescriptorSampledImages (6)");
    EXPECT_EQ(problem({{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}}), "");
    EXPECT_EQ(
        problem({{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2}}),
        "3 descriptors past the device's maxPerStageDescriptorStorageImages (2)");
    EXPECT_EQ(problem({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}}), "");
    EXPECT_EQ(
        problem({{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}, {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}}),
        "2 descriptors past the device's maxPerStageDescriptorUniformBuffers (1)");
    EXPECT_EQ(problem({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}}), "");
    EXPECT_EQ(problem({{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4}}),
              "4 descriptors past the device's maxPerStageDescriptorStorageBuffers (3)");
    // Every kind together counts against the push set's size and the stage's resources.
    const std::vector<B> mixed{{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5},
                               {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2},
                               {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                               {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}};
    EXPECT_EQ(problem(mixed, 11), "");
    EXPECT_EQ(problem(mixed, 10), "11 descriptors past the device's maxPushDescriptors (10)");
    limits.maxPerStageResources = 10;
    EXPECT_EQ(problem(mixed), "11 descriptors past the device's maxPerStageResources (10)");
    // A device's own limits hold every layout Penumbra makes (the frame's are made with it).
    const vk::Context ctx({.deviceIndex = -1, .validation = true});
    EXPECT_GE(ctx.maxPushDescriptors(), 32u) << "the specification's least";
    const vk::Binding tooMany{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, ctx.maxPushDescriptors() + 1};
    try {
        vk::createPipelineLayout(ctx, std::span(&tooMany, 1), VK_SHADER_STAGE_COMPUTE_BIT, 0);
        ADD_FAILURE() << "a layout past maxPushDescriptors was made";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), "--device");
        EXPECT_NE(std::string(e.what()).find("maxPushDescriptors"), std::string::npos) << e.what();
    }
}
