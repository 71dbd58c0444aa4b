// SceneRenderer (include/penumbra/renderer.h): one frame, start to end.
//   1. The scene is sanitized and uploaded once (constructor), with a ring of per-frame slots.
//   2. Per render: the lights with the options' size overrides; for each light that casts a
//      shadow map, its shadow views (one, or a point light's six cube faces) and their records;
//      the camera. FrameData,
//      LightData[] and ShadowViewData[] go into the next ring slot.
//   3. Targets (the technique's maps, an array layer per view; G-buffer; visibility; colour;
//      readback) are made when the sizes or the technique's maps change, and kept otherwise.
//   4. recordFrame (render/frame.cpp) records the shadow passes and the technique's own depth
//      passes, its post passes, the G-buffer, visibility and composite; a warm-up frame, then
//      the timed frames.
//   5. recordReadback copies colour, visibility, position and normal into one buffer.
//   A technique that traces the distance field (sdf) draws no shadow map: its field is built
//   before the first frame that needs it (render/distance_field.h) and kept while the scene
//   renderer lives and sdf.resolution and sdf.thickness stay the same.
#include "bias.h"
#include "core/projection.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "render/distance_field.h"
#include "render/frame.h"
#include "render/frame_data.h"
#include "render/renderer_impl.h"
#include "vk/check.h"
#include "vk/sync.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

static_assert(penumbra::kMaxCascades == MAX_CASCADES,
              "the shaders size their cascade arrays by it");

