// The PerLight and Composite phases (render/frame.h). Each shadow-casting light is evaluated by
// the base technique (one visibility dispatch, "visibility"), the screen passes its module adds
// (shadows::ScreenPassDecl, timed under their names: smrt's checkerboard fill as "visibility",
// its filter as "filter"), and then by each enabled layer (one dispatch of the layer's shader,
// timed under the layer's name), which multiplies into the light's visibility layer. The composite
// shades every pixel from the lights' layers: fused into the last light's visibility dispatch
// ("composite", composite.fused) when no screen pass or layer runs after it, else composite.comp
// on its own.
#include "checkerboard.h"
#include "render/frame.h"
#include "render/pass_utils.h"
#include "vk/pipelines.h"
#include "vk/sync.h"

#include <algorithm>

namespace penumbra::render {
namespace {

// The visibility dispatch of one light with shadow views, into its layer of the visibility
// image; `fused`: it also shades every pixel into the colour image (the last light's).
// `checkerboard`: which of its pixels it traces (CHECKERBOARD_*).
void dispatchVisibility(PassContext& c, FramePipelines& p, const FrameSettings& s,
                        const FrameInputs& in, const FrameResources& r, const LightDispatch& light,
                        bool fused, uint32_t checkerboard = CHECKERBOARD_OFF) {
    std::vector<shadows::SpecConstant> constants = s.constants;
    constants.push_back({SPEC_LIGHT_TYPE, light.type});
    constants.push_back({SPEC_LIGHT_VIEWS, light.views});
    if (checkerboard != CHECKERBOARD_OFF)
        constants.push_back({SPEC_CHECKERBOARD, checkerboard});
    if (fused) {
        constants.insert(constants.end(), s.sceneLights.begin(), s.sceneLights.end());
        constants.push_back({SPEC_FUSED_COMPOSITE, 1u});
    }
    vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.visibility(constants));
    vk::PushDescriptors descriptors;
    r.filtered.write(descriptors, c, in.nearest, in.compare);
    descriptors.uniformBuffer(BIND_FRAME, in.frame)
        .uniformBuffer(VIS_LIGHTS, in.lights)
        .sampled(VIS_GBUFFER_DEPTH, c.image(r.gbufferDepth).view(), in.nearest)
        .sampled(VIS_GBUFFER_NORMAL, c.image(r.gbufferNormal).view(), in.nearest)
        .uniformBuffer(TECH_PARAMS, in.params)
        .storageImage(VIS_OUT, c.image(r.visibility).view())
        .uniformBuffer(VIS_VIEWS, in.views)
        .sampled(TECH_FIELD, c.image(r.field).view(), in.fieldSampler)
        .storageImage(VIS_INTERMEDIATES, c.image(r.intermediates).view())
        .sampled(VIS_GBUFFER_ALBEDO, c.image(r.gbufferAlbedo).view(), in.nearest)
        .storageImage(VIS_COLOR, c.image(r.color).view())
        .storageBuffer(TECH_PAGE_TABLE, c.buffer(r.pageTable))
        .storageBuffer(VIS_TRACE_LIST, c.buffer(r.traceList))
        .push(p.ctx, c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.visibilityLayout);
    vkCmdPushConstants(c.cmd, p.visibilityLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       sizeof light.push, &light.push);
    if (checkerboard == CHECKERBOARD_LIST)
        vkCmdDispatchIndirect(c.cmd, c.buffer(r.traceList), 0);
    else if (checkerboard == CHECKERBOARD_EVEN)
        vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(gpu::checkerboardRows(s.sizes.height)),
                      1);
    else
        vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(s.sizes.height), 1);
}

// One dispatch over the image (`rows` high: the image's height unless given) on the layers'
// pipeline layout for one light: every binding written, the block at `paramsOffset` of the layer
// buffer, `results` at LAYER_RESULTS.
void dispatchOnLayerLayout(PassContext& c, FramePipelines& p, const FrameSettings& s,
                           const FrameInputs& in, const FrameResources& r, VkPipeline pipeline,
                           VkDeviceSize paramsOffset, ResourceId results,
                           const LightDispatch& light, uint32_t rows = 0) {
    vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vk::PushDescriptors()
        .uniformBuffer(BIND_FRAME, in.frame)
        .uniformBuffer(LAYER_LIGHTS, in.lights)
        .sampled(LAYER_GBUFFER_DEPTH, c.image(r.gbufferDepth).view(), in.nearest)
        .sampled(LAYER_GBUFFER_NORMAL, c.image(r.gbufferNormal).view(), in.nearest)
        .storageImage(LAYER_VISIBILITY, c.image(r.visibility).view())
        .uniformBuffer(LAYER_PARAMS, in.layerParams, paramsOffset, TECHNIQUE_BLOCK_BYTES)
        .storageImage(LAYER_RESULTS, c.image(results).view())
        .storageBuffer(LAYER_TRACE_LIST, c.buffer(r.traceList))
        .push(p.ctx, c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layerLayout);
    vkCmdPushConstants(c.cmd, p.layerLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       sizeof light.push, &light.push);
    vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(rows > 0 ? rows : s.sizes.height), 1);
}

