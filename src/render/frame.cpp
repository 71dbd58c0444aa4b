#include "render/frame.h"

#include "penumbra/error.h"

#include <fmt/format.h>

namespace penumbra::render {

static_assert(kPreviousSuffix == shadows::kPreviousMapSuffix,
              "a module names last frame's maps as the pool does");

void FrameResources::declareOwnMaps(FrameGraph& graph, const shadows::TechniqueModule& module,
                                    std::span<const ImageDecl> decls) {
    for (size_t m = 0; m < decls.size(); ++m) {
        maps.push_back(graph.declare(decls[m]));
        previousMaps.push_back(module.maps[m].history ? std::optional(graph.previous(maps.back()))
                                                      : std::nullopt);
    }
}

ResourceId FrameResources::named(const shadows::TechniqueModule& module,
                                 std::string_view name) const {
    if (name == shadows::kDepthMap)
        return depthMap;
    if (name.ends_with(shadows::kPreviousMapSuffix)) {
        const std::string_view own = name.substr(0, name.size() - kPreviousSuffix.size());
        for (size_t m = 0; m < previousMaps.size(); ++m)
            if (module.maps[m].name == own && previousMaps[m])
                return *previousMaps[m];
        fatal(__FILE__, __LINE__,
              fmt::format("FrameResources::named: technique {} keeps no history of '{}'",
                          module.info.name, own));
    }
    for (size_t m = 0; m < module.maps.size(); ++m)
        if (module.maps[m].name == name)
            return maps[m];
    fatal(__FILE__, __LINE__,
          fmt::format("FrameResources::named: technique {} declares no map '{}'", module.info.name,
                      name));
}

std::optional<ResourceId> FrameResources::currentOf(ResourceId id) const {
    for (size_t m = 0; m < previousMaps.size(); ++m)
        if (previousMaps[m] == id)
            return maps[m];
    return std::nullopt;
}

FrameResources declareFrame(FrameGraph& graph, const FrameSettings& s, const FrameInputs& in) {
    FrameResources r;
    // The technique's maps of every shadow view (a technique that draws none binds 1x1 ones).
    std::vector<ImageDecl> maps = shadowMapDecls(*s.technique, *s.params, s.views);
    // only bound: nothing lost between frames
    const bool drawsNoMap = !shadows::drawsLightMaps(*s.technique);
    if (drawsNoMap)
        maps.front().lifetime = Lifetime::Persistent;
    r.depthMap = graph.declare(maps.front());
    if (drawsNoMap)
        graph.markBoundOnly(r.depthMap);
    r.declareOwnMaps(graph, *s.technique, std::span(maps).subspan(1));
    if (const std::optional<ImageDecl> decl = staticPoolDecl(*s.technique, *s.params))
        r.staticPool = graph.declare(*decl);
    const shadows::TechniqueModule& module = *s.technique;
    // On virtual maps a technique has the page pool alone: it reads it as its depth map.
    const bool ownMaps = r.maps.size() == module.maps.size();
    auto screen = [&](std::string_view name) {
        for (const ImageDecl& decl : screenDecls(s.intermediates))
            if (decl.name == name)
                return graph.declare(decl);
        fatal(__FILE__, __LINE__, "declareFrame: no such screen target");
    };
    r.gbufferDepth = screen(target::kGBufferDepth);
    r.gbufferNormal = screen(target::kGBufferNormal);
    r.gbufferAlbedo = screen(target::kGBufferAlbedo);
    if (s.motion)
        r.gbufferMotion = screen(target::kGBufferMotion);
    r.visibility = screen(target::kVisibility);
    r.intermediates = screen(target::kIntermediates);
    r.layerResults = screen(target::kLayerResults);
    for (const shadows::LayerModule* layer : s.layers) {
        ResourceId history = 0, previous = 0;
        if (layer->history) {
            history = graph.declare(layerHistoryDecl(*layer, *s.technique, *s.params));
            previous = graph.previous(history);
        }
        r.layerHistory.push_back(history);
        r.layerHistoryPrevious.push_back(previous);
    }
    const std::vector<shadows::ScreenPassDecl> screenPasses = screenPassesOf(s);
    if (std::any_of(screenPasses.begin(), screenPasses.end(), [](const shadows::ScreenPassDecl& p) {
            return p.results == shadows::kScreenScratch;
        }))
        r.screenScratch = screen(target::kScreenScratch);
    r.color = screen(target::kColor);
    graph.markOutput(r.color);
    graph.markOutput(r.visibility);
    r.position = screen(target::kPosition);
    r.normal = screen(target::kNormal);
    r.faceNormal = screen(target::kFaceNormal);
    r.integerPlaceholder = screen(target::kIntegerPlaceholder);
    r.depthPlaceholder = screen(target::kDepthPlaceholder);
    // Stand-ins: the placeholder, and the viewer's intermediates, 1x1 unless asked for and
    // handed over unwritten when no layer ran.
    for (const ResourceId id :
         {r.integerPlaceholder, r.depthPlaceholder, r.intermediates, r.layerResults})
        graph.markBoundOnly(id);
    r.filtered = FilteredBindings::of(
        module, *s.params, r.depthMap, {r.integerPlaceholder, r.depthPlaceholder},
        ownMaps ? std::function([&](std::string_view name) { return r.named(module, name); })
                : nullptr);
    r.readback = graph.declare(ReadbackLayout(s.sizes.width, s.sizes.height, s.sizes.shadowLights,
                                              s.motion, s.translucent != 0)
                                   .decl());
    // Built (or made) sampled, and only ever sampled.
    r.field = graph.importImage(std::string(target::kField), *in.field, Access::ComputeSampled);
    r.frame = graph.importBuffer(std::string(target::kFrameBlock), in.frame);
    r.lights = graph.importBuffer(std::string(target::kLights), in.lights);
    r.views = graph.importBuffer(std::string(target::kViews), in.views);
    r.params = graph.importBuffer(std::string(target::kParams), in.params);
    r.layerParams = graph.importBuffer(std::string(target::kLayerParams), in.layerParams);
    r.pageTable = graph.importBuffer(std::string(target::kPageTable), in.pageTable);
    if (s.virtualMaps)
        r.pageRequests = graph.importBuffer(std::string(target::kPageRequests), in.pageRequests);
    if (s.devicePages)
        r.pageRenderList = graph.importBuffer("pages.renderList", in.pageRenderList);
    if (s.translucent != 0) {
        for (const ImageDecl& decl : translucentMapDecls(s.translucent))
            r.translucentMaps.push_back(graph.declare(decl));
        r.translucentColour = screen(target::kTranslucentColour);
    }
    r.traceList = graph.declare(traceListDecl(s.sizes.width, s.sizes.height,
                                              shadows::checkerboardFill(screenPasses) != nullptr));
    return r;
}

std::vector<shadows::ScreenPassDecl> screenPassesOf(const FrameSettings& s) {
    std::vector<shadows::ScreenPassDecl> passes = shadows::screenPassesOf(*s.technique, *s.params);
    if (s.intermediates && shadows::checkerboardFill(passes))
        passes.erase(passes.begin());
    return passes;
}

FrameResources buildFrame(FrameGraph& graph, FramePipelines& pipelines, const GpuScene& scene,
                          const FrameSettings& s, const FrameInputs& in) {
    FrameResources r = declareFrame(graph, s, in);
    r.vertices = graph.importBuffer(std::string(target::kVertices), scene.vertices.get());
    r.positions = graph.importBuffer(std::string(target::kPositions), scene.positions.get());
    if (scene.previousPositions.get() != VK_NULL_HANDLE)
        r.previousPositions = graph.importBuffer(std::string(target::kPreviousPositions),
                                                 scene.previousPositions.get());
    if (scene.skin && scene.skin->pending) // the pose changed since the last skinning
        addSkinPass(graph, pipelines, scene, r);
    // A technique that reads no map (a distance field's tracer) gets none drawn: its 1x1 depth
    // map is only bound (the graph gives it a layout on first use).
    if (s.virtualMaps)
        addVirtualPagePasses(graph, pipelines, scene, s, in, r);
    else if (shadows::drawsLightMaps(*s.technique))
        addShadowPasses(graph, pipelines, scene, s, in, r);
    if (s.translucent != 0)
        addTranslucentCasterPass(graph, pipelines, scene, s, in, r);
    addGBufferPass(graph, pipelines, scene, s, in, r);
    addLightPasses(graph, pipelines, s, in, r);
    if (s.readback)
        addReadbackPasses(graph, pipelines, s, in, r);
    if (s.present)
        addPresentPass(graph, r);
    return r;
}

FilteredBindings FilteredBindings::of(const shadows::TechniqueModule& module,
                                      const ParameterValues& params, ResourceId depthMap,
                                      Placeholders placeholders,
                                      const std::function<ResourceId(std::string_view)>& named) {
    FilteredBindings b;
    b.floats.fill(depthMap);
    b.integers.fill(placeholders.integers);
    b.compare = depthMap;
    if (!named)
        return b;
    const shadows::VisibilitySlots slots = shadows::visibilitySlots(module, params);
    for (size_t k = 0; k < TECH_MAX_MAPS; ++k) {
        b.floats[k] = named(slots.floats[k]);
        if (!slots.integers[k].empty())
            b.integers[k] = named(slots.integers[k]);
    }
    // A technique that reads no depth map leaves it to its own passes: its memory may be
    // another transient's once they are done.
    if (!slots.readsDepthMap)
        b.compare = placeholders.depth;
    return b;
}

void FilteredBindings::write(vk::PushDescriptors& descriptors, const PassContext& c,
                             VkSampler nearest, VkSampler compareSampler) const {
    std::array<VkImageView, TECH_MAX_MAPS> floatViews{}, integerViews{};
    for (size_t k = 0; k < TECH_MAX_MAPS; ++k) {
        floatViews[k] = c.image(floats[k]).view();
        integerViews[k] = c.image(integers[k]).view();
    }
    descriptors.sampled(TECH_MAP, floatViews, nearest)
        .sampled(TECH_TABLE, integerViews, nearest)
        .sampled(TECH_COMPARE, c.image(compare).view(), compareSampler);
}

void FilteredBindings::addUses(std::vector<Use>& uses) const {
    for (size_t k = 0; k < TECH_MAX_MAPS; ++k) {
        uses.push_back({floats[k], Access::ComputeSampled});
        uses.push_back({integers[k], Access::ComputeSampled});
    }
    uses.push_back({compare, Access::ComputeSampled});
}

void addPresentPass(FrameGraph& graph, const FrameResources& r) {
    graph.addPass({.name = "",
                   .phase = Phase::Readback,
                   .uses = {{r.color, Access::ComputeWrite},
                            {r.visibility, Access::ComputeSampled},
                            {r.depthMap, Access::ComputeSampled},
                            {r.gbufferDepth, Access::ComputeSampled},
                            {r.intermediates, Access::ComputeSampled},
                            {r.layerResults, Access::ComputeSampled}},
                   .record = [](PassContext&) {}});
}

vk::Image makeFieldPlaceholder(const vk::Context& ctx) {
    return vk::createImage(ctx, {.name = "distance field placeholder",
                                 .format = VK_FORMAT_R32_SFLOAT,
                                 .width = 1,
                                 .height = 1,
                                 .usage = VK_IMAGE_USAGE_SAMPLED_BIT,
                                 .depth = 2});
}

} // namespace penumbra::render
