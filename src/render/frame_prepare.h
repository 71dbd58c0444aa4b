#pragma once
// The frame's preparation on the host, step by step. SceneRenderer (render/scene_renderer.cpp)
// runs them in this order before it builds the frame's graph:
//   1. lightsOf        the scene's lights with a frame state's edits and the size overrides
//   2. shadowViewsOf   each shadow-casting light's views (cascades, spot frustum, cube faces),
//                      their uniform records, its evaluation dispatch and what it reports
//   3. frameBlocks     the frame block, the technique's and the layers' parameter blocks
//   4. frameSettings   what the graph's passes read (render/frame.h)
#include "core/light_space.h"
#include "core/virtual_maps.h"
#include "frame_block.h"
#include "light_geometry.h"
#include "penumbra/renderer.h"
#include "render/frame.h"
#include "vk/context.h"

#include <functional>
#include <vector>

namespace penumbra::render {

// 1. The lights a frame sees: `edited` (a frame state's: the viewer's, a camera path's) or the
// scene's, with the options' light sizes.
std::vector<Light> lightsOf(const Scene& scene, const std::vector<Light>* edited,
                            const RenderOptions& options);

// 2. Every shadow view of every light, in layer order.
struct ShadowViews {
    std::vector<ShadowView> views;
    std::vector<gpu::ShadowViewData> records; // one per view
    std::vector<gpu::LightData> lights;       // one per scene light
    std::vector<LightDispatch> dispatches;    // one per shadow-casting light
    std::vector<LightShadow> report;          // RenderResult::lights
    // virtual.enabled: every view is a level of a light's virtual map (its record's texel.z the
    // level's first page-table entry, cascade.w its pages a side), the table's size and each
    // shadowed light's contents key (pageContentsKey).
    std::vector<VirtualLevel> levels;
    uint32_t tableEntries = 0;
    std::vector<std::pair<uint32_t, uint64_t>> contentsKeys;
};
struct ViewInputs {
    const Bounds& bounds;
    const std::vector<float>& nearestSurface; // per light: from its position (spot, point)
    const Camera& camera;                     // the one the cascades follow
    float aspect;
    // visibleDepthRange() for that camera, asked for only when a sun has cascades.
    std::function<glm::vec2()> visibleDepths;
};
ShadowViews shadowViewsOf(const std::vector<Light>& lights, const RenderOptions& options,
                          const ViewInputs& inputs);

// 3. The blocks the host writes into the frame's ring slot.
struct FrameBlocks {
    gpu::FrameData frame;
    shadows::ParamBlock technique; // its module's parameters
    // Every layer's block, at its index in shadows::allLayers() (a TECHNIQUE_BLOCK_BYTES slice
    // each of the slot's layer buffer).
    std::vector<shadows::ParamBlock> layers;
};
FrameBlocks frameBlocks(const Camera& camera, const RenderOptions& options, uint32_t lightCount,
                        const vk::Context& ctx);

// 4. What the graph's passes read.
FrameSettings frameSettings(const RenderOptions& options, const std::vector<Light>& lights,
                            const ShadowViews& views, const FrameBlocks& blocks,
                            bool intermediates);

// The shadow pass's depth offsets, bias.constant and bias.slope (x, y): none with
// bias.mode=adaptive, whose map holds exact depths [Dou et al. 2014].
glm::vec2 casterDepthBias(const ParameterValues& params);

} // namespace penumbra::render
