#include "render/frame_targets.h"

#include "checkerboard.h"
#include "core/fnv1a.h"
#include "core/virtual_maps.h"
#include "render/pipelines.h"
#include "translucent.h"

#include <algorithm>

namespace penumbra::render {

std::string target::shadowMap(std::string_view name) {
    return "shadow." + std::string(name);
}

VkFormat formatOf(shadows::MapFormat format) {
    switch (format) {
    case shadows::MapFormat::Depth32:
        return kDepthFormat;
    case shadows::MapFormat::R32F:
        return VK_FORMAT_R32_SFLOAT;
    case shadows::MapFormat::RG32F:
        return VK_FORMAT_R32G32_SFLOAT;
    case shadows::MapFormat::R32UI:
        return VK_FORMAT_R32_UINT;
    case shadows::MapFormat::RG32UI:
        return VK_FORMAT_R32G32_UINT;
    case shadows::MapFormat::RGBA32UI:
        return VK_FORMAT_R32G32B32A32_UINT;
    case shadows::MapFormat::RGBA16:
        return VK_FORMAT_R16G16B16A16_UNORM;
    case shadows::MapFormat::RGBA32F:
        break;
    }
    return VK_FORMAT_R32G32B32A32_SFLOAT;
}

namespace {

constexpr VkImageUsageFlags kSampled = VK_IMAGE_USAGE_SAMPLED_BIT;
constexpr VkImageUsageFlags kDepthTarget =
    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
constexpr VkImageUsageFlags kStorageOut =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

// A map of every shadow view: a layer each, a 2D view of each layer (and level) to render into
// or write in a post pass.
ImageDecl viewMap(std::string_view name, shadows::MapFormat format, bool mipmapped,
                  uint32_t shrink = 0, bool history = false) {
    return {.name = target::shadowMap(name),
            .size = SizeClass::ShadowView,
            .shrink = shrink,
            .format = formatOf(format),
            .usage = format == shadows::MapFormat::Depth32 ? kDepthTarget
                                                           : VK_IMAGE_USAGE_STORAGE_BIT | kSampled,
            .mipmapped = mipmapped,
            .layerViews = true,
            .lifetime = history ? Lifetime::History : Lifetime::PerFrame};
}

ImageDecl screen(std::string_view name, VkFormat format, VkImageUsageFlags usage,
                 bool perLight = false) {
    return {.name = std::string(name),
            .size = SizeClass::Screen,
            .format = format,
            .usage = usage,
            .perLight = perLight,
            .arrayView = perLight};
}

// A pool of virtual.poolSize^2 depth texels, its contents kept across frames.
ImageDecl virtualPoolDecl(std::string_view name, const ParameterValues& params,
                          VkImageUsageFlags usage) {
    const auto pool = static_cast<uint32_t>(params.number("virtual.poolSize"));
    const auto page = static_cast<uint32_t>(params.number("virtual.pageSize"));
    return {.name = std::string(name),
            .size = SizeClass::Fixed,
            .format = kDepthFormat,
            .usage = usage,
            .width = pool,
            .height = pool,
            .layerViews = true,
            .lifetime = Lifetime::Persistent,
            .key = (uint64_t{pool} << 32) | page};
}

} // namespace

std::optional<ImageDecl> staticPoolDecl(const shadows::TechniqueModule& module,
                                        const ParameterValues& params) {
    const VirtualSettings v = VirtualSettings::of(params);
    if (!module.readsVirtualMaps || !v.enabled || !v.staticLayer)
        return std::nullopt;
    return virtualPoolDecl(target::kStaticPool, params,
                           VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                               VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
}

std::vector<ImageDecl> shadowMapDecls(const shadows::TechniqueModule& module,
                                      const ParameterValues& params,
                                      std::span<const ShadowView> views) {
    if (module.readsVirtualMaps && params.number("virtual.enabled") != 0.0)
        return {virtualPoolDecl(target::kVirtualPool, params,
                                kDepthTarget | VK_IMAGE_USAGE_TRANSFER_DST_BIT)};
    std::vector<ImageDecl> decls{viewMap(shadows::kDepthMap, shadows::MapFormat::Depth32, false)};
    for (const shadows::MapDecl& map : module.maps) {
        decls.push_back(viewMap(map.name, shadows::formatOf(map, params),
                                shadows::mipmappedOf(map, params), map.shrink, map.history));
        if (map.history)
            decls.back().key = historyKeyOf(views);
    }
    return decls;
}

std::vector<ImageDecl> translucentMapDecls(uint32_t method) {
    auto map = [](std::string name, VkFormat format) {
        return ImageDecl{.name = target::shadowMap("translucent." + name),
                         .size = SizeClass::ShadowView,
                         .format = format,
                         .usage = format == kDepthFormat
                                      ? kDepthTarget
                                      : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | kSampled,
                         .layerViews = true};
    };
    if (method == TRANSLUCENT_COLOURED)
        return {map("nearest", kDepthFormat), map("second", kDepthFormat),
                map("front", kTranslucentProductFormat), map("product", kTranslucentProductFormat)};
    std::vector<ImageDecl> moments;
    for (uint32_t i = 0; i < TRANSLUCENT_MAPS; ++i)
        moments.push_back(map("moments" + std::to_string(i), kTranslucentMomentsFormat));
    return moments;
}

uint64_t historyKeyOf(std::span<const ShadowView> views) {
    uint64_t hash = kFnv1aOffset; // over each view's bytes that place it
    for (const ShadowView& view : views) {
        hash = fnv1a(&view.light, sizeof view.light, hash);
        hash = fnv1a(&view.projection.perspective, sizeof view.projection.perspective, hash);
        hash = fnv1a(&view.projection.viewProj, sizeof view.projection.viewProj, hash);
    }
    return hash;
}

std::vector<ImageDecl> screenDecls(bool intermediates) {
    std::vector<ImageDecl> decls{
        screen(target::kGBufferDepth, kDepthFormat, kDepthTarget),
        screen(target::kGBufferNormal, kNormalFormat,
               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | kSampled),
        screen(target::kGBufferAlbedo, kAlbedoFormat,
               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | kSampled),
        screen(target::kGBufferMotion, kMotionFormat,
               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | kSampled | VK_IMAGE_USAGE_TRANSFER_SRC_BIT),
        screen(target::kVisibility, VK_FORMAT_R32_SFLOAT, kStorageOut | kSampled, true),
        // The translucent layer's light per channel (declared when the layer runs; the composite
        // reads it).
        screen(target::kTranslucentColour, VK_FORMAT_R32G32B32A32_SFLOAT, kStorageOut | kSampled,
               true),
        // The screen passes' scratch (shadows::kScreenScratch; declared when one binds it).
        screen(target::kScreenScratch, VK_FORMAT_R32_SFLOAT, kStorageOut, true),
        screen(target::kColor, VK_FORMAT_R8G8B8A8_UNORM, kStorageOut),
        screen(target::kPosition, VK_FORMAT_R32G32B32A32_SFLOAT, kStorageOut),
        screen(target::kNormal, VK_FORMAT_R32G32B32A32_SFLOAT, kStorageOut),
        screen(target::kFaceNormal, VK_FORMAT_R32G32B32A32_SFLOAT, kStorageOut)};
    // The viewer's intermediate results (the technique's, and each layer's own) at full size,
    // else 1x1 stand-ins: every binding a shader uses must be written. Persistent: a frame may
    // hand them over unwritten (no layer ran), their layout set.
    for (auto [name, format] : {std::pair{target::kIntermediates, VK_FORMAT_R32G32B32A32_SFLOAT},
                                std::pair{target::kLayerResults, VK_FORMAT_R32_SFLOAT}})
        decls.push_back(intermediates
                            ? screen(name, format, VK_IMAGE_USAGE_STORAGE_BIT | kSampled, true)
                            : ImageDecl{.name = std::string(name),
                                        .size = SizeClass::Fixed,
                                        .format = format,
                                        .usage = VK_IMAGE_USAGE_STORAGE_BIT | kSampled});
    for (ImageDecl& decl : decls)
        if (decl.name == target::kIntermediates || decl.name == target::kLayerResults)
            decl.lifetime = Lifetime::Persistent;
    decls.push_back(integerPlaceholderDecl());
    decls.push_back(depthPlaceholderDecl());
    return decls;
}

ImageDecl layerHistoryDecl(const shadows::LayerModule& layer,
                           const shadows::TechniqueModule& technique,
                           const ParameterValues& params) {
    uint64_t key = fnv1a(technique.info.name.data(), technique.info.name.size());
    for (const auto& [name, value] : params.all()) {
        key = fnv1a(name.data(), name.size(), key);
        key = fnv1a(&value, sizeof value, key);
    }
    ImageDecl decl = screen("layer." + std::string(layer.name) + ".history",
                            formatOf(*layer.history), VK_IMAGE_USAGE_STORAGE_BIT | kSampled, true);
    decl.lifetime = Lifetime::History;
    decl.key = key;
    return decl;
}

// 1x1, one layer, viewed as an array: what a comparison sampler of the depth map reads.
ImageDecl depthPlaceholderDecl() {
    return {.name = std::string(target::kDepthPlaceholder),
            .size = SizeClass::Fixed,
            .format = VK_FORMAT_D32_SFLOAT,
            .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
            .lifetime = Lifetime::Persistent};
}

ImageDecl integerPlaceholderDecl() {
    return {.name = std::string(target::kIntegerPlaceholder),
            .size = SizeClass::Fixed,
            .format = VK_FORMAT_R32G32B32A32_UINT,
            .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
            .lifetime = Lifetime::Persistent};
}

ReadbackLayout::ReadbackLayout(uint32_t width, uint32_t height, uint32_t visibilityLayers,
                               bool withMotion, bool withColour) {
    const VkDeviceSize pixels = VkDeviceSize{width} * height;
    VkDeviceSize offset = 0;
    // A copy's buffer offset must be a multiple of its format's texel block (Vulkan: up to 16
    // bytes here, RGBA32F); an odd-sized image's 4-byte parts would leave the next one off it.
    constexpr VkDeviceSize kBlock = 16;
    auto part = [&](std::string_view target, VkDeviceSize size) {
        const Part p{target, offset, size};
        offset = (offset + size + kBlock - 1) / kBlock * kBlock;
        return p;
    };
    color = part(target::kColor, pixels * 4);
    visibility = part(target::kVisibility, pixels * 4 * std::max(visibilityLayers, 1u));
    position = part(target::kPosition, pixels * 16);
    normal = part(target::kNormal, pixels * 16);
    faceNormal = part(target::kFaceNormal, pixels * 16);
    if (withMotion)
        motion = part(target::kGBufferMotion, pixels * 16);
    if (withColour)
        colour = part(target::kTranslucentColour, pixels * 16 * std::max(visibilityLayers, 1u));
    bytes = offset;
}

BufferDecl ReadbackLayout::decl() const {
    return {.name = std::string(target::kReadback),
            .size = SizeClass::Fixed,
            .bytes = bytes,
            .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
            .memory = vk::MemoryUse::Readback};
}

TargetBytes targetBytes(const shadows::TechniqueModule& module, const ParameterValues& params,
                        const FrameSizes& sizes, bool motion) {
    TargetBytes bytes{0, 0};
    for (const ImageDecl& decl : shadowMapDecls(module, params, {})) // bytes: keys aside
        bytes.shadowMaps += ResourcePool::bytesOf(decl, sizes);
    if (const std::optional<ImageDecl> decl = staticPoolDecl(module, params))
        bytes.shadowMaps += ResourcePool::bytesOf(*decl, sizes);
    const std::vector<const shadows::LayerModule*> layers = shadows::enabledLayers(params);
    const bool colour = std::any_of(layers.begin(), layers.end(), [](const auto* layer) {
        return layer->translucentMethod != nullptr;
    });
    for (const ImageDecl& decl : screenDecls(false))
        if ((motion || decl.name != target::kGBufferMotion) &&
            (colour || decl.name != target::kTranslucentColour))
            bytes.screen += ResourcePool::bytesOf(decl, sizes);
    for (const shadows::LayerModule* layer : layers) {
        if (layer->history) // bytesOf counts its two versions, last frame's and this frame's
            bytes.screen += ResourcePool::bytesOf(layerHistoryDecl(*layer, module, params), sizes);
        if (layer->translucentMethod) // whether or not the scene has translucent casters
            for (const ImageDecl& decl : translucentMapDecls(layer->translucentMethod(params)))
                bytes.shadowMaps += ResourcePool::bytesOf(decl, sizes);
    }
    bytes.screen +=
        ReadbackLayout(sizes.width, sizes.height, sizes.shadowLights, motion, colour).bytes;
    const bool checkerboard =
        shadows::checkerboardFill(shadows::screenPassesOf(module, params)) != nullptr;
    bytes.screen += traceListDecl(sizes.width, sizes.height, checkerboard).bytes;
    return bytes;
}

uint32_t traceListEntries(uint32_t width, uint32_t height) {
    return static_cast<uint32_t>((uint64_t{width} * height + 1) / 2);
}

BufferDecl traceListDecl(uint32_t width, uint32_t height, bool checkerboard) {
    const VkDeviceSize filled = traceListEntries(width, height);
    return {.name = std::string(target::kTraceList),
            .size = SizeClass::Fixed,
            .bytes = sizeof(gpu::TraceListHead) + (checkerboard ? filled * sizeof(uint32_t) : 0),
            .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                     VK_BUFFER_USAGE_TRANSFER_DST_BIT};
}

} // namespace penumbra::render
