#include "render/frame_data.h"

#include "core/projection.h"
#include "core/virtual_maps.h"
#include "shadows/technique.h"

#include <algorithm>
#include <cmath>

namespace penumbra::render {

gpu::FrameData frameData(const Camera& camera, const RenderOptions& o, uint32_t lightCount,
                         const vk::Context& ctx) {
    const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
    const glm::mat4 view = lookAt(camera.position, camera.target, camera.up);
    const glm::mat4 proj = cameraProjection(camera, aspect);
    const glm::mat4 viewProj = proj * view;
    // Multiplying and inverting in double keeps reconstructed positions accurate far from the
    // origin.
    const glm::dmat4 inv = glm::inverse(glm::dmat4(proj) * glm::dmat4(view));
    const ParameterValues& params = o.parameters;
    gpu::FrameData f{
        .viewProj = viewProj,
        .invViewProj = glm::mat4(inv),
        .position = glm::vec4(camera.position, 1.0f),
        .imageSize = {o.width, o.height, lightCount, 0},
        .composite = {static_cast<float>(params.number("composite.ambient")),
                      static_cast<float>(params.number("composite.shadowIntensity")),
                      std::exp2(static_cast<float>(params.number("composite.exposure"))), 0},
        .background = {0.55f, 0.65f, 0.8f, 1.0f}};
    f.cameraForward = glm::vec4(glm::normalize(camera.target - camera.position), 0.0f);
    f.previousViewProj = viewProj; // no motion unless the renderer knows the last frame's
    f.motion = glm::uvec4(0u);
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    shadows::setSharedSettings(f, module, params, ctx.info().depthLinearFilter,
                               ctx.limits().subTexelPrecisionBits);
    const VirtualSettings v = VirtualSettings::of(params);
    if (v.enabled && module.readsVirtualMaps) {
        f.virtualPages = {v.pageSize, v.poolPagesPerSide(), v.localLevels(), 1u};
        // The pages a filter reads around its receiver; a comparison sampler reads the pool's
        // neighbouring pages instead: the bilinear comparison is done by hand.
        const double reach = shadows::readReachTexels(module, params);
        f.virtualLod = {v.levelBias(o.width, o.height), static_cast<float>(std::ceil(reach)), 0.0f,
                        0.0f};
        f.biasMode.y = 0u;
    }
    return f;
}

gpu::ShadowViewData probeViewData(const ProbeLight& light) {
    return {.shadowMatrix = glm::mat4(1.0f),
            .frustum = {light.nearPlane, light.farPlane, light.worldPerUv.x, light.worldPerUv.y},
            .texel = {0.0f,
                      light.cubeFace      ? 2.0f
                      : light.perspective ? 1.0f
                                          : 0.0f,
                      0.0f, light.size},
            .cascade = {kNotACascade, kNotACascade, 1.0f, 0.0f},
            .fromFirst = {1.0f, 1.0f, 0.0f, 0.0f}};
}

} // namespace penumbra::render
