// The RAII Vulkan layer's images and samplers beyond what the frame uses today: 3D images (a
// distance field), cube and cube-array images (point lights' views), mip chains, anisotropic
// and comparison samplers. Made on their own device with validation on; any message fails.
#include "vk/context.h"
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
