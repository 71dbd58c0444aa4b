#include "render/frame_prepare.h"

#include "bias.h"
#include "core/projection.h"
#include "penumbra/error.h"
#include "render/frame_data.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::render {
namespace {

// A shadow view's record: its projection, and the light's size as this view measures it (the
// techniques that reason in light-space distances, PCSS, read both).
gpu::ShadowViewData viewData(const Light& light, const LightProjection& shadow, uint32_t layer) {
    const glm::vec2 worldPerUv = shadow.perspective ? glm::vec2(2.0f * std::tan(0.5f * shadow.yfov))
                                                    : glm::vec2(shadow.window.y - shadow.window.x,
                                                                shadow.window.w - shadow.window.z);
    return {.shadowMatrix = textureMatrix() * shadow.viewProj,
            .frustum = {shadow.nearPlane, shadow.farPlane, worldPerUv},
            // texel.y: 2 marks a point light's cube face (kernelCap, light_geometry.h).
            .texel = {shadow.texelWorldSize,
                      light.type == LightType::Point ? 2.0f
                      : shadow.perspective           ? 1.0f
                                                     : 0.0f,
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

} // namespace

// Measured: a slope-scaled offset of even 0.5 brings back the light leaks of thin casters at
// grazing angles that the adaptive mode removes (docs/techniques.md, "Adaptive depth bias").
glm::vec2 casterDepthBias(const ParameterValues& params) {
    if (params.number("bias.mode") == BIAS_ADAPTIVE)
        return glm::vec2(0.0f);
    return {static_cast<float>(params.number("bias.constant")),
            static_cast<float>(params.number("bias.slope"))};
}

std::vector<Light> lightsOf(const Scene& scene, const std::vector<Light>* edited,
                            const RenderOptions& o) {
    Scene lit; // the lights with the options' sizes; the geometry is not needed
    lit.lights = edited ? *edited : scene.lights;
    PENUMBRA_CHECK(lit.lights.size() == scene.lights.size(),
                   "a frame state must keep the scene's lights");
    for (size_t i = 0; i < lit.lights.size(); ++i)
        PENUMBRA_CHECK(lit.lights[i].type == scene.lights[i].type,
                       "a frame state must keep the lights' types");
    applyLightSizeOverrides(lit, o.lightRadiusOverride, o.lightAngleOverride);
    return lit.lights;
}

ShadowViews shadowViewsOf(const std::vector<Light>& lights, const RenderOptions& o,
                          const ViewInputs& in) {
    ShadowViews out;
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    // Cascades' and cube faces' guard bands (virtual maps: the widest; fitted views: the
    // light's size may narrow them): the soft members cap a cube face's kernels apart.
    const uint32_t cascadeGuard = viewGuardTexels(module, o.parameters),
                   cubeGuard = viewGuardTexels(module, o.parameters, true);
    const CascadeSettings cascades{.count =
                                       static_cast<uint32_t>(o.parameters.number("csm.cascades")),
                                   .lambda = static_cast<float>(o.parameters.number("csm.lambda")),
                                   .blend = static_cast<float>(o.parameters.number("csm.blend")),
                                   .stabilize = o.parameters.number("csm.stabilize") != 0.0};
    const VirtualSettings virtualMaps = VirtualSettings::of(o.parameters);
    const bool virtualViews =
        virtualMaps.enabled && shadows::moduleOf(o.technique).readsVirtualMaps;
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        LightShadow info{.sceneLight = i, .projection = "none"};
        const uint32_t guard = light.type == LightType::Point ? cubeGuard : cascadeGuard;
        const auto firstView = static_cast<uint32_t>(out.views.size());
        if (castsShadowMap(light) && virtualViews) {
            info.visibilityIndex = static_cast<int>(out.dispatches.size());
            // A cube face's guard band in its finest level's texels, wide enough in its
            // coarsest (one page): a kernel at a face's edge reads that face at every level.
            const std::vector<VirtualLevel> levels =
                virtualLevels(light, i, in.bounds, in.camera.position, virtualMaps,
                              {.guard = guard * virtualMaps.pagesPerSide(),
                               .nearestSurface = in.nearestSurface[i]},
                              out.tableEntries);
            for (const VirtualLevel& level : levels) {
                out.views.push_back({.light = i, .projection = level.projection});
                out.records.push_back(viewData(light, level.projection, level.tableOffset));
                out.records.back().cascade.w = static_cast<float>(level.pagesPerSide);
                // A sun's levels share the finest's orientation and depth (the page marking
                // maps its uv to theirs); a spot's or a face's mips share its projection.
                if (light.type == LightType::Directional)
                    out.records.back().fromFirst = fromFirstCascade(
                        out.records[firstView].shadowMatrix, out.records.back().shadowMatrix);
                info.views.push_back(
                    viewInfo(level.projection, level.tableOffset, out.records.back().shadowMatrix));
            }
            out.contentsKeys.emplace_back(
                i, pageContentsKey(light, levels, virtualMaps, casterDepthBias(o.parameters)));
            out.levels.insert(out.levels.end(), levels.begin(), levels.end());
            out.dispatches.push_back(
                {.push = {.light = {i, static_cast<uint32_t>(info.visibilityIndex),
                                    virtualMaps.size, firstView}},
                 .type = lightTypeOf(light),
                 .views = static_cast<uint32_t>(levels.size()),
                 .sized = light.hasSize()});
            info.projection = "virtual";
        } else if (castsShadowMap(light)) {
            info.visibilityIndex = static_cast<int>(out.dispatches.size());
            const bool cascaded = light.type == LightType::Directional && cascades.count > 1;
            const GuardBand band = viewGuardBand(module, o.parameters, light);
            const ViewFitting fitting{.guard = band,
                                      .nearestSurface = in.nearestSurface[i],
                                      .camera = &in.camera,
                                      .aspect = in.aspect,
                                      .visibleDepths =
                                          cascaded ? in.visibleDepths() : glm::vec2(1.0f, 0.0f),
                                      .cascades = cascades};
            for (const LightProjection& shadow :
                 fitLightViews(light, in.bounds, o.shadowMapSize, fitting)) {
                const auto layer = static_cast<uint32_t>(out.views.size());
                out.views.push_back({.light = i, .projection = shadow});
                out.records.push_back(viewData(light, shadow, layer));
                if (cascaded)
                    out.records.back().fromFirst = fromFirstCascade(
                        out.records[firstView].shadowMatrix, out.records.back().shadowMatrix);
                info.views.push_back(viewInfo(shadow, layer, out.records.back().shadowMatrix));
            }
            out.dispatches.push_back(
                {.push = {.light = {i, static_cast<uint32_t>(info.visibilityIndex), o.shadowMapSize,
                                    firstView}},
                 .type = lightTypeOf(light),
                 .views = static_cast<uint32_t>(out.views.size()) - firstView,
                 .sized = light.hasSize()});
            info.projection =
                light.type == LightType::Point ? "cube" : info.views.front().projection;
            info.guardTexels = light.type == LightType::Point
                                   ? static_cast<uint32_t>(
                                         band.cubeFaceTexels(static_cast<float>(o.shadowMapSize)))
                                   : 0;
        }
        out.lights.push_back(lightData(light, info.visibilityIndex, firstView,
                                       static_cast<uint32_t>(out.views.size()) - firstView,
                                       o.parameters));
        out.report.push_back(info);
    }
    return out;
}

FrameBlocks frameBlocks(const Camera& camera, const RenderOptions& o, uint32_t lightCount,
                        const vk::Context& ctx) {
    FrameBlocks b{.frame = frameData(camera, o, lightCount, ctx)};
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    if (module.pack)
        module.pack(o.parameters, b.technique);
    b.layers.resize(shadows::allLayers().size());
    for (size_t i = 0; i < b.layers.size(); ++i)
        if (shadows::allLayers()[i]->pack)
            shadows::allLayers()[i]->pack(o.parameters, b.layers[i]);
    return b;
}

FrameSettings frameSettings(const RenderOptions& o, const std::vector<Light>& lights,
                            const ShadowViews& views, const FrameBlocks& blocks,
                            bool intermediates) {
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    std::vector<shadows::SpecConstant> constants =
        shadows::visibilityConstants(module, o.parameters);
    if (intermediates)
        constants.push_back({SPEC_INTERMEDIATES, 1u});
    const glm::vec2 bias = casterDepthBias(o.parameters);
    return {.technique = &module,
            .params = &o.parameters,
            .constants = std::move(constants),
            .shadowLights = views.dispatches,
            .layers = shadows::enabledLayers(o.parameters),
            .sceneLights = sceneLightConstants(lights),
            .fuseComposite = o.parameters.number("composite.fused") != 0.0,
            .intermediates = intermediates,
            .readback = false,
            .motion = o.motion || shadows::keepsHistory(o.parameters),
            .cameraViewProj = blocks.frame.viewProj,
            .slopeBias = bias.y,
            .constantBias = bias.x,
            .sizes = {.width = o.width,
                      .height = o.height,
                      .shadowMapSize = shadows::drawnMapSize(module, o.shadowMapSize),
                      .shadowViews = static_cast<uint32_t>(views.views.size()),
                      .shadowLights = static_cast<uint32_t>(views.dispatches.size())},
            .views = views.views,
            .virtualMaps = !views.levels.empty(),
            .pageSize = static_cast<uint32_t>(o.parameters.number("virtual.pageSize"))};
}

} // namespace penumbra::render
