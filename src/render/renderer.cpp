#include "penumbra/renderer.h"

#include "core/fault_injection.h"
#include "core/projection.h"
#include "core/virtual_maps.h"
#include "page_passes.h"
#include "penumbra/error.h"
#include "render/distance_field.h"
#include "render/frame.h"
#include "render/frame_data.h"
#include "render/frame_targets.h"
#include "render/pipelines.h"
#include "render/renderer_impl.h"
#include "shadows/layer.h"
#include "shadows/technique.h"
#include "translucent.h"
#include "vk/context.h"
#include "vk/resources.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace penumbra {

namespace {

// Lights with a shadow map (a visibility layer each) and their views (a map layer each).
struct ShadowCount {
    std::string scene;
    size_t lights = 0, views = 0;
};

ShadowCount shadowCount(const Scene& scene, const RenderOptions& o) {
    ShadowCount n{.scene = scene.name};
    const auto cascades = static_cast<uint32_t>(o.parameters.number("csm.cascades"));
    const VirtualSettings v = VirtualSettings::of(o.parameters);
    for (const Light& l : scene.lights) {
        n.lights += castsShadowMap(l);
        n.views += v.enabled ? virtualViewCount(l, v) : shadowViewCount(l, cascades);
    }
    return n;
}

// virtual.*: a technique that reads its map texel by texel, sizes that make whole pages and a
// pool and page table the device holds.
void checkVirtualMaps(const vk::Context& ctx, const Scene& scene, const RenderOptions& o) {
    const VirtualSettings v = VirtualSettings::of(o.parameters);
    if (!v.enabled)
        return;
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    if (!module.readsVirtualMaps)
        throw InputError(
            "virtual.enabled",
            fmt::format("technique {} does not read its maps through a page table "
                        "(its maps are filtered whole, or it draws none); virtual maps serve {}",
                        techniqueName(o.technique),
                        shadows::techniquesWhere(
                            [](const shadows::TechniqueModule& m) { return m.readsVirtualMaps; })));
    auto powerOfTwo = [](const char* key, uint32_t value) {
        if (!std::has_single_bit(value))
            throw InputError(key, fmt::format("{} is not a power of two", value));
    };
    if (v.deviceDecides) {
        VkPhysicalDeviceFeatures features{};
        vkGetPhysicalDeviceFeatures(ctx.physicalDevice(), &features);
        if (!features.shaderClipDistance)
            throw InputError("virtual.deviceDecides",
                             "this device lacks shaderClipDistance, which the pages drawn on the "
                             "device need (set virtual.deviceDecides=0)");
    }
    if (v.deviceDecides && o.parameters.isSet("virtual.staticLayer") &&
        o.parameters.number("virtual.staticLayer") != 0.0)
        throw InputError("virtual.staticLayer",
                         "the device's decisions draw every caster into every page they render; "
                         "set virtual.staticLayer=0 or virtual.deviceDecides=0");
    powerOfTwo("virtual.size", v.size);
    powerOfTwo("virtual.pageSize", v.pageSize);
    if (v.pageSize > v.size)
        throw InputError("virtual.pageSize",
                         fmt::format("{} exceeds virtual.size ({})", v.pageSize, v.size));
    if (v.poolSize % v.pageSize != 0)
        throw InputError("virtual.poolSize", fmt::format("{} is not a multiple of "
                                                         "virtual.pageSize ({})",
                                                         v.poolSize, v.pageSize));
    if (v.poolSize > ctx.limits().maxImageDimension2D)
        throw InputError("virtual.poolSize",
                         fmt::format("{} exceeds this device's maxImageDimension2D ({})",
                                     v.poolSize, ctx.limits().maxImageDimension2D));
    uint64_t entries = 0;
    for (const Light& l : scene.lights)
        entries += virtualTableEntries(l, v);
    const uint64_t range = ctx.limits().maxStorageBufferRange;
    if (entries * sizeof(uint32_t) > range)
        throw InputError(scene.name,
                         fmt::format("its virtual maps need a page table of {} entries; this "
                                     "device's storage buffers hold {} (maxStorageBufferRange); "
                                     "raise virtual.pageSize or lower virtual.size",
                                     entries, range / sizeof(uint32_t)));
    if (v.deviceDecides && entries > PAGES_MOST_ENTRIES)
        throw InputError("virtual.deviceDecides",
                         fmt::format("its virtual maps need a page table of {} entries; the "
                                     "device decides at most {} (one dispatch's reach); raise "
                                     "virtual.pageSize, lower virtual.size or set "
                                     "virtual.deviceDecides=0",
                                     entries, PAGES_MOST_ENTRIES));
}

void checkDeviceLimits(const vk::Context& ctx, const RenderOptions& o, const ShadowCount& shadows) {
    const size_t shadowLights = shadows.lights;
    const uint32_t limit = ctx.limits().maxImageDimension2D;
    auto tooBig = [&](const char* option, uint32_t value) {
        if (value > limit)
            throw InputError(
                option,
                fmt::format("{} exceeds this device's maxImageDimension2D ({})", value, limit));
    };
    tooBig("--width", o.width);
    tooBig("--height", o.height);
    tooBig("--shadow-map-size", o.shadowMapSize);
    const uint32_t layers = ctx.limits().maxImageArrayLayers;
    if (shadows.views > layers || shadowLights > layers)
        throw InputError(shadows.scene,
                         fmt::format("its {} shadow-casting lights need {} shadow views "
                                     "(a point light takes 6, a sun csm.cascades); this device's "
                                     "maxImageArrayLayers is {}",
                                     shadowLights, shadows.views, layers));
    const size_t viewRecords =
        render::uniformCapacity(ctx, sizeof(gpu::ShadowViewData), MAX_UNIFORM_VIEWS);
    if (shadows.views > viewRecords)
        throw InputError(shadows.scene,
                         fmt::format("its {} shadow-casting lights need {} shadow views (a point "
                                     "light takes 6, a sun csm.cascades); this device's uniform "
                                     "buffers hold {} (maxUniformBufferRange {})",
                                     shadowLights, shadows.views, viewRecords,
                                     ctx.limits().maxUniformBufferRange));
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    // Checkerboard tracing's list is one storage buffer. (Its pixels are packed 16 bits a
    // coordinate: no device has maxImageDimension2D past 65536.)
    const std::vector<shadows::ScreenPassDecl> screenPasses =
        shadows::screenPassesOf(module, o.parameters);
    if (const shadows::ScreenPassDecl* fill = shadows::checkerboardFill(screenPasses)) {
        const VkDeviceSize list = render::traceListDecl(o.width, o.height, true).bytes;
        if (list > ctx.limits().maxStorageBufferRange)
            throw InputError("--width",
                             fmt::format("{}x{} needs a trace list of {} bytes for checkerboard "
                                         "tracing; this device's storage buffers hold {} "
                                         "(maxStorageBufferRange): render smaller or set "
                                         "{}=false",
                                         o.width, o.height, list,
                                         ctx.limits().maxStorageBufferRange, fill->parameter));
    }
    // The frame's targets as it declares them (render/frame_targets.h), the readback included.
    const render::TargetBytes bytes =
        render::targetBytes(module, o.parameters,
                            {.width = o.width,
                             .height = o.height,
                             .shadowMapSize = shadows::drawnMapSize(module, o.shadowMapSize),
                             .shadowViews = static_cast<uint32_t>(shadows.views),
                             .shadowLights = static_cast<uint32_t>(shadowLights)},
                            o.motion || shadows::keepsHistory(o.parameters));
    const double pixels = double(o.width) * double(o.height);
    const auto shadowBytes = static_cast<double>(bytes.shadowMaps);
    const double need = static_cast<double>(bytes.screen) + shadowBytes;
    const double have = static_cast<double>(deviceMemoryForChecks(ctx.deviceLocalHeapBytes()));
    if (need > 0.8 * have) {
        // With virtual maps the shadow bytes are the pool's, whatever --shadow-map-size says.
        const VirtualSettings v = VirtualSettings::of(o.parameters);
        const bool pooled = v.enabled && module.readsVirtualMaps;
        const std::string shadowWhat =
            pooled ? fmt::format("{} of {}^2 texels{}",
                                 v.staticLayer ? "two virtual pools" : "a virtual pool", v.poolSize,
                                 v.staticLayer ? ", the pages' and their static layers' "
                                                 "(virtual.staticLayer=0 keeps one)"
                                               : "")
                   : fmt::format("{} shadow views of {} texels", shadows.views, o.shadowMapSize);
        const char* shadowOption = pooled ? "virtual.poolSize" : "--shadow-map-size";
        throw InputError(shadowBytes > pixels * 100 ? shadowOption : "--width",
                         fmt::format("{} needs {:.2f} GiB of device memory ({:.2f} GiB for {}); "
                                     "a render may use {:.2f} GiB, 80% of the device's {:.2f} GiB",
                                     techniqueName(o.technique), need / (1 << 30),
                                     shadowBytes / (1 << 30), shadowWhat, 0.8 * have / (1 << 30),
                                     have / (1 << 30)));
    }
}

} // namespace