// One layer's dispatch for one light: reads the G-buffer and the light's visibility layer and
// writes it back multiplied by what the layer finds.
void dispatchLayer(PassContext& c, FramePipelines& p, const FrameSettings& s, const FrameInputs& in,
                   const FrameResources& r, const shadows::LayerModule& layer,
                   const LightDispatch& light) {
    const std::vector<shadows::SpecConstant> constants{
        {SPEC_LIGHT_TYPE, light.type}, {SPEC_INTERMEDIATES, s.intermediates ? 1u : 0u}};
    dispatchOnLayerLayout(c, p, s, in, r, p.layer(layer.shader, constants),
                          TECHNIQUE_BLOCK_BYTES * shadows::layerIndex(layer), r.layerResults,
                          light);
}

Access accessOf(shadows::ScreenAccess access) {
    switch (access) {
    case shadows::ScreenAccess::Read:
        return Access::ComputeRead;
    case shadows::ScreenAccess::Write:
        return Access::ComputeWrite;
    case shadows::ScreenAccess::ReadWrite:
        break;
    }
    return Access::ComputeReadWrite;
}

// What a screen pass binds at LAYER_RESULTS (shadows::screenPassesOf checked it is one of these).
ResourceId resultsOf(const FrameResources& r, const shadows::ScreenPassDecl& pass) {
    return pass.results == shadows::kScreenScratch ? r.screenScratch : r.layerResults;
}

// One dispatch of a technique's screen pass for one light, `rows` high (the image's unless
// given).
void dispatchScreenPass(PassContext& c, FramePipelines& p, const FrameSettings& s,
                        const FrameInputs& in, const FrameResources& r,
                        const shadows::ScreenPassDecl& pass, const LightDispatch& light,
                        uint32_t rows = 0) {
    const std::vector<shadows::SpecConstant> constants =
        pass.constants ? pass.constants(*s.params, light.type, light.sized)
                       : std::vector<shadows::SpecConstant>{};
    dispatchOnLayerLayout(c, p, s, in, r, p.layer(pass.shader, constants), 0, resultsOf(r, pass),
                          light, rows);
}

// What a pass on the layers' pipeline layout binds: `visibility` and `results` (at
// LAYER_RESULTS) as it uses them.
std::vector<Use> layerLayoutUses(const FrameResources& r, Access visibility, ResourceId results,
                                 Access resultsAccess) {
    return {{r.frame, Access::UniformRead},
            {r.lights, Access::UniformRead},
            {r.layerParams, Access::UniformRead},
            {r.gbufferDepth, Access::ComputeSampled},
            {r.gbufferNormal, Access::ComputeSampled},
            {r.visibility, visibility},
            {results, resultsAccess}};
}

// What every visibility dispatch binds; `visibility` as the pass uses it.
std::vector<Use> visibilityUses(const FrameResources& r, Access visibility) {
    std::vector<Use> uses{{r.frame, Access::UniformRead},
                          {r.lights, Access::UniformRead},
                          {r.views, Access::UniformRead},
                          {r.params, Access::UniformRead},
                          {r.pageTable, Access::ComputeRead},
                          {r.gbufferDepth, Access::ComputeSampled},
                          {r.gbufferNormal, Access::ComputeSampled},
                          {r.gbufferAlbedo, Access::ComputeSampled},
                          {r.field, Access::ComputeSampled},
                          {r.visibility, visibility},
                          {r.intermediates, Access::ComputeWrite},
                          {r.color, Access::ComputeWrite}}; // bound by every dispatch
    r.filtered.addUses(uses);
    return uses;
}

// Checkerboard tracing's trace list emptied (checkerboard.h): its head's group count, and the
// rows its groups take on this image.
void addListEmptying(FrameGraph& graph, const FrameSettings& s, const FrameResources& r) {
    graph.addPass({.name = "",
                   .phase = Phase::PerLight,
                   .uses = {{r.traceList, Access::TransferWrite}},
                   .record = [list = r.traceList, &s](PassContext& c) {
                       const gpu::TraceListHead empty{
                           .groupsY = gpu::checkerboardListRows(
                               traceListEntries(s.sizes.width, s.sizes.height)),
                           .groupsZ = 1};
                       vkCmdUpdateBuffer(c.cmd, c.buffer(list), 0, sizeof empty, &empty);
                   }});
}