namespace penumbra {
namespace {

// A shadow view's record: its projection, and the light's size as this view measures it (the
// techniques that reason in light-space distances, PCSS, read both).
gpu::ShadowViewData viewData(const Light& light, const LightProjection& shadow, uint32_t layer) {
    const glm::vec2 worldPerUv = shadow.perspective ? glm::vec2(2.0f * std::tan(0.5f * shadow.yfov))
                                                    : glm::vec2(shadow.window.y - shadow.window.x,
                                                                shadow.window.w - shadow.window.z);
    return {.shadowMatrix = textureMatrix() * shadow.viewProj,
            .frustum = {shadow.nearPlane, shadow.farPlane, worldPerUv},
            .texel = {shadow.texelWorldSize, shadow.perspective ? 1.0f : 0.0f,
                      static_cast<float>(layer),
                      light.type == LightType::Directional
                          ? std::tan(0.5f * glm::radians(light.angularDiameter))
                          : light.radius},
            .cascade = {std::min(shadow.splitFar, render::kNotACascade),
                        std::min(shadow.blendStart, render::kNotACascade), shadow.kernelScale,
                        0.0f},
            .moments = {shadow.receiverDepths.x, 1.0f - shadow.receiverDepths.y, 0.0f, 0.0f},
            .fromFirst = {1.0f, 1.0f, 0.0f, 0.0f}};
}

// A sun's cascade `view` as an affine map of its first cascade's (u, v), the depth shared
// (light_geometry.h, ShadowViewData::fromFirst): cascades.cpp gives them one orientation and depth
// range, which this checks rather than assumes.
glm::vec4 fromFirstCascade(const glm::mat4& first, const glm::mat4& view) {
    const glm::dmat4 d = glm::dmat4(view) * glm::inverse(glm::dmat4(first));
    const glm::dmat4 expected(glm::dvec4(d[0][0], 0, 0, 0), glm::dvec4(0, d[1][1], 0, 0),
                              glm::dvec4(0, 0, 1, 0), glm::dvec4(d[3][0], d[3][1], 0, 1));
    double off = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            off = std::max(off, std::abs(d[c][r] - expected[c][r]));
    PENUMBRA_CHECK(off <= 1e-4 * std::max({1.0, std::abs(d[0][0]), std::abs(d[1][1])}),
                   "cascades with different orientations or depth ranges");
    return glm::vec4(d[0][0], d[1][1], d[3][0], d[3][1]);
}

ShadowViewInfo viewInfo(const LightProjection& shadow, uint32_t layer,
                        const glm::mat4& worldToShadow) {
    return {.name = shadow.name,
            .layer = layer,
            .projection = shadow.perspective ? "perspective" : "orthographic",
            .nearPlane = shadow.nearPlane,
            .farPlane = shadow.farPlane,
            .texelWorldSize = shadow.texelWorldSize,
            .fovDegrees = shadow.perspective ? glm::degrees(shadow.yfov) : 0.0f,
            .cascade = shadow.splitFar < std::numeric_limits<float>::max(),
            .splitNear = shadow.splitNear,
            .splitFar = shadow.splitFar,
            .blendStart = shadow.blendStart,
            .kernelScale = shadow.kernelScale,
            .worldToShadow = worldToShadow};
}

uint32_t lightTypeOf(const Light& light) {
    return light.type == LightType::Directional ? LIGHT_DIRECTIONAL
           : light.type == LightType::Spot      ? LIGHT_SPOT
                                                : LIGHT_POINT;
}

// shading.glsl's specialisation: the lights' count and kinds when there are few enough.
std::vector<shadows::SpecConstant> sceneLightConstants(const std::vector<Light>& lights) {
    if (lights.size() > MAX_SPECIALIZED_LIGHTS)
        return {{SPEC_SCENE_LIGHTS, 0u}, {SPEC_SCENE_LIGHT_TYPES, 0u}};
    uint32_t types = 0;
    for (size_t i = 0; i < lights.size(); ++i)
        types |= lightTypeOf(lights[i]) << (2 * i);
    return {{SPEC_SCENE_LIGHTS, static_cast<uint32_t>(lights.size())},
            {SPEC_SCENE_LIGHT_TYPES, types}};
}

// The shadow pass's depth offsets, bias.constant and bias.slope (x, y): none with
// bias.mode=adaptive, whose map holds exact depths [Dou et al. 2014] (measured: a slope-scaled
// offset of even 0.5 brings back the light leaks of thin casters at grazing angles that the mode
// removes; docs/techniques.md, "Adaptive depth bias").
glm::vec2 casterDepthBias(const ParameterValues& params) {
    if (params.number("bias.mode") == BIAS_ADAPTIVE)
        return glm::vec2(0.0f);
    return {static_cast<float>(params.number("bias.constant")),
            static_cast<float>(params.number("bias.slope"))};
}

gpu::LightData lightData(const Light& light, int visibilityLayer, uint32_t firstView,
                         uint32_t viewCount, const ParameterValues& params) {
    return {
        .positionType = glm::vec4(light.position, static_cast<float>(lightTypeOf(light))),
        .directionRange = glm::vec4(glm::normalize(light.direction), light.range),
        .colorIntensity = glm::vec4(light.color, light.intensity),
        .cone = {std::cos(light.outerConeAngle), std::cos(light.innerConeAngle), 0.0f,
                 static_cast<float>(visibilityLayer)},
        .bias = {casterDepthBias(params), static_cast<float>(params.number("bias.normal")), 0.0f},
        .views = {firstView, viewCount, 0u, 0u}};
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

// What the targets were made for: a render with another key makes new ones.
struct TargetKey {
    uint32_t width, height, shadowMapSize;
    uint32_t shadowViews, shadowLights;        // map layers, visibility layers
    const shadows::TechniqueModule* technique; // its maps
    std::vector<shadows::MapFormat> formats;   // of its maps, for these parameters
    std::vector<bool> mipmapped;               // of its maps, for these parameters
    bool intermediates;                        // the viewer's: VIS_INTERMEDIATES full size
    bool operator==(const TargetKey&) const = default;
};

// Frames in flight: each render takes the next slot for its camera, lights and settings.
constexpr size_t kFramesInFlight = 2;

} // namespace

struct SceneRenderer::Impl {
    Renderer& renderer;
    Scene scene; // sanitized
    Bounds bounds;
    render::GpuScene gpu;
    std::vector<float> nearestSurface; // per scene light: from its position (spot and point)
    size_t viewCapacity = 0;           // records the view buffers hold: shadowViewCount's sum
    // visibleDepthRange() for the last camera a sun's cascades followed (compare renders every
    // row from one camera: the triangles are clipped once).
    struct VisibleDepths {
        Camera camera;
        float aspect = 0.0f;
        glm::vec2 range{1.0f, 0.0f};
    };
    std::optional<VisibleDepths> visibleDepths;
    glm::vec2 visibleDepthsFor(const Camera& c, float aspect) {
        auto same = [&](const VisibleDepths& v) {
            const Camera& k = v.camera;
            return v.aspect == aspect && k.position == c.position && k.target == c.target &&
                   k.up == c.up && k.yfov == c.yfov && k.orthographic == c.orthographic &&
                   k.ymag == c.ymag && k.znear == c.znear && k.zfar == c.zfar;
        };
        if (!visibleDepths || !same(*visibleDepths))
            visibleDepths = VisibleDepths{c, aspect, visibleDepthRange(scene, c, aspect)};
        return visibleDepths->range;
    }
    std::optional<TargetKey> key;
    render::FrameTargets targets;
    vk::Buffer readback;
    struct Slot {
        // FrameData, LightData[], ShadowViewData[], the technique's parameter block (mapped)
        vk::Buffer frame, lights, views, params;
    };
    std::array<Slot, kFramesInFlight> slots;
    size_t nextSlot = 0;
    vk::SamplerHandle nearest, compare, linear;
    // The distance field (sdf) and the settings it was built for; a 1x1x2 placeholder bound in
    // its place otherwise (every binding a shader uses must be written).
    std::optional<render::DistanceField> field;
    std::pair<uint32_t, double> fieldKey{0, 0.0};
    vk::Image fieldPlaceholder;
    const render::DistanceField& fieldFor(const ParameterValues& p, const ProgressFn& progress,
                                          bool& built);

