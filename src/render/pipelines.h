#pragma once
// Every pipeline of the frame (design.md §2), created once per Renderer. The visibility pass
// has one pipeline per technique, made on first use with TECHNIQUE as a specialization
// constant, so adding a technique adds a shader function and a table row, not a pass.
#include "penumbra/settings.h"
#include "vk/pipelines.h"

#include <map>

namespace penumbra::render {

class FramePipelines {
public:
    explicit FramePipelines(const vk::Context& ctx);

    const vk::Context& ctx;
    vk::PipelineLayout shadowLayout, gbufferLayout, screenLayout, exportLayout;
    vk::PipelineHandle shadowOrtho;       // depth clamp on: casters before the near plane clamp
    vk::PipelineHandle shadowPerspective; // depth clamp off
    vk::PipelineHandle gbuffer, composite, exportGBuffer;

    VkPipeline visibility(Technique technique);

private:
    std::map<Technique, vk::PipelineHandle> mVisibility;
};

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;

} // namespace penumbra::render