// Checkerboard tracing's passes for one light after its even pixels and its list's emptying: the
// module's fill (over the even pixels' rows: the odd pixels filled or listed), then the list
// traced, timed as "visibility" with the even pixels' dispatch: the technique's whole cost.
void addFillAndList(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                    const FrameInputs& in, const FrameResources& r,
                    const shadows::ScreenPassDecl& fill, size_t light) {
    std::vector<Use> fillUses = layerLayoutUses(r, accessOf(fill.visibility), resultsOf(r, fill),
                                                accessOf(fill.resultsAccess));
    fillUses.push_back({r.traceList, Access::ComputeReadWrite});
    graph.addPass({.name = std::string(fill.name),
                   .cost = CostGroup::PerPixel,
                   .phase = Phase::PerLight,
                   .uses = fillUses,
                   .record = [&p, &s, &in, r, fill, light](PassContext& c) {
                       dispatchScreenPass(c, p, s, in, r, fill, s.shadowLights[light],
                                          gpu::checkerboardRows(s.sizes.height));
                   }});
    std::vector<Use> trace = visibilityUses(r, Access::ComputeWrite);
    trace.push_back({r.traceList, Access::IndirectRead});
    graph.addPass({.name = "visibility",
                   .cost = CostGroup::PerPixel,
                   .phase = Phase::PerLight,
                   .uses = trace,
                   .record = [&p, &s, &in, r, light](PassContext& c) {
                       dispatchVisibility(c, p, s, in, r, s.shadowLights[light], false,
                                          CHECKERBOARD_LIST);
                   }});
}

// A layer that keeps a history (the temporal layer): one dispatch per light on its own layout,
// which reads the G-buffer's motion vectors and last frame's history and writes this frame's.
void addHistoryLayer(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                     const FrameInputs& in, const FrameResources& r,
                     const shadows::LayerModule& layer, size_t index) {
    const ResourceId history = r.layerHistory[index], previous = r.layerHistoryPrevious[index];
    graph.addPass(
        {.name = std::string(layer.name),
         .cost = CostGroup::PerPixel,
         .phase = Phase::PerLight,
         .uses = {{r.frame, Access::UniformRead},
                  {r.layerParams, Access::UniformRead},
                  {r.gbufferDepth, Access::ComputeSampled},
                  {r.gbufferNormal, Access::ComputeSampled},
                  {r.gbufferMotion, Access::ComputeSampled},
                  {r.visibility, Access::ComputeReadWrite},
                  {previous, Access::ComputeSampled},
                  {history, Access::ComputeWrite}}, // read after its own writes only
         .record = [&p, &s, &in, r, &layer, history, previous](PassContext& c) {
             const FramePipelines::HistoryLayerPipeline& pipeline = p.historyLayer(layer.shader);
             vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.blend.get());
             vk::PushDescriptors()
                 .uniformBuffer(BIND_FRAME, in.frame)
                 .sampled(LAYER_GBUFFER_DEPTH, c.image(r.gbufferDepth).view(), in.nearest)
                 .sampled(LAYER_GBUFFER_NORMAL, c.image(r.gbufferNormal).view(), in.nearest)
                 .storageImage(LAYER_VISIBILITY, c.image(r.visibility).view())
                 .uniformBuffer(LAYER_PARAMS, in.layerParams,
                                TECHNIQUE_BLOCK_BYTES * shadows::layerIndex(layer),
                                TECHNIQUE_BLOCK_BYTES)
                 .sampled(LAYER_MOTION, c.image(r.gbufferMotion).view(), in.nearest)
                 .sampled(LAYER_HISTORY_PREVIOUS, c.image(previous).view(), in.nearest)
                 .storageImage(LAYER_HISTORY, c.image(history).view())
                 .push(p.ctx, c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout);
             const auto everyLight = [&] {
                 for (const LightDispatch& light : s.shadowLights) {
                     vkCmdPushConstants(c.cmd, pipeline.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT,
                                        0, sizeof light.push, &light.push);
                     vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(s.sizes.height), 1);
                 }
             };
             everyLight(); // the blends into the history, every visibility read as it was
             vk::memoryBarrier(
                 c.cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
             vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.resolve.get());
             everyLight(); // ... then copied into it
         }});
}

} // namespace