    std::vector<glm::vec3> nearestFrom; // the positions nearestSurface was measured from

    const vk::Context& ctx() const { return renderer.mImpl->ctx; }
    void makeTargets(const TargetKey& k);
    // Everything before recording: the lights' views, the targets, the distance field, and
    // ring slot `slotIndex` filled; what the frame reports besides its pixels and times.
    struct Prepared {
        RenderResult result;
        render::FrameSettings settings;
    };
    // `intermediates`: the viewer's; the visibility pass also writes the technique's
    // intermediate results (targets.intermediates at full size).
    Prepared prepare(const RenderOptions& o, const FrameState& state, size_t slotIndex,
                     const ProgressFn& progress, bool intermediates = false);
};

const render::DistanceField&
SceneRenderer::Impl::fieldFor(const ParameterValues& p, const ProgressFn& progress, bool& built) {
    const std::pair<uint32_t, double> wanted{static_cast<uint32_t>(p.number("sdf.resolution")),
                                             p.number("sdf.thickness")};
    built = !field || fieldKey != wanted;
    if (built) {
        if (progress)
            progress(fmt::format("building the distance field ({} voxels on the longest axis)",
                                 wanted.first));
        VK_CHECK(vkDeviceWaitIdle(ctx().device())); // a frame in flight may still trace it
        field.reset();                              // its memory first
        field = render::buildDistanceField(ctx(), renderer.mImpl->pipelines, scene, wanted.first,
                                           static_cast<float>(wanted.second));
        fieldKey = wanted;
    }
    return *field;
}

void SceneRenderer::Impl::makeTargets(const TargetKey& k) {
    const vk::Context& c = ctx();
    render::FrameTargets& t = targets;
    t = {.width = k.width, .height = k.height};
    constexpr VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT;
    constexpr VkImageUsageFlags storageOut =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    constexpr VkImageUsageFlags depthTarget = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled;
    const uint32_t n = k.shadowMapSize, views = k.shadowViews;
    t.shadowDepth = render::makeViewMaps(c, shadows::MapFormat::Depth32, n, views, depthTarget);
    for (size_t m = 0; m < k.formats.size(); ++m) {
        const shadows::MapFormat format = k.formats[m];
        t.maps.push_back(render::makeViewMaps(c, format, n, views,
                                              format == shadows::MapFormat::Depth32
                                                  ? depthTarget
                                                  : VK_IMAGE_USAGE_STORAGE_BIT | sampled,
                                              k.mipmapped[m]));
    }
    t.integerPlaceholder = render::makeIntegerPlaceholder(c);
    const uint32_t w = k.width, h = k.height;
    t.depth = targetImage(c, "G-buffer depth", render::kDepthFormat, w, h, depthTarget);
    t.normal = targetImage(c, "G-buffer normal", render::kNormalFormat, w, h,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | sampled);
    t.albedo = targetImage(c, "G-buffer albedo", render::kAlbedoFormat, w, h,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | sampled);
    const uint32_t layers = std::max(1u, k.shadowLights);
    t.visibility =
        targetImage(c, "visibility", VK_FORMAT_R32_SFLOAT, w, h, storageOut | sampled, layers);
    t.intermediates =
        k.intermediates ? targetImage(c, "intermediates", VK_FORMAT_R32G32B32A32_SFLOAT, w, h,
                                      VK_IMAGE_USAGE_STORAGE_BIT | sampled, layers)
                        : targetImage(c, "intermediates placeholder", VK_FORMAT_R32G32B32A32_SFLOAT,
                                      1, 1, VK_IMAGE_USAGE_STORAGE_BIT | sampled, 1);
    t.color = targetImage(c, "colour", VK_FORMAT_R8G8B8A8_UNORM, w, h, storageOut);
    t.position = targetImage(c, "position", VK_FORMAT_R32G32B32A32_SFLOAT, w, h, storageOut);
    t.exportNormal = targetImage(c, "normal", VK_FORMAT_R32G32B32A32_SFLOAT, w, h, storageOut);
    t.nearest = nearest.get();
    t.compare = compare.get();
    t.fieldSampler = linear.get();
    const size_t pixels = size_t{w} * h;
    readback =
        vk::createBuffer(c, pixels * (4 + 4 * layers + 16 + 16), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         vk::MemoryUse::Readback, "readback buffer");
    key = k;
}

SceneRenderer::SceneRenderer(Renderer& renderer, const Scene& sceneIn)
    : mImpl(std::make_unique<Impl>(Impl{.renderer = renderer, .scene = sceneIn})) {
    Impl& m = *mImpl;
    dropInvalidTriangles(m.scene); // the same rule the ground truth applies
    if (m.scene.triangleCount() == 0)
        throw InputError(m.scene.name, "the scene has no valid triangles");
    m.bounds = m.scene.bounds();
    m.gpu = render::uploadScene(m.ctx(), m.scene);
    const size_t lightRecords =
        render::uniformCapacity(m.ctx(), sizeof(gpu::LightData), MAX_UNIFORM_LIGHTS);
    if (m.scene.lights.size() > lightRecords)
        throw InputError(m.scene.name,
                         fmt::format("it has {} lights; this device's uniform buffers hold {} "
                                     "(maxUniformBufferRange {})",
                                     m.scene.lights.size(), lightRecords,
                                     m.ctx().limits().maxUniformBufferRange));
    const size_t lightBytes = sizeof(gpu::LightData) * std::max<size_t>(m.scene.lights.size(), 1);
    size_t viewCount = 0;
    for (const Light& light : m.scene.lights) {
        viewCount += shadowViewCount(light, kMaxCascades); // room for any csm.cascades
        m.nearestSurface.push_back(castsShadowMap(light) && light.type != LightType::Directional
                                       ? nearestSurfaceDistance(m.scene, light.position)
                                       : std::numeric_limits<float>::infinity());
        m.nearestFrom.push_back(light.position);
    }
    // Room for any csm.cascades up to what the device holds: render refuses more views.
    viewCount = std::min(viewCount, render::uniformCapacity(m.ctx(), sizeof(gpu::ShadowViewData),
                                                            MAX_UNIFORM_VIEWS));
    m.viewCapacity = viewCount;
    const size_t viewBytes = sizeof(gpu::ShadowViewData) * std::max<size_t>(viewCount, 1);
    for (Impl::Slot& slot : m.slots) {
        slot.frame =
            vk::createBuffer(m.ctx(), sizeof(gpu::FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             vk::MemoryUse::Upload, "frame buffer");
        // Buffers cannot be empty: a scene without lights still gets one record.
        slot.lights = vk::createBuffer(m.ctx(), lightBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                       vk::MemoryUse::Upload, "light buffer");
        std::memset(slot.lights.mapped, 0, lightBytes);
        slot.views = vk::createBuffer(m.ctx(), viewBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                      vk::MemoryUse::Upload, "shadow view buffer");
        std::memset(slot.views.mapped, 0, viewBytes);
        slot.params =
            vk::createBuffer(m.ctx(), TECHNIQUE_BLOCK_BYTES, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             vk::MemoryUse::Upload, "technique parameter buffer");
    }
    m.nearest = vk::createSampler(m.ctx(), {});
    const VkFilter compareFilter =
        m.ctx().info().depthLinearFilter ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    m.compare = vk::createSampler(
        m.ctx(), {.magFilter = compareFilter, .minFilter = compareFilter, .compare = true});
    m.linear =
        vk::createSampler(m.ctx(), {.magFilter = VK_FILTER_LINEAR, .minFilter = VK_FILTER_LINEAR});
    m.fieldPlaceholder = render::makeFieldPlaceholder(m.ctx());
    m.ctx().submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, m.fieldPlaceholder, vk::kUndefined, vk::kComputeSampled);
    });
}

