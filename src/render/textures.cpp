#include "render/textures.h"

#include "penumbra/error.h"
#include "vk/check.h"
#include "vk/sync.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>

namespace penumbra::render {
namespace {

VkSamplerAddressMode addressOf(TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::ClampToEdge:
        return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case TextureWrap::MirroredRepeat:
        return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case TextureWrap::Repeat:
        break;
    }
    return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

// Trilinear minification; magnification as the asset asks. The alpha test reads level 0
// (textureLod 0 magnifies), the same texels the ground truth's CPU test reads.
vk::SamplerHandle createTextureSampler(const vk::Context& ctx, const Texture& t) {
    return vk::createSampler(ctx, {.magFilter = t.nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
                                   .minFilter = VK_FILTER_LINEAR,
                                   .mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR,
                                   .maxLod = VK_LOD_CLAMP_NONE,
                                   .addressU = addressOf(t.wrapS),
                                   .addressV = addressOf(t.wrapT),
                                   .addressW = VK_SAMPLER_ADDRESS_MODE_REPEAT});
}

// Records the copy of level 0 from `staging` and the blits down the mip chain; leaves every
// level ready for fragment shaders.
void recordUpload(VkCommandBuffer cmd, const vk::Image& image, VkBuffer staging,
                  VkDeviceSize offset) {
    vk::imageBarrier(cmd, image, vk::kUndefined, vk::kCopyWrite, 0, 1);
    if (image.mipLevels > 1)
        vk::imageBarrier(cmd, image, vk::kUndefined, vk::kBlitWrite, 1);
    const VkBufferImageCopy region{
        .bufferOffset = offset,
        .imageSubresource = {.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT, .layerCount = 1},
        .imageExtent = {image.width, image.height, 1}};
    vkCmdCopyBufferToImage(cmd, staging, image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
    auto size = [](uint32_t extent, uint32_t level) {
        return static_cast<int32_t>(std::max(1u, extent >> level));
    };
    for (uint32_t level = 1; level < image.mipLevels; ++level) {
        vk::imageBarrier(cmd, image, level == 1 ? vk::kCopyWrite : vk::kBlitWrite, vk::kBlitRead,
                         level - 1, 1);
        const VkImageBlit blit{
            .srcSubresource = {.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT,
                               .mipLevel = level - 1,
                               .layerCount = 1},
            .srcOffsets = {{0, 0, 0},
                           {size(image.width, level - 1), size(image.height, level - 1), 1}},
            .dstSubresource = {.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT,
                               .mipLevel = level,
                               .layerCount = 1},
            .dstOffsets = {{0, 0, 0}, {size(image.width, level), size(image.height, level), 1}}};
        vkCmdBlitImage(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.get(),
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        vk::imageBarrier(cmd, image, vk::kBlitRead, vk::kFragmentSampled, level - 1, 1);
    }
    vk::imageBarrier(cmd, image, image.mipLevels == 1 ? vk::kCopyWrite : vk::kBlitWrite,
                     vk::kFragmentSampled, image.mipLevels - 1, 1);
}

} // namespace

GpuTextures::Binding GpuTextures::of(const Scene& scene, const Material& material) const {
    const int32_t t = material.baseColorTexture;
    if (t < 0)
        return white();
    const Texture& texture = scene.textures[static_cast<size_t>(t)];
    return {images[texture.image].view.get(), samplers[static_cast<size_t>(t)].get()};
}

GpuTextures::Binding GpuTextures::transmissionOf(const Scene& scene,
                                                 const Material& material) const {
    const int32_t t = material.transmissionTexture;
    if (t < 0 || static_cast<size_t>(t) >= scene.textures.size())
        return white();
    // An image that is not there reads white, as the truth reads the factor alone then.
    const Texture& texture = scene.textures[static_cast<size_t>(t)];
    if (texture.image >= linearViews.size() || !linearViews[texture.image])
        return white();
    return {linearViews[texture.image].get(), samplers[static_cast<size_t>(t)].get()};
}

GpuTextures uploadTextures(const vk::Context& ctx, const Scene& scene) {
    static const TextureImage kWhite{
        .name = "white", .width = 1, .height = 1, .rgba = {255, 255, 255, 255}};
    std::vector<const TextureImage*> sources;
    for (const TextureImage& image : scene.images)
        sources.push_back(&image);
    sources.push_back(&kWhite);

    VkDeviceSize total = 0;
    for (const TextureImage* image : sources)
        total += image->rgba.size();
    vk::Buffer staging = vk::createBuffer(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                          vk::MemoryUse::Upload, "texture staging buffer");
    // The images a transmission texture reads, stored linear: viewed UNORM as well.
    std::vector<bool> linear(sources.size(), false);
    for (const Material& m : scene.materials)
        if (m.transmissionTexture >= 0 &&
            static_cast<size_t>(m.transmissionTexture) < scene.textures.size())
            if (const uint32_t image = scene.textures[size_t(m.transmissionTexture)].image;
                image < scene.images.size())
                linear[image] = true;
    GpuTextures out;
    VkDeviceSize offset = 0;
    std::vector<VkDeviceSize> offsets;
    for (const TextureImage* image : sources) {
        PENUMBRA_CHECK(image->rgba.size() == size_t{image->width} * image->height * 4,
                       "texture pixel count");
        std::memcpy(static_cast<std::byte*>(staging.mapped) + offset, image->rgba.data(),
                    image->rgba.size());
        offsets.push_back(offset);
        offset += image->rgba.size();
        out.images.push_back(vk::createImage(
            ctx, {.name = fmt::format("texture '{}'", image->name),
                  .format = VK_FORMAT_R8G8B8A8_SRGB,
                  .width = image->width,
                  .height = image->height,
                  .usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                           VK_IMAGE_USAGE_SAMPLED_BIT,
                  .mipLevels =
                      static_cast<uint32_t>(std::bit_width(std::max(image->width, image->height))),
                  .alsoViewedAs =
                      linear[out.images.size()] ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_UNDEFINED}));
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        for (size_t i = 0; i < out.images.size(); ++i)
            recordUpload(cmd, out.images[i], staging.get(), offsets[i]);
    });
    for (size_t i = 0; i < out.images.size(); ++i)
        out.linearViews.push_back(
            linear[i] ? vk::createFormatView(ctx, out.images[i], VK_FORMAT_R8G8B8A8_UNORM)
                      : vk::ImageViewHandle{});
    for (const Texture& texture : scene.textures)
        out.samplers.push_back(createTextureSampler(ctx, texture));
    out.samplers.push_back(createTextureSampler(ctx, Texture{}));
    return out;
}

} // namespace penumbra::render
