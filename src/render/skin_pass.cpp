// The Geometry phase (render/frame.h): the `skin` pass, linear blend skinning on the GPU
// (shaders/skin.comp). It runs in the first frame after a pose (GpuScene::Skin::pending): the
// skinned vertices go from bind space to this pose's places in the vertex and positions buffers,
// which every draw of the frame and of the frames after it reads. The host placed the same
// vertices (placeSkinnedVertices) for the ground truth, the bounds and culling.
#include "render/frame.h"
#include "render/pipelines.h"
#include "skinning.h"

#include <algorithm>

namespace penumbra::render {

void addSkinPass(FrameGraph& graph, FramePipelines& p, const GpuScene& scene,
                 const FrameResources& r) {
    const GpuScene::Skin& skin = *scene.skin;
    const SkinPipeline& pipeline = p.skin();
    graph.addPass(
        {.name = "skin",
         .cost = CostGroup::Frame,
         .phase = Phase::Geometry,
         .bindings = {.layout = &pipeline.layout,
                      .bound = {{SKIN_BIND_VERTICES,
                                 graph.importBuffer("skin.vertices", skin.vertices.get())},
                                {SKIN_INFLUENCES,
                                 graph.importBuffer("skin.influences", skin.influences.get())},
                                {SKIN_JOINTS, graph.importBuffer("skin.joints", skin.joints.get())},
                                {SKIN_VERTICES, r.vertices},
                                {SKIN_POSITIONS, r.positions}}},
         .record = [&pipeline, count = skin.count](PassContext& c) {
             vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline.get());
             // Every device dispatches at least 65535 workgroups along x: larger meshes in parts.
             constexpr uint32_t kMostGroups = 65535;
             for (uint32_t first = 0; first < count; first += kMostGroups * SKIN_BLOCK) {
                 const gpu::SkinPush push{.first = first, .count = count};
                 vkCmdPushConstants(c.cmd, pipeline.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                    sizeof push, &push);
                 const uint32_t left = count - first;
                 vkCmdDispatch(c.cmd, std::min(kMostGroups, (left + SKIN_BLOCK - 1) / SKIN_BLOCK),
                               1, 1);
             }
         }});
}

} // namespace penumbra::render