std::vector<float> SceneRenderer::distanceField(DistanceFieldInfo& info) const {
    if (!mImpl->field)
        return {};
    const render::DistanceField& f = *mImpl->field;
    info.voxels = f.layout.size;
    info.voxelSize = f.layout.voxel;
    info.origin = f.layout.origin;
    info.bytes = f.bytes();
    return render::readDistanceField(mImpl->ctx(), f);
}

SceneRenderer::~SceneRenderer() = default;

const Scene& SceneRenderer::scene() const {
    return mImpl->scene;
}

void SceneRenderer::check(const RenderOptions& o) const {
    mImpl->renderer.check(mImpl->scene, o);
}

RenderResult SceneRenderer::render(const RenderOptions& o, const ProgressFn& progress) {
    return render(o, FrameState{}, progress);
}

SceneRenderer::Impl::Prepared
SceneRenderer::Impl::prepare(const RenderOptions& o, const FrameState& state, size_t slotIndex,
                             const ProgressFn& progress, bool intermediates) {
    renderer.check(scene, o);
    Impl& m = *this;
    const vk::Context& ctx = m.ctx();
    Scene lit; // the lights with the options' sizes; the uploaded geometry stays as it is
    lit.lights = state.lights ? *state.lights : m.scene.lights;
    PENUMBRA_CHECK(lit.lights.size() == m.scene.lights.size(),
                   "a frame state must keep the scene's lights");
    applyLightSizeOverrides(lit, o.lightRadiusOverride, o.lightAngleOverride);
    for (size_t i = 0; i < lit.lights.size(); ++i) { // a light the viewer moved
        const Light& light = lit.lights[i];
        PENUMBRA_CHECK(light.type == m.scene.lights[i].type,
                       "a frame state must keep the lights' types");
        if (light.position != m.nearestFrom[i] && castsShadowMap(light) &&
            light.type != LightType::Directional) {
            m.nearestSurface[i] = nearestSurfaceDistance(m.scene, light.position);
            m.nearestFrom[i] = light.position;
        }
    }
    const Camera camera = state.camera ? *state.camera : m.scene.camera(o.camera);

    RenderResult result{.width = o.width, .height = o.height};
    std::vector<render::ShadowView> views; // every shadow view of every light, in layer order
    std::vector<gpu::ShadowViewData> viewRecords;
    std::vector<gpu::LightData> lights;
    std::vector<render::LightDispatch> shadowLights;
    const uint32_t guard = viewGuardTexels(shadows::moduleOf(o.technique), o.parameters);
    const CascadeSettings cascades{.count =
                                       static_cast<uint32_t>(o.parameters.number("csm.cascades")),
                                   .lambda = static_cast<float>(o.parameters.number("csm.lambda")),
                                   .blend = static_cast<float>(o.parameters.number("csm.blend")),
                                   .stabilize = o.parameters.number("csm.stabilize") != 0.0};
    for (uint32_t i = 0; i < lit.lights.size(); ++i) {
        const Light& light = lit.lights[i];
        LightShadow info{.sceneLight = i, .projection = "none"};
        const auto firstView = static_cast<uint32_t>(views.size());
        if (castsShadowMap(light)) {
            info.visibilityIndex = static_cast<int>(shadowLights.size());
            const Camera& follows = state.shadowCamera ? *state.shadowCamera : camera;
            const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
            const bool cascaded = light.type == LightType::Directional && cascades.count > 1;
            const ViewFitting fitting{.guardTexels = guard,
                                      .nearestSurface = m.nearestSurface[i],
                                      .camera = &follows,
                                      .aspect = aspect,
                                      .visibleDepths = cascaded
                                                           ? m.visibleDepthsFor(follows, aspect)
                                                           : glm::vec2(1.0f, 0.0f),
                                      .cascades = cascades};
            for (const LightProjection& shadow :
                 fitLightViews(light, m.bounds, o.shadowMapSize, fitting)) {
                const auto layer = static_cast<uint32_t>(views.size());
                views.push_back({.light = i, .projection = shadow});
                viewRecords.push_back(viewData(light, shadow, layer));
                if (cascaded)
                    viewRecords.back().fromFirst = fromFirstCascade(
                        viewRecords[firstView].shadowMatrix, viewRecords.back().shadowMatrix);
                info.views.push_back(viewInfo(shadow, layer, viewRecords.back().shadowMatrix));
            }
            shadowLights.push_back(
                {.push = {.light = {i, static_cast<uint32_t>(info.visibilityIndex), o.shadowMapSize,
                                    firstView}},
                 .type = lightTypeOf(light),
                 .views = static_cast<uint32_t>(views.size()) - firstView});
            info.projection =
                light.type == LightType::Point ? "cube" : info.views.front().projection;
            info.guardTexels = light.type == LightType::Point ? guard : 0;
        }
        lights.push_back(lightData(light, info.visibilityIndex, firstView,
                                   static_cast<uint32_t>(views.size()) - firstView, o.parameters));
        result.lights.push_back(info);
    }

    // fitLightViews and shadowViewCount must agree: the buffers were sized by the latter.
    if (viewRecords.size() > m.viewCapacity)
        fatal(__FILE__, __LINE__, "SceneRenderer: more shadow views than shadowViewCount counted");
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    TargetKey wanted{.width = o.width,
                     .height = o.height,
                     // A technique that draws no shadow map binds a 1x1 one.
                     .shadowMapSize = module.tracesField ? 1u : o.shadowMapSize,
                     .shadowViews = static_cast<uint32_t>(views.size()),
                     .shadowLights = static_cast<uint32_t>(shadowLights.size()),
                     .technique = &module,
                     .intermediates = intermediates};
    for (const shadows::MapDecl& map : module.maps) {
        wanted.formats.push_back(shadows::formatOf(map, o.parameters));
        wanted.mipmapped.push_back(shadows::mipmappedOf(map, o.parameters));
    }
    if (m.key != wanted) {
        if (progress)
            progress("creating targets");
        VK_CHECK(vkDeviceWaitIdle(ctx.device())); // a frame in flight may still use the old ones
        m.makeTargets(wanted);
    }
    render::FrameTargets& t = m.targets;
    t.views = views;

    Impl::Slot& slot = m.slots[slotIndex % m.slots.size()];
    gpu::FrameData frameBlock =
        render::frameData(camera, o, static_cast<uint32_t>(lights.size()), ctx);
    t.field = m.fieldPlaceholder.view.get();
    if (module.tracesField) {
        bool built = false;
        const render::DistanceField& grid = m.fieldFor(o.parameters, progress, built);
        frameBlock.fieldOrigin = glm::vec4(grid.layout.origin, grid.layout.voxel);
        frameBlock.fieldSize = glm::uvec4(grid.layout.size, 0u);
        t.field = grid.image.view.get();
        result.field = DistanceFieldInfo{.voxels = grid.layout.size,
                                         .voxelSize = grid.layout.voxel,
                                         .origin = grid.layout.origin,
                                         .bytes = grid.bytes(),
                                         .triangles = grid.triangles,
                                         .openTriangles = grid.openTriangles,
                                         .buildGpuMs = grid.buildMs,
                                         .buildPasses = grid.passMs,
                                         .buildCpuMs = grid.cpuMs,
                                         .built = built};
    }
    std::memcpy(slot.frame.mapped, &frameBlock, sizeof frameBlock);
    shadows::ParamBlock params;
    if (module.pack)
        module.pack(o.parameters, params);
    std::memcpy(slot.params.mapped, params.bytes().data(), params.bytes().size());
    if (!lights.empty())
        std::memcpy(slot.lights.mapped, lights.data(), lights.size() * sizeof(gpu::LightData));
    if (!viewRecords.empty())
        std::memcpy(slot.views.mapped, viewRecords.data(),
                    viewRecords.size() * sizeof(gpu::ShadowViewData));
    t.frame = slot.frame.get();
    t.lights = slot.lights.get();
    t.viewData = slot.views.get();
    t.params = slot.params.get();

    std::vector<shadows::SpecConstant> constants =
        shadows::visibilityConstants(*wanted.technique, o.parameters);
    if (intermediates)
        constants.push_back({SPEC_INTERMEDIATES, 1u});
    return {std::move(result),
            render::FrameSettings{.technique = wanted.technique,
                                  .constants = std::move(constants),
                                  .shadowLights = shadowLights,
                                  .sceneLights = sceneLightConstants(lit.lights),
                                  .fuseComposite = o.parameters.number("composite.fused") != 0.0,
                                  .cameraViewProj = frameBlock.viewProj,
                                  .slopeBias = casterDepthBias(o.parameters).y,
                                  .constantBias = casterDepthBias(o.parameters).x,
                                  .shadowMapSize = o.shadowMapSize}};
}

