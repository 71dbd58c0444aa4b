#include "penumbra/renderer.h"

#include "core/projection.h"
#include "penumbra/error.h"
#include "render/frame.h"
#include "render/frame_data.h"
#include "render/renderer_impl.h"
#include "vk/context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace penumbra {

namespace {

size_t shadowCasterCount(const Scene& scene) {
    size_t n = 0;
    for (const Light& l : scene.lights)
        n += castsShadowMap(l);
    return n;
}

void checkDeviceLimits(const vk::Context& ctx, const RenderOptions& o, size_t shadowLights) {
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
    // Bytes per pixel: G-buffer 16, visibility 4 per light, colour 4, export 32, readback copy.
    const double pixels = double(o.width) * double(o.height);
    const double shadowBytes = double(o.shadowMapSize) * o.shadowMapSize * 4.0 *
                               double(shadowLights) *
                               (o.technique == Technique::SecondDepth ? 3.0 : 1.0);
    const double need =
        pixels * (16 + 36 + 2 * 4.0 * double(std::max<size_t>(shadowLights, 1)) + 36) + shadowBytes;
    const double have = static_cast<double>(ctx.deviceLocalHeapBytes());
    if (need > 0.8 * have)
        throw InputError(shadowBytes > pixels * 100 ? "--shadow-map-size" : "--width",
                         fmt::format("this render needs {:.1f} GiB of device memory; the device "
                                     "has {:.1f} GiB",
                                     need / (1 << 30), have / (1 << 30)));
}

// Near, far and the world size of one uv unit (perspective: at unit distance), for the
// techniques that reason in light-space distances (PCSS).
glm::vec4 lightFrustum(const LightProjection* shadow) {
    if (!shadow)
        return glm::vec4(0.0f, 1.0f, 1.0f, 1.0f);
    const glm::vec2 worldPerUv =
        shadow->perspective
            ? glm::vec2(2.0f * std::tan(0.5f * shadow->yfov))
            : glm::vec2(shadow->window.y - shadow->window.x, shadow->window.w - shadow->window.z);
    return {shadow->nearPlane, shadow->farPlane, worldPerUv};
}

gpu::LightData lightData(const Light& light, const LightProjection* shadow, int layer,
                         const ParameterValues& params) {
    const float type = light.type == LightType::Directional ? LIGHT_DIRECTIONAL
                       : light.type == LightType::Spot      ? LIGHT_SPOT
                                                            : LIGHT_POINT;
    return {.shadowMatrix = shadow ? textureMatrix() * shadow->viewProj : glm::mat4(1.0f),
            .positionType = glm::vec4(light.position, type),
            .directionRange = glm::vec4(glm::normalize(light.direction), light.range),
            .colorIntensity = glm::vec4(light.color, light.intensity),
            .cone = {std::cos(light.outerConeAngle), std::cos(light.innerConeAngle),
                     shadow ? shadow->texelWorldSize : 0.0f, static_cast<float>(layer)},
            .bias = {static_cast<float>(params.number("bias.constant")),
                     static_cast<float>(params.number("bias.slope")),
                     static_cast<float>(params.number("bias.normal")),
                     shadow && shadow->perspective ? 1.0f : 0.0f},
            .frustum = lightFrustum(shadow),
            .shape = {light.type == LightType::Directional
                          ? std::tan(0.5f * glm::radians(light.angularDiameter))
                          : light.radius,
                      0.0f, 0.0f, 0.0f}};
}

vk::Buffer hostBuffer(const vk::Context& ctx, std::span<const std::byte> bytes,
                      VkBufferUsageFlags usage, const char* name) {
    vk::Buffer buffer = vk::createBuffer(ctx, bytes.size(), usage, vk::MemoryUse::Upload, name);
    std::memcpy(buffer.mapped, bytes.data(), bytes.size());
    return buffer;
}

vk::Image targetImage(const vk::Context& ctx, const char* name, VkFormat format, uint32_t w,
                      uint32_t h, VkImageUsageFlags usage, uint32_t layers = 0) {
    // layers = 0: a plain 2D image; >= 1: an array image with an array view.
    return vk::createImage(ctx, {.name = name,
                                 .format = format,
                                 .width = w,
                                 .height = h,
                                 .layers = std::max(layers, 1u),
                                 .usage = usage,
                                 .arrayView = layers > 0});
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
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
uint32_t Renderer::validationMessages() const {
    return mImpl->ctx.validationErrors() + mImpl->ctx.validationWarnings();
}

void Renderer::check(const Scene& scene, const RenderOptions& o) const {
    validate(o);
    if (scene.triangleCount() == 0)
        throw InputError(scene.name, "the scene has no triangles");
    (void)scene.camera(o.camera); // throws for an unknown camera name
    checkDeviceLimits(mImpl->ctx, o, shadowCasterCount(scene));
}

RenderResult Renderer::render(const Scene& sceneIn, const RenderOptions& o,
                              const ProgressFn& progress) {
    check(sceneIn, o);
    const vk::Context& ctx = mImpl->ctx;
    Scene scene = sceneIn;
    dropInvalidTriangles(scene); // the same rule the ground truth applies
    applyLightSizeOverrides(scene, o.lightRadiusOverride, o.lightAngleOverride);
    if (scene.triangleCount() == 0)
        throw InputError(scene.name, "the scene has no valid triangles");
    const Camera camera = scene.camera(o.camera);
    const Bounds bounds = scene.bounds();

    RenderResult result{.width = o.width, .height = o.height};
    render::FrameTargets t{.width = o.width, .height = o.height};
    std::vector<gpu::LightData> lights;
    for (uint32_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        LightShadow info{.sceneLight = i, .projection = "none"};
        const bool casts = castsShadowMap(light);
        if (casts) {
            info.visibilityIndex = static_cast<int>(t.shadows.size());
            t.shadows.push_back(
                {.light = i, .projection = fitLight(light, bounds, o.shadowMapSize)});
            const LightProjection& p = t.shadows.back().projection;
            info.projection = p.perspective ? "perspective" : "orthographic";
            info.nearPlane = p.nearPlane, info.farPlane = p.farPlane;
            info.texelWorldSize = p.texelWorldSize;
            info.worldToShadow = textureMatrix() * p.viewProj;
        }
        lights.push_back(lightData(light, casts ? &t.shadows.back().projection : nullptr,
                                   info.visibilityIndex, o.parameters));
        result.lights.push_back(info);
    }

    if (progress)
        progress("uploading scene");
    const render::GpuScene gpuScene = render::uploadScene(ctx, scene);
    const gpu::FrameData frameBlock =
        render::frameData(camera, o, static_cast<uint32_t>(lights.size()), ctx);
    t.frame = hostBuffer(ctx, std::as_bytes(std::span(&frameBlock, 1)),
                         VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "frame buffer");
    if (lights.empty())
        lights.push_back({}); // storage buffers cannot be empty; count is 0
    t.lights = hostBuffer(ctx, std::as_bytes(std::span(lights)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          "light buffer");
    t.nearest = vk::createSampler(ctx, {.filter = VK_FILTER_NEAREST});
    t.compare = vk::createSampler(
        ctx, {.filter = ctx.info().depthLinearFilter ? VK_FILTER_LINEAR : VK_FILTER_NEAREST,
              .compare = true});
    constexpr VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT;
    constexpr VkImageUsageFlags storageOut =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    for (render::ShadowView& view : t.shadows)
        view.map =
            targetImage(ctx, "--shadow-map-size", render::kDepthFormat, o.shadowMapSize,
                        o.shadowMapSize, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled);
    if (o.technique == Technique::SecondDepth)
        for (render::ShadowView& view : t.shadows) {
            view.second =
                targetImage(ctx, "--shadow-map-size", render::kDepthFormat, o.shadowMapSize,
                            o.shadowMapSize, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled);
            view.midpoint =
                targetImage(ctx, "--shadow-map-size", VK_FORMAT_R32_SFLOAT, o.shadowMapSize,
                            o.shadowMapSize, VK_IMAGE_USAGE_STORAGE_BIT | sampled);
        }
    const uint32_t w = o.width, h = o.height;
    t.depth = targetImage(ctx, "G-buffer depth", render::kDepthFormat, w, h,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled);
    t.normal = targetImage(ctx, "G-buffer normal", render::kNormalFormat, w, h,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | sampled);
    t.albedo = targetImage(ctx, "G-buffer albedo", render::kAlbedoFormat, w, h,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | sampled);
    const uint32_t layers = std::max<uint32_t>(1, static_cast<uint32_t>(t.shadows.size()));
    t.visibility =
        targetImage(ctx, "visibility", VK_FORMAT_R32_SFLOAT, w, h, storageOut | sampled, layers);
    t.color = targetImage(ctx, "colour", VK_FORMAT_R8G8B8A8_UNORM, w, h, storageOut);
    t.position = targetImage(ctx, "position", VK_FORMAT_R32G32B32A32_SFLOAT, w, h, storageOut);
    t.exportNormal = targetImage(ctx, "normal", VK_FORMAT_R32G32B32A32_SFLOAT, w, h, storageOut);

    const render::FrameSettings settings{
        .technique = o.technique,
        .filter = static_cast<uint32_t>(o.parameters.number("pcf.filter")),
        .receiver = static_cast<uint32_t>(o.parameters.number("bias.receiver")),
        .slopeBias = static_cast<float>(o.parameters.number("bias.slope")),
        .constantBias = static_cast<float>(o.parameters.number("bias.constant")),
        .shadowMapSize = o.shadowMapSize,
        .lightCount = static_cast<uint32_t>(scene.lights.size())};
    vk::GpuTimer timer(ctx, 8);
    for (uint32_t frame = 0; frame <= o.frames; ++frame) {
        if (progress)
            progress(frame == 0 ? std::string("warm-up frame")
                                : fmt::format("frame {}/{}", frame, o.frames));
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            render::recordFrame(cmd, mImpl->pipelines, gpuScene, t, settings, timer);
        });
        if (frame == 0)
            continue; // the warm-up frame pays for first-use costs
        for (const auto& [pass, ms] : timer.read()) {
            auto it = std::find_if(result.passes.begin(), result.passes.end(),
                                   [&, name = pass](const PassTime& p) { return p.pass == name; });
            if (it == result.passes.end())
                it = result.passes.insert(result.passes.end(), {.pass = pass});
            it->frameMs.push_back(ms);
        }
    }
    for (PassTime& p : result.passes)
        p.medianMs = median(p.frameMs);

    if (progress)
        progress("reading back");
    const size_t pixels = size_t{w} * h;
    const size_t bytes = pixels * (4 + 4 * layers + 16 + 16);
    vk::Buffer readback = vk::createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           vk::MemoryUse::Readback, "readback buffer");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        render::recordReadback(cmd, mImpl->pipelines, t, readback.get());
    });
    const auto* src = static_cast<const std::byte*>(readback.mapped);
    result.image.resize(pixels * 4);
    std::memcpy(result.image.data(), src, pixels * 4);
    src += pixels * 4;
    for (size_t l = 0; l < t.shadows.size(); ++l) {
        std::vector<float>& v = result.visibility.emplace_back(pixels);
        std::memcpy(v.data(), src + l * pixels * 4, pixels * 4);
    }
    src += pixels * 4 * layers;
    for (std::vector<float>* out : {&result.position, &result.normal}) {
        out->resize(pixels * 3);
        const auto* rgba = reinterpret_cast<const float*>(src);
        for (size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < 3; ++c)
                (*out)[3 * i + c] = rgba[4 * i + c];
        src += pixels * 16;
    }
    return result;
}

std::vector<DeviceInfo> listDevices() {
    vk::Instance instance(false);
    std::vector<DeviceInfo> infos;
    const auto devices = instance.physicalDevices();
    for (uint32_t i = 0; i < devices.size(); ++i)
        infos.push_back(instance.describe(devices[i], i));
    return infos;
}

} // namespace penumbra