Renderer::Renderer(const DeviceOptions& options) : mImpl(std::make_unique<Impl>(options)) {}
Renderer::~Renderer() = default;

const DeviceInfo& Renderer::device() const {
    return mImpl->ctx.info();
}
uint32_t Renderer::validationErrors() const {
    return mImpl->ctx.validationErrors();
}
DeviceMemoryUse Renderer::deviceMemoryInUse() const {
    const vk::LiveDeviceMemory live = vk::liveDeviceMemory();
    return {.allocations = live.allocations, .bytes = live.bytes};
}

uint32_t Renderer::validationMessages() const {
    return mImpl->ctx.validationErrors() + mImpl->ctx.validationWarnings();
}
const vk::Context& Renderer::context() const {
    return mImpl->ctx;
}

namespace {

// The translucent layer, on a scene with translucent casters (elsewhere it does not run): whole
// maps drawn from the light (not virtual ones, not a distance field's tracer, whose field takes
// translucent casters as opaque), and a device that blends 32-bit float moments.
void checkTranslucentLayer(const vk::Context& ctx, const Scene& scene, const RenderOptions& o) {
    const uint32_t method = shadows::translucentLayer().translucentMethod(o.parameters);
    // Its casters are triangles with a translucent material, as the upload groups them: a
    // material no triangle uses casts nothing.
    if (method == TRANSLUCENT_OFF || !scene.hasTranslucentCasters())
        return;
    if (o.parameters.number("virtual.enabled") != 0.0)
        throw InputError("translucent.method", "translucent shadows need whole shadow maps: "
                                               "virtual.enabled=1 does not draw them yet");
    if (!shadows::drawsLightMaps(shadows::moduleOf(o.technique)))
        throw InputError("translucent.method",
                         fmt::format("{} draws no shadow map from the light; translucent "
                                     "shadows need one",
                                     shadows::moduleOf(o.technique).info.name));
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), render::kTranslucentMomentsFormat,
                                        &properties);
    if (method == TRANSLUCENT_MOMENTS &&
        !(properties.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT))
        throw InputError("translucent.method", "this device does not blend 32-bit float "
                                               "colour attachments, which the moments add up in "
                                               "(translucent.method=coloured does not need it)");
}

} // namespace

