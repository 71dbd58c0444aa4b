#pragma once
// What the frame graph's tests (test_frame_graph.cpp, test_frame_graph_checks.cpp) declare: a
// screen-sized R32F image, a pass of a phase with its uses (timed when named), the planned
// order by name, and small frame sizes.
#include "gpu_fixture.h"
#include "render/frame_graph.h"
#include "vk/context.h"

#include <optional>
#include <string>
#include <vector>

namespace penumbra::test {
inline const vk::Context& context() {
    return sharedRenderer().context();
}

inline render::ImageDecl screenImage(std::string name,
                                     render::Lifetime lifetime = render::Lifetime::PerFrame) {
    return {.name = std::move(name),
            .size = render::SizeClass::Screen,
            .format = VK_FORMAT_R32_SFLOAT,
            .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
            .lifetime = lifetime};
}

inline render::PassDecl pass(std::string name, render::Phase phase, std::vector<render::Use> uses) {
    const bool timed = !name.empty();
    return {.name = std::move(name),
            .cost = timed ? std::optional(CostGroup::PerPixel) : std::nullopt,
            .phase = phase,
            .uses = std::move(uses),
            .record = [](render::PassContext&) {}};
}

// The planned passes' names, in order.
inline std::vector<std::string> order(render::FrameGraph& graph) {
    std::vector<std::string> names;
    for (const render::PlannedPass& p : graph.plan())
        names.push_back(graph.passes()[p.pass].name);
    return names;
}

inline const render::FrameSizes kSizes{
    .width = 8, .height = 4, .shadowMapSize = 16, .shadowViews = 2, .shadowLights = 1};

} // namespace penumbra::test