RenderResult SceneRenderer::render(const RenderOptions& o, const FrameState& state,
                                   const ProgressFn& progress) {
    Impl& m = *mImpl;
    const vk::Context& ctx = m.ctx();
    auto [result, settings] = m.prepare(o, state, m.nextSlot, progress);
    m.nextSlot = (m.nextSlot + 1) % m.slots.size();
    render::FrameTargets& t = m.targets;
    render::FramePipelines& pipelines = m.renderer.mImpl->pipelines;
    vk::GpuTimer timer(ctx, static_cast<uint32_t>(4 + shadows::kMaxPostPasses));
    for (uint32_t frame = 0; frame <= o.frames; ++frame) {
        if (progress)
            progress(frame == 0 ? std::string("warm-up frame")
                                : fmt::format("frame {}/{}", frame, o.frames));
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            render::recordFrame(cmd, pipelines, m.gpu, t, settings, timer);
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
    ctx.submitAndWait(
        [&](VkCommandBuffer cmd) { render::recordReadback(cmd, pipelines, t, m.readback.get()); });
    const size_t pixels = size_t{o.width} * o.height;
    const auto* src = static_cast<const std::byte*>(m.readback.mapped);
    result.image.resize(pixels * 4);
    std::memcpy(result.image.data(), src, pixels * 4);
    src += pixels * 4;
    for (size_t l = 0; l < settings.shadowLights.size(); ++l) {
        std::vector<float>& v = result.visibility.emplace_back(pixels);
        std::memcpy(v.data(), src + l * pixels * 4, pixels * 4);
    }
    src += pixels * 4 * t.visibility.layers;
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

const vk::Context& RendererAccess::context(const Renderer& renderer) {
    return renderer.mImpl->ctx;
}

render::FramePipelines& RendererAccess::pipelines(Renderer& renderer) {
    return renderer.mImpl->pipelines;
}

RendererAccess::LiveFrame
RendererAccess::recordFrame(SceneRenderer& scene, VkCommandBuffer cmd, const RenderOptions& options,
                            const SceneRenderer::FrameState& state, size_t slot,
                            vk::GpuTimer& timer, bool intermediates, const ProgressFn& progress) {
    SceneRenderer::Impl& m = *scene.mImpl;
    auto [result, settings] = m.prepare(options, state, slot, progress, intermediates);
    // Frames in flight share the targets: this frame's first writes wait for every command
    // submitted before it (the frame's own barriers start from "undefined").
    const VkMemoryBarrier2 previousFrames{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                                          .srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                          .srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT,
                                          .dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                          .dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT |
                                                           VK_ACCESS_2_MEMORY_WRITE_BIT};
    const VkDependencyInfo dependency{.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
                                      .memoryBarrierCount = 1,
                                      .pMemoryBarriers = &previousFrames};
    vkCmdPipelineBarrier2(cmd, &dependency);
    render::recordFrame(cmd, m.renderer.mImpl->pipelines, m.gpu, m.targets, settings, timer);
    return {std::move(result), &m.targets};
}

} // namespace penumbra
