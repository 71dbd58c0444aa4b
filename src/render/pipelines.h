#pragma once
// Every pipeline of the frame (design.md §2), created once per Renderer. The visibility pass
// has one pipeline per technique, made on first use with TECHNIQUE as a specialization
// constant, so adding a technique adds a shader function and a table row, not a pass.
#include "penumbra/settings.h"
#include "vk/pipelines.h"

#include <map>
#include <string_view>
#include <tuple>

namespace penumbra::render {

class FramePipelines {
public:
    explicit FramePipelines(const vk::Context& ctx);

    const vk::Context& ctx;
    vk::PipelineLayout shadowLayout, gbufferLayout, screenLayout, exportLayout, probeLayout;
    vk::PipelineLayout peelLayout, midpointLayout; // second-depth shadow maps
    vk::PipelineLayout shadowMaskLayout;           // alpha-tested casters
    vk::PipelineHandle shadowOrtho;       // depth clamp on: casters before the near plane clamp
    vk::PipelineHandle shadowPerspective; // depth clamp off
    vk::PipelineHandle shadowMaskOrtho, shadowMaskPerspective; // alpha-tested casters
    vk::PipelineHandle peelOrtho, peelPerspective, midpoint;
    vk::PipelineHandle gbuffer, composite, exportGBuffer;

    // Pipelines per specialization: technique, pcf.filter and bias.receiver (choice indices).
    VkPipeline visibility(Technique technique, uint32_t filter, uint32_t receiver);
    VkPipeline probe(Technique technique, uint32_t filter); // filter_probe.comp (parity tests)

private:
    using Key = std::tuple<Technique, uint32_t, uint32_t>;
    VkPipeline specialized(std::map<Key, vk::PipelineHandle>& cache,
                           const vk::PipelineLayout& layout, std::string_view shader,
                           const Key& key);
    std::map<Key, vk::PipelineHandle> mVisibility, mProbe;
};

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;

} // namespace penumbra::render