void Renderer::check(const Scene& scene, const RenderOptions& o) const {
    validate(o);
    if (scene.triangleCount() == 0)
        throw InputError(scene.name, "the scene has no triangles");
    (void)scene.camera(o.camera); // throws for an unknown camera name
    checkDeviceLimits(mImpl->ctx, o, shadowCount(scene, o));
    checkVirtualMaps(mImpl->ctx, scene, o);
    checkTranslucentLayer(mImpl->ctx, scene, o);
    if (const auto& declared = shadows::moduleOf(o.technique).tracedField)
        render::checkDistanceField(mImpl->ctx, scene,
                                   render::FieldSetting::of(*declared, o.parameters));
}

RenderResult Renderer::render(const Scene& scene, const RenderOptions& o,
                              const ProgressFn& progress) {
    check(scene, o);
    if (progress)
        progress("uploading scene");
    SceneRenderer once(*this, scene);
    return once.render(o, progress);
}

std::vector<DeviceInfo> listDevices() {
    vk::Instance instance(false, {});
    std::vector<DeviceInfo> infos;
    const auto devices = instance.physicalDevices();
    for (uint32_t i = 0; i < devices.size(); ++i)
        infos.push_back(instance.describe(devices[i], i));
    return infos;
}

} // namespace penumbra