void addLightPasses(FrameGraph& graph, FramePipelines& p, const FrameSettings& s,
                    const FrameInputs& in, const FrameResources& r) {
    // With no layer after it, the last light's visibility dispatch shades too: one pass fewer
    // over the G-buffer, and its position and normal reconstructed once.
    const std::vector<shadows::ScreenPassDecl> screenPasses = screenPassesOf(s);
    const shadows::ScreenPassDecl* fill = shadows::checkerboardFill(screenPasses);
    const bool checkerboard = fill && !s.shadowLights.empty();
    const bool fused =
        s.fuseComposite && !s.shadowLights.empty() && s.layers.empty() && screenPasses.empty();
    const size_t separate = fused ? s.shadowLights.size() - 1 : s.shadowLights.size();
    if (checkerboard) // the first light's list, emptied before the pass that binds it
        addListEmptying(graph, s, r);
    std::vector<Use> uses = visibilityUses(r, Access::ComputeWrite);
    if (checkerboard)
        uses.push_back({r.traceList, Access::ComputeRead});
    graph.addPass({.name = "visibility",
                   .cost = CostGroup::PerPixel,
                   .phase = Phase::PerLight,
                   .uses = uses,
                   .record = [&p, &s, &in, r, separate, checkerboard](PassContext& c) {
                       for (size_t i = 0; i < separate; ++i)
                           dispatchVisibility(c, p, s, in, r, s.shadowLights[i], false,
                                              checkerboard ? CHECKERBOARD_EVEN : CHECKERBOARD_OFF);
                   }});
    for (size_t i = 0; checkerboard && i < s.shadowLights.size(); ++i) {
        if (i > 0) // the lights take turns at one list
            addListEmptying(graph, s, r);
        addFillAndList(graph, p, s, in, r, *fill, i);
    }
    // The module's other screen passes, each one pass over the lights it runs for.
    for (const shadows::ScreenPassDecl& pass : screenPasses) {
        if (pass.fillsCheckerboard)
            continue;
        graph.addPass({.name = std::string(pass.name),
                       .cost = CostGroup::PerPixel,
                       .phase = Phase::PerLight,
                       .uses = layerLayoutUses(r, accessOf(pass.visibility), resultsOf(r, pass),
                                               accessOf(pass.resultsAccess)),
                       .record = [&p, &s, &in, r, pass](PassContext& c) {
                           for (const LightDispatch& light : s.shadowLights)
                               if (!pass.runsFor || pass.runsFor(*s.params, light.type))
                                   dispatchScreenPass(c, p, s, in, r, pass, light);
                       }});
    }
    for (size_t l = 0; l < s.layers.size(); ++l) {
        const shadows::LayerModule* layer = s.layers[l];
        if (layer->history) {
            addHistoryLayer(graph, p, s, in, r, *layer, l);
            continue;
        }
        if (layer->translucentMethod) {
            addTranslucentLayerPass(graph, p, s, in, r, *layer);
            continue;
        }
        graph.addPass({.name = std::string(layer->name),
                       .cost = CostGroup::PerPixel,
                       .phase = Phase::PerLight,
                       .uses = layerLayoutUses(r, Access::ComputeReadWrite, r.layerResults,
                                               Access::ComputeWrite),
                       .record = [&p, &s, &in, r, layer](PassContext& c) {
                           for (const LightDispatch& light : s.shadowLights)
                               dispatchLayer(c, p, s, in, r, *layer, light);
                       }});
    }
    if (fused) {
        // The last light reads the earlier lights' layers as it writes its own.
        graph.addPass({.name = "composite",
                       .cost = CostGroup::PerPixel,
                       .phase = Phase::Composite,
                       .uses = visibilityUses(r, Access::ComputeReadWrite),
                       .record = [&p, &s, &in, r](PassContext& c) {
                           dispatchVisibility(c, p, s, in, r, s.shadowLights.back(), true);
                       }});
        return;
    }
    // The translucent layer's tint, or (unread) the visibility: a binding must hold something.
    const bool coloured = r.translucentColour != 0;
    const ResourceId transmittance = coloured ? r.translucentColour : r.visibility;
    graph.addPass({.name = "composite",
                   .cost = CostGroup::PerPixel,
                   .phase = Phase::Composite,
                   .bindings = {.layout = &p.compositeLayout,
                                .bound = {{BIND_FRAME, r.frame},
                                          {COMPOSITE_LIGHTS, r.lights},
                                          {COMPOSITE_GBUFFER_DEPTH, r.gbufferDepth, in.nearest},
                                          {COMPOSITE_GBUFFER_NORMAL, r.gbufferNormal, in.nearest},
                                          {COMPOSITE_GBUFFER_ALBEDO, r.gbufferAlbedo, in.nearest},
                                          {COMPOSITE_VISIBILITY, r.visibility, in.nearest},
                                          {COMPOSITE_OUT, r.color},
                                          {COMPOSITE_TRANSMITTANCE, transmittance, in.nearest}}},
                   .record = [&p, &s, coloured](PassContext& c) {
                       std::vector<shadows::SpecConstant> constants = s.sceneLights;
                       constants.push_back({SPEC_COMPOSITE_COLOURED, coloured ? 1u : 0u});
                       vkCmdBindPipeline(c.cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                                         p.composite(constants));
                       vkCmdDispatch(c.cmd, groups(s.sizes.width), groups(s.sizes.height), 1);
                   }});
}

} // namespace penumbra::render
