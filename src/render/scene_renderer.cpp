// SceneRenderer (include/penumbra/renderer.h): one scene uploaded once, any number of frames.
//   1. The scene is sanitized and uploaded once (constructor, render/scene_upload.h), with a ring
//      of per-frame slots (FrameData, LightData[], ShadowViewData[], the technique's and the
//      layers' parameter blocks).
//   2. Per frame, prepare: the steps of render/frame_prepare.h (lights, shadow views, blocks,
//      settings), the distance field when the technique traces one, the slot filled.
//   3. The frame's graph (render/frame.h) is built, planned and recorded; its targets live in the
//      pool, kept while later frames declare them the same way.
//   4. render(): a warm-up frame and the timed frames, each with the readback passes; the host
//      unpacks the last frame's readback buffer at ReadbackLayout's offsets.
//   A technique that traces the distance field (sdf) draws no shadow map: its field is built
//   before the first frame that needs it (render/distance_field.h) and kept while the scene
//   renderer lives and sdf.resolution and sdf.thickness stay the same.
#include "core/moved_casters.h"
#include "core/virtual_maps.h"
#include "penumbra/error.h"
#include "penumbra/pass_times.h"
#include "penumbra/renderer.h"
#include "render/distance_field.h"
#include "render/frame.h"
#include "render/frame_data.h"
#include "render/frame_prepare.h"
#include "render/page_draw_passes.h"
#include "render/renderer_impl.h"
#include "scene/framing.h"
#include "virtual_pages.h"
#include "vk/check.h"
#include "vk/sync.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>
#include <optional>

static_assert(penumbra::kMaxCascades == MAX_CASCADES,
              "the shaders size their cascade arrays by it");

namespace penumbra {
namespace {

// How near the nearest surface is to a spot or point light that casts a map (its near plane
// follows it); infinite for the rest.
float nearestSurfaceFor(const Scene& scene, const Light& light) {
    return castsShadowMap(light) && light.type != LightType::Directional
               ? nearestSurfaceDistance(scene, light.position)
               : std::numeric_limits<float>::infinity();
}

// Frames in flight: each render takes the next slot for its camera, lights and settings.
constexpr size_t kFramesInFlight = 2;
// GPU timestamp scopes a frame may open: its named passes.
constexpr uint32_t kTimedPasses = 32;

} // namespace

struct SceneRenderer::Impl {
    Renderer& renderer;
    Scene scene; // sanitized
    Bounds bounds;
    float automaticExposure = 0.0f; // EV, when composite.exposure is not set (scene/framing.h)
    render::GpuScene gpu;
    std::vector<float> nearestSurface;  // per scene light: from its position (spot and point)
    std::vector<glm::vec3> nearestFrom; // the positions nearestSurface was measured from
    size_t viewCapacity = 0;            // records the view buffers hold: shadowViewCount's sum
    // visibleDepthRange() for the last camera a sun's cascades followed (compare renders every
    // row from one camera: the triangles are clipped once).
    struct VisibleDepths {
        Camera camera;
        float aspect = 0.0f;
        glm::vec2 range{1.0f, 0.0f};
    };
    std::optional<VisibleDepths> visibleDepths;
    glm::vec2 visibleDepthsFor(const Camera& c, float aspect);
    // `o` with the scene's automatic exposure unless composite.exposure was set.
    RenderOptions exposed(const RenderOptions& o) const {
        RenderOptions shaded = o;
        if (automaticExposure != 0.0f && !o.parameters.isSet("composite.exposure"))
            shaded.parameters.set("composite.exposure", fmt::format("{}", automaticExposure));
        return shaded;
    }
    std::unique_ptr<render::ResourcePool> pool;
    struct Slot {
        // FrameData, LightData[], ShadowViewData[], the technique's and the layers' parameter
        // blocks (mapped)
        vk::Buffer frame, lights, views, params, layerParams;
        // Virtual maps: the page table the host writes, the requests the GPU's marking writes
        // (both mapped, a word per page), and the levels the last marking into it used.
        vk::Buffer pageTable, pageRequests;
        std::vector<VirtualLevel> markedWith;
    };
    std::array<Slot, kFramesInFlight> slots;
    // The camera of the last frame prepared: the next frame's motion vectors start from it.
    std::optional<glm::mat4> lastViewProj;
    // Motion since the last frame, written into a prepared frame's block (FrameData
    // previousViewProj and motion): from the last camera and pose unless the view jumped.
    // y: the frame's index while a layer keeps a history (`turns`), else 0.
    void setMotion(gpu::FrameData& frame, bool cut, bool turns);
    uint32_t frameIndex = 0; // frames drawn while a layer kept a history
    size_t nextSlot = 0;
    size_t lastSlot = 0; // render()'s last: a frame that continues it uses it again
    vk::SamplerHandle nearest, compare, linear;
    // The distance field a technique declares and the setting it was built for; a 1x1x2
    // placeholder bound in its place otherwise (every binding a shader uses must be written).
    std::optional<render::DistanceField> field;
    render::FieldSetting fieldKey;
    vk::Image fieldPlaceholder;
    const render::DistanceField& fieldFor(const render::FieldSetting& wanted,
                                          const ProgressFn& progress, bool& built);
    render::FrameOutputs outputs;
    // Virtual maps: which page the pool holds where, across renders while the pool keeps its
    // contents; the pages this frame renders; what the last frame did.
    std::unique_ptr<PageCache> pageCache;
    uint32_t pageCacheSize = 0;
    uint64_t pageFrame = 0;
    // Where casters moved since the last update (before and after each repose): the pages the
    // next update drops (dropMovedPages) and so draws again.
    MovedCasters movedSinceUpdate;
    // Each triangle that a pose has moved (its index in the scene), and whether one moved for the
    // first time since the last update: the static layers under it hold it where it was.
    std::vector<uint8_t> everMoved;
    bool firstMoveSinceUpdate = false;
    std::vector<render::PageDraw> pageDraws;
    VirtualMapInfo pageInfo;
    // The last update's levels, requests and rendered physical pages: the debug views' source.
    std::vector<VirtualLevel> pageLevels;
    std::vector<PageKey> pageRequests;
    std::vector<uint32_t> pagesRendered;
    uint32_t poolPagesPerSide = 0;
    // Pages decided on the device (virtual.deviceDecides): the passes (made for a pool's pages
    // and page size), the lights' contents keys they last saw, each slot's settings for the
    // frame's passes.
    std::unique_ptr<render::PageDecisionPasses> deviceDecisions;
    std::unique_ptr<render::PageDrawPasses> deviceDraws;
    uint32_t devicePageSize = 0;
    std::map<uint32_t, uint64_t> deviceKeys;
    std::array<render::DevicePages, kFramesInFlight> devicePages{};

    const vk::Context& ctx() const { return renderer.mImpl->ctx; }
    render::FramePipelines& pipelines() { return renderer.mImpl->pipelines; }
    // Everything before recording, ring slot `slotIndex` filled; what the frame reports besides
    // its pixels and times.
    struct Prepared {
        RenderResult result;
        render::FrameSettings settings;
        render::FrameInputs inputs;
        size_t slot = 0;
        // Virtual maps: every light's levels, the page table's size, the lights' contents keys.
        std::vector<VirtualLevel> levels;
        uint32_t tableEntries = 0;
        std::vector<std::pair<uint32_t, uint64_t>> contentsKeys;
    };
    Prepared prepare(const RenderOptions& o, const FrameState& state, size_t slotIndex,
                     const ProgressFn& progress, bool intermediates);
    // Builds, plans and records the frame's graph into `cmd`.
    render::FrameResources record(VkCommandBuffer cmd, const Prepared& p, vk::GpuTimer& timer);
    // Virtual maps, before a frame records: the requests of the frame before it (its slot's)
    // made resident, the pages that were not listed for rendering, the slot's page table
    // written. `poolHolds`: the pool kept its contents (else every page is gone).
    void updatePages(const Prepared& p, bool poolHolds);
    // Pages decided on the device, in prepare: the passes for this pool, room for the frame's
    // table. In record: the frame's inputs written into its slot (`poolHolds` as updatePages').
    // After the frame's fence: what it decided, into pageInfo.
    void reserveDevicePages(const VirtualSettings& v, uint32_t entries);
    void prepareDevicePages(const Prepared& p, bool poolHolds);
    void readDevicePages(const Prepared& p);
    // The slot's page table and request buffers, at least `entries` words each.
    void reservePageBuffers(Slot& slot, uint32_t entries);
};

glm::vec2 SceneRenderer::Impl::visibleDepthsFor(const Camera& c, float aspect) {
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

const render::DistanceField& SceneRenderer::Impl::fieldFor(const render::FieldSetting& wanted,
                                                           const ProgressFn& progress,
                                                           bool& built) {
    built = !field || fieldKey != wanted;
    if (built) {
        VK_CHECK(vkDeviceWaitIdle(ctx().device())); // a frame in flight may still trace it
        field.reset();                              // its memory first
        field = render::buildDistanceField(ctx(), pipelines(), scene, wanted, progress);
        if (progress)
            for (const std::string& warning : field->warnings)
                progress("warning: " + warning);
        fieldKey = wanted;
    }
    return *field;
}

SceneRenderer::SceneRenderer(Renderer& renderer, const Scene& sceneIn)
    : mImpl(std::make_unique<Impl>(Impl{.renderer = renderer, .scene = sceneIn})) {
    Impl& m = *mImpl;
    dropInvalidTriangles(m.scene); // the same rule the ground truth applies
    if (m.scene.triangleCount() == 0)
        throw InputError(m.scene.name, "the scene has no valid triangles");
    checkSkinning(m.scene); // what the `skin` pass reads
    m.bounds = m.scene.bounds();
    m.automaticExposure = automaticExposure(m.scene);
    m.gpu = render::uploadScene(m.ctx(), m.scene);
    m.pool = std::make_unique<render::ResourcePool>(m.ctx());
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
    // Room for any virtual map: a sun's most levels, a cube's faces with the most mips.
    const VirtualSettings mostLevels{.size = 65536, .pageSize = 16, .levels = VIRTUAL_MAX_LEVELS};
    for (const Light& light : m.scene.lights) {
        viewCount += std::max(shadowViewCount(light, kMaxCascades), // room for any csm.cascades
                              virtualViewCount(light, mostLevels));
        m.nearestSurface.push_back(nearestSurfaceFor(m.scene, light));
        m.nearestFrom.push_back(light.position);
    }
    // Room for any csm.cascades up to what the device holds: render refuses more views.
    viewCount = std::min(viewCount, render::uniformCapacity(m.ctx(), sizeof(gpu::ShadowViewData),
                                                            MAX_UNIFORM_VIEWS));
    m.viewCapacity = viewCount;
    const size_t viewBytes = sizeof(gpu::ShadowViewData) * std::max<size_t>(viewCount, 1);
    const size_t layerBytes =
        TECHNIQUE_BLOCK_BYTES * std::max<size_t>(shadows::allLayers().size(), 1);
    auto mapped = [&](size_t bytes, const char* name) {
        vk::Buffer b = vk::createBuffer(m.ctx(), bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                        vk::MemoryUse::Upload, name);
        std::memset(b.mapped, 0, bytes);
        return b;
    };
    for (Impl::Slot& slot : m.slots) {
        slot.frame = mapped(sizeof(gpu::FrameData), "frame buffer");
        // Buffers cannot be empty: a scene without lights still gets one record.
        slot.lights = mapped(lightBytes, "light buffer");
        slot.views = mapped(viewBytes, "shadow view buffer");
        slot.params = mapped(TECHNIQUE_BLOCK_BYTES, "technique parameter buffer");
        slot.layerParams = mapped(layerBytes, "layer parameter buffer");
        m.reservePageBuffers(slot, 4); // a stand-in table: the visibility pass binds one
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

void SceneRenderer::repose(const Scene& posedIn) {
    Impl& m = *mImpl;
    Scene posed = posedIn;
    dropInvalidTriangles(posed); // the same rule the ground truth applies
    if (posed.triangleCount() == 0)
        throw InputError(posed.name, "the scene has no valid triangles at this time");
    if (posed.materials.size() != m.scene.materials.size() ||
        posed.textures.size() != m.scene.textures.size() ||
        posed.images.size() != m.scene.images.size() ||
        posed.lights.size() != m.scene.lights.size())
        throw InputError(posed.name, fmt::format("posed anew it has {} materials, {} textures and "
                                                 "{} lights; it was uploaded with {}, {} and {}",
                                                 posed.materials.size(), posed.textures.size(),
                                                 posed.lights.size(), m.scene.materials.size(),
                                                 m.scene.textures.size(), m.scene.lights.size()));
    checkSkinning(posed);
    const MovedCasters moved = movedCasters(m.scene, posed);
    VK_CHECK(vkDeviceWaitIdle(m.ctx().device())); // a frame in flight may read the old geometry
    // Only skinned vertices moved: this pose's joints, and the `skin` pass places them.
    if (!render::reposeSkinned(m.ctx(), m.gpu, m.scene, posed))
        render::uploadGeometry(m.ctx(), m.gpu, posed);
    // A triangle that moves once is dynamic from then on (virtual.staticLayer).
    for (const uint32_t t : moved.indices) {
        if (t >= m.everMoved.size())
            m.everMoved.resize(t + 1, 0);
        m.firstMoveSinceUpdate = m.firstMoveSinceUpdate || !m.everMoved[t];
        m.everMoved[t] = 1;
    }
    render::markDynamicClusters(m.gpu.clusters, m.gpu.triangleOf, m.everMoved);
    m.scene = std::move(posed);
    // Everything the constructor measured on the geometry, measured again.
    m.bounds = m.scene.bounds();
    m.automaticExposure = automaticExposure(m.scene);
    for (size_t i = 0; i < m.scene.lights.size(); ++i) {
        const Light& light = m.scene.lights[i];
        m.nearestSurface[i] = nearestSurfaceFor(m.scene, light);
        m.nearestFrom[i] = light.position;
    }
    m.visibleDepths.reset();
    m.field.reset(); // traced from the old geometry: built again when a frame needs it
    // Pages keep what no moved, added or removed triangle may draw into.
    if (m.pageCache || m.deviceDecisions)
        m.movedSinceUpdate.append(moved);
    else
        m.movedSinceUpdate.clear();
}

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
    if (state.cut) // latched: the next frame that begins, this one, starts its history again
        pool->invalidateHistory();
    const std::vector<Light> lights =
        render::lightsOf(scene, state.lights ? &*state.lights : nullptr, o);
    for (size_t i = 0; i < lights.size(); ++i) { // a light the viewer moved
        const Light& light = lights[i];
        if (light.position != nearestFrom[i] && castsShadowMap(light) &&
            light.type != LightType::Directional) {
            nearestSurface[i] = nearestSurfaceDistance(scene, light.position);
            nearestFrom[i] = light.position;
        }
    }
    const Camera camera = state.camera ? *state.camera : scene.camera(o.camera);
    const Camera& follows = state.shadowCamera ? *state.shadowCamera : camera;
    const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
    render::ShadowViews views =
        render::shadowViewsOf(lights, o,
                              {.bounds = bounds,
                               .nearestSurface = nearestSurface,
                               .camera = follows,
                               .aspect = aspect,
                               .visibleDepths = [&] { return visibleDepthsFor(follows, aspect); }});
    // shadowViewsOf and shadowViewCount must agree: the buffers were sized by the latter.
    if (views.records.size() > viewCapacity)
        fatal(__FILE__, __LINE__, "SceneRenderer: more shadow views than shadowViewCount counted");

    RenderResult result{.width = o.width, .height = o.height, .lights = views.report};
    const RenderOptions shaded = exposed(o);
    render::FrameBlocks blocks =
        render::frameBlocks(camera, shaded, static_cast<uint32_t>(lights.size()), ctx());
    setMotion(blocks.frame, state.cut, shadows::keepsHistory(o.parameters));
    result.exposure = static_cast<float>(shaded.parameters.number("composite.exposure"));
    const vk::Image* fieldImage = &fieldPlaceholder;
    if (const auto& declared = shadows::moduleOf(o.technique).tracedField) {
        bool built = false;
        const render::DistanceField& grid =
            fieldFor(render::FieldSetting::of(*declared, o.parameters), progress, built);
        blocks.frame.fieldOrigin = glm::vec4(grid.layout.origin, grid.layout.voxel);
        blocks.frame.fieldSize = glm::uvec4(grid.layout.size, 0u);
        fieldImage = &grid.image;
        result.field = DistanceFieldInfo{.voxels = grid.layout.size,
                                         .voxelSize = grid.layout.voxel,
                                         .origin = grid.layout.origin,
                                         .bytes = grid.bytes(),
                                         .triangles = grid.sceneTriangles,
                                         .fieldTriangles = grid.triangles,
                                         .openTriangles = grid.openTriangles,
                                         .alphaTriangles = grid.alphaTriangles,
                                         .alphaPieces = grid.alphaPieces,
                                         .buildGpuMs = grid.buildMs,
                                         .buildPasses = grid.passMs,
                                         .buildCpuMs = grid.cpuMs,
                                         .built = built};
    }
    Slot& slot = slots[slotIndex % slots.size()];
    std::memcpy(slot.frame.mapped, &blocks.frame, sizeof blocks.frame);
    if (!views.lights.empty())
        std::memcpy(slot.lights.mapped, views.lights.data(),
                    views.lights.size() * sizeof(gpu::LightData));
    if (!views.records.empty())
        std::memcpy(slot.views.mapped, views.records.data(),
                    views.records.size() * sizeof(gpu::ShadowViewData));
    std::memcpy(slot.params.mapped, blocks.technique.bytes().data(), TECHNIQUE_BLOCK_BYTES);
    for (size_t i = 0; i < blocks.layers.size(); ++i)
        std::memcpy(static_cast<std::byte*>(slot.layerParams.mapped) + i * TECHNIQUE_BLOCK_BYTES,
                    blocks.layers[i].bytes().data(), TECHNIQUE_BLOCK_BYTES);
    if (!views.levels.empty())
        reservePageBuffers(slot, views.tableEntries);
    render::FrameSettings settings = render::frameSettings(o, lights, views, blocks, intermediates);
    settings.pages = &pageDraws;
    // The translucent layer runs where translucent casters are: elsewhere the frame is the same
    // as without it.
    std::erase_if(settings.layers, [&](const shadows::LayerModule* layer) {
        return layer->translucentMethod && !gpu.hasTranslucent();
    });
    for (const shadows::LayerModule* layer : settings.layers)
        if (layer->translucentMethod)
            settings.translucent = layer->translucentMethod(o.parameters);
    VkBuffer pageTable = slot.pageTable.get(), pageRenderList = VK_NULL_HANDLE;
    if (const VirtualSettings v = VirtualSettings::of(o.parameters);
        !views.levels.empty() && v.deviceDecides) {
        reserveDevicePages(v, views.tableEntries);
        render::DevicePages& device = devicePages[slotIndex % slots.size()];
        device = {.decisions = deviceDecisions.get(),
                  .draws = deviceDraws.get(),
                  .slot = static_cast<uint32_t>(slotIndex % slots.size()),
                  .poolPagesPerSide = v.poolPagesPerSide()};
        settings.devicePages = &device;
        pageTable = deviceDecisions->table();
        pageRenderList = deviceDecisions->renderList();
    }
    return {.result = std::move(result),
            .settings = std::move(settings),
            .inputs = {.frame = slot.frame.get(),
                       .lights = slot.lights.get(),
                       .views = slot.views.get(),
                       .params = slot.params.get(),
                       .layerParams = slot.layerParams.get(),
                       .pageTable = pageTable,
                       .pageRequests = slot.pageRequests.get(),
                       .pageRenderList = pageRenderList,
                       .field = fieldImage,
                       .nearest = nearest.get(),
                       .compare = compare.get(),
                       .fieldSampler = linear.get()},
            .slot = slotIndex % slots.size(),
            .levels = std::move(views.levels),
            .tableEntries = views.tableEntries,
            .contentsKeys = std::move(views.contentsKeys)};
}

void SceneRenderer::Impl::setMotion(gpu::FrameData& frame, bool cut, bool turns) {
    frame.previousViewProj = cut || !lastViewProj ? frame.viewProj : *lastViewProj;
    frame.motion.x = !cut && gpu.moved ? 1u : 0u;
    frame.motion.y = turns ? ++frameIndex : 0u;
    lastViewProj = frame.viewProj;
}

void SceneRenderer::Impl::reservePageBuffers(Slot& slot, uint32_t entries) {
    const VkDeviceSize bytes = VkDeviceSize{entries} * sizeof(uint32_t);
    if (slot.pageTable.get() != VK_NULL_HANDLE && slot.pageTable.size >= bytes)
        return;
    VK_CHECK(vkDeviceWaitIdle(ctx().device())); // a frame in flight may read them
    for (auto [buffer, name] : {std::pair{&slot.pageTable, "page table"},
                                std::pair{&slot.pageRequests, "page requests"}}) {
        *buffer = vk::createBuffer(
            ctx(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
            vk::MemoryUse::Readback, name);
        std::memset(buffer->mapped, 0, bytes);
    }
    slot.markedWith.clear();
}

void SceneRenderer::Impl::reserveDevicePages(const VirtualSettings& v, uint32_t entries) {
    const bool fits = deviceDecisions && devicePageSize == v.pageSize &&
                      deviceDecisions->poolPages() == v.poolPages();
    // Frames in flight read the passes' buffers: none may be when they go or grow.
    if (!fits || deviceDecisions->entryCapacity() < entries)
        VK_CHECK(vkDeviceWaitIdle(ctx().device()));
    if (!fits) {
        deviceDecisions = std::make_unique<render::PageDecisionPasses>(
            ctx(), v.poolPages(),
            render::PageDecisionOptions{.readable = false,
                                        .slots = static_cast<uint32_t>(slots.size())});
        devicePageSize = v.pageSize;
        deviceKeys.clear();
        pageCache.reset(); // one of the two decides
    }
    if (!deviceDraws)
        deviceDraws =
            std::make_unique<render::PageDrawPasses>(ctx(), static_cast<uint32_t>(slots.size()));
    deviceDecisions->reserve(entries);
}

void SceneRenderer::Impl::prepareDevicePages(const Prepared& p, bool poolHolds) {
    const VirtualSettings v = VirtualSettings::of(*p.settings.params);
    if (!poolHolds) {
        deviceDecisions->freeAll();
        deviceKeys.clear();
    }
    std::vector<uint32_t> rekeyed;
    for (const auto& [light, key] : p.contentsKeys) {
        const auto [at, added] = deviceKeys.emplace(light, key);
        if (!added && at->second != key)
            rekeyed.push_back(light);
        at->second = key;
    }
    const std::vector<std::vector<PageRect>> moved =
        movedSinceUpdate.boxes.empty() ? std::vector<std::vector<PageRect>>{}
                                       : movedPageRects(p.levels, movedSinceUpdate.boxes,
                                                        v.pageSize, {}, movedSinceUpdate.triangles);
    movedSinceUpdate.clear();
    const auto slot = static_cast<uint32_t>(p.slot);
    deviceDecisions->prepare({.levels = &p.levels,
                              .lightsRekeyed = rekeyed,
                              .moved = moved,
                              .frame = static_cast<uint32_t>(++pageFrame)},
                             slot);
    deviceDraws->prepare(p.levels, slot);
    pageLevels = p.levels;
    pageInfo.poolPages = v.poolPages();
    pageInfo.poolBytes = uint64_t{v.poolSize} * v.poolSize * sizeof(float);
    pageInfo.tableBytes = uint64_t{p.tableEntries} * sizeof(uint32_t);
    pageInfo.pageSize = v.pageSize;
    pageInfo.virtualSize = v.size;
    pageInfo.levelBias = v.levelBias(p.settings.sizes.width, p.settings.sizes.height);
}

void SceneRenderer::Impl::readDevicePages(const Prepared& p) {
    const gpu::PageCounts& c = deviceDecisions->counts(static_cast<uint32_t>(p.slot));
    pageInfo.requested = c.requested;
    pageInfo.resident = c.resident;
    pageInfo.rendered = c.rendered;
    pageInfo.cached = c.cached;
    pageInfo.dropped = c.dropped;
    pageInfo.evicted = c.evicted;
    pageInfo.renderedPerFrame.push_back(c.rendered);
    pageInfo.droppedFrames += c.dropped > 0;
}

void SceneRenderer::Impl::updatePages(const Prepared& p, bool poolHolds) {
    const VirtualSettings v = VirtualSettings::of(*p.settings.params);
    if (deviceDecisions) { // one of the two decides (frames in flight may read its buffers)
        VK_CHECK(vkDeviceWaitIdle(ctx().device()));
        deviceDecisions.reset();
    }
    if (!pageCache || !poolHolds || pageCacheSize != v.pageSize ||
        pageCache->capacity() != v.poolPages()) {
        pageCache = std::make_unique<PageCache>(v.poolPages());
        pageCacheSize = v.pageSize;
    }
    for (const auto& [light, key] : p.contentsKeys)
        pageCache->keyLight(light, key);
    // The pages under what moved keep their places (so a page is drawn at the same place in the
    // pool with or without the layer: the rasterizer's rounding may depend on the place) and
    // their static layers, unless a caster moved for the first time: those layers hold it where
    // it was.
    dropMovedPages(
        *pageCache, p.levels, movedSinceUpdate.boxes, v.pageSize, movedSinceUpdate.triangles,
        v.staticLayer && !firstMoveSinceUpdate ? MovedPage::Stale : MovedPage::StaleLayerLost);
    movedSinceUpdate.clear();
    firstMoveSinceUpdate = false;
    // The level a page belongs to in this frame, if its window holds the page.
    auto levelHolding = [&](const PageKey& k) -> const VirtualLevel* {
        const VirtualLevel* level = levelOf(p.levels, k);
        return level && entryOf(*level, k.page) ? level : nullptr;
    };
    Slot& slot = slots[p.slot];
    std::vector<PageKey> requests;
    if (!slot.markedWith.empty())
        for (const PageKey& k : requestedPages(
                 slot.markedWith, static_cast<const uint32_t*>(slot.pageRequests.mapped)))
            if (levelHolding(k)) // a sun's window may have moved on
                requests.push_back(k);
    pageRequests = withCoarserPages(requests, p.levels);
    const PageCache::Update u = pageCache->update(pageRequests, ++pageFrame);
    pageDraws.clear();
    pagesRendered.clear();
    pageLevels = p.levels;
    const uint32_t side = poolPagesPerSide = v.poolPagesPerSide();
    for (size_t i = 0; i < u.render.size(); ++i) {
        const auto& [physical, key] = u.render[i];
        pagesRendered.push_back(physical);
        const VirtualLevel& level = *levelHolding(key);
        pageDraws.push_back({.viewProj = pageViewProj(level, key.page - level.firstPage),
                             .perspective = level.projection.perspective,
                             .origin = glm::uvec2(physical % side, physical / side) * v.pageSize,
                             .staticHeld = u.staticHeld[i] != 0});
    }
    pageInfo.staticHeld =
        static_cast<uint32_t>(std::count(u.staticHeld.begin(), u.staticHeld.end(), 1));
    const std::vector<uint32_t> table = pageTable(p.levels, *pageCache, p.tableEntries);
    std::memcpy(slot.pageTable.mapped, table.data(), table.size() * sizeof(uint32_t));
    slot.markedWith = p.levels;
    pageInfo.requested = u.requested;
    pageInfo.resident = pageCache->resident();
    pageInfo.rendered = static_cast<uint32_t>(u.render.size());
    pageInfo.cached = u.cached;
    pageInfo.dropped = u.dropped;
    pageInfo.evicted = u.evicted;
    pageInfo.poolPages = pageCache->capacity();
    pageInfo.poolBytes =
        uint64_t{v.poolSize} * v.poolSize * sizeof(float) * (v.staticLayer ? 2 : 1);
    pageInfo.tableBytes = uint64_t{p.tableEntries} * sizeof(uint32_t);
    pageInfo.pageSize = v.pageSize;
    pageInfo.virtualSize = v.size;
    pageInfo.levelBias = v.levelBias(p.settings.sizes.width, p.settings.sizes.height);
    pageInfo.renderedPerFrame.push_back(pageInfo.rendered);
    pageInfo.droppedFrames += u.dropped > 0;
}

render::FrameResources SceneRenderer::Impl::record(VkCommandBuffer cmd, const Prepared& p,
                                                   vk::GpuTimer& timer) {
    render::FrameGraph graph(*pool, p.settings.sizes);
    const render::FrameResources r =
        render::buildFrame(graph, pipelines(), gpu, p.settings, p.inputs);
    graph.plan(); // the pool's resources exist from here
    if (p.settings.devicePages)
        prepareDevicePages(p, graph.holdsContents(r.depthMap));
    else if (p.settings.virtualMaps)
        updatePages(p, graph.holdsContents(r.depthMap) &&
                           (!r.staticPool || graph.holdsContents(r.staticPool)));
    timer.reset(cmd);
    graph.record(cmd, &timer);
    if (gpu.skin) // placed for this pose: later frames draw what it wrote
        gpu.skin->pending = false;
    gpu.moved = false; // later frames of this pose see no motion
    gpu.drawn = true;
    outputs = {.color = &graph.image(r.color).get(),
               .visibility = &graph.image(r.visibility).get(),
               .depthMap = &graph.image(r.depthMap).get(),
               .gbufferDepth = &graph.image(r.gbufferDepth).get(),
               .intermediates = &graph.image(r.intermediates).get(),
               .layerResults = &graph.image(r.layerResults).get(),
               .frame = p.inputs.frame};
    return r;
}

RenderResult SceneRenderer::render(const RenderOptions& o, const FrameState& state,
                                   const ProgressFn& progress) {
    Impl& m = *mImpl;
    const vk::Context& ctx = m.ctx();
    // A frame that continues the last one reads the page requests that frame's marking wrote
    // into its slot: the same slot again.
    const size_t slot = state.continues ? m.lastSlot : m.nextSlot;
    Impl::Prepared prepared = m.prepare(o, state, slot, progress, false);
    m.lastSlot = slot;
    m.nextSlot = (slot + 1) % m.slots.size();
    RenderResult& result = prepared.result;
    vk::GpuTimer timer(ctx, kTimedPasses);
    m.pageInfo = {};
    // Virtual maps: a frame renders the pages the frame before it asked for, so the first
    // warm-up frame asks (its own pixels read whatever the pool held) and the second renders.
    // A frame that continues the last one has none: what it kept must show.
    // Pages decided on the device are rendered in the frame that asks for them: one warm-up
    // (shadows::warmUpFrames counts them all, as stats.json reports).
    // A layer that keeps a history draws what it needs to hold the pose's steady state.
    const uint32_t warmUps =
        state.continues ? 0 : shadows::warmUpFrames(o.parameters, prepared.settings.virtualMaps);
    for (uint32_t frame = 0; frame < o.frames + warmUps; ++frame) {
        const bool warmUp = frame < warmUps;
        if (progress)
            progress(warmUp ? std::string("warm-up frame")
                            : fmt::format("frame {}/{}", frame + 1 - warmUps, o.frames));
        // Every frame reads back (untimed), so that every frame is the same graph with its
        // memory placed the same: a last frame that alone read back was placed anew, and its
        // first touches showed in its GPU times (on lavapipe a 30 ms shadow pass took 560).
        prepared.settings.readback = true;
        ctx.submitAndWait([&](VkCommandBuffer cmd) { m.record(cmd, prepared, timer); });
        { // the frames after it draw the same pose and camera again: no motion, the next index
            auto& block = *static_cast<gpu::FrameData*>(m.slots[slot].frame.mapped);
            m.setMotion(block, false, block.motion.y != 0u);
        }
        if (prepared.settings.devicePages)
            m.readDevicePages(prepared);
        if (warmUp)
            continue; // the warm-up frames pay for first-use costs
        std::vector<PassTime> frameTimes = timer.read();
        // A continuing frame that built the distance field again (a pose drops it) pays for the
        // build in that frame: it counts as a pass of its own, `sdf_build`.
        if (frame == warmUps && state.continues && result.field && result.field->built)
            frameTimes.push_back({.pass = "sdf_build",
                                  .cost = CostGroup::ShadowMaps,
                                  .medianMs = result.field->buildGpuMs});
        appendFrameTimes(result.passes, frameTimes, frame - warmUps);
    }
    setMedians(result.passes);
    const render::ResourcePool::TransientBytes transient = m.pool->transientBytes();
    result.transientMemory = {.separateBytes = transient.separate, .sharedBytes = transient.shared};
    if (prepared.settings.virtualMaps) {
        result.virtualMaps = m.pageInfo;
        if (m.pageInfo.dropped > 0 && progress)
            progress(fmt::format("warning: the virtual pool holds {} pages; this view asked for "
                                 "{} and {} read coarser pages (raise virtual.poolSize)",
                                 m.pageInfo.poolPages, m.pageInfo.requested, m.pageInfo.dropped));
    }

    if (progress)
        progress("reading back");
    const render::ReadbackLayout layout(o.width, o.height, prepared.settings.sizes.shadowLights,
                                        prepared.settings.motion,
                                        prepared.settings.translucent != 0);
    const VkBuffer readback = m.pool->findBuffer(render::target::kReadback);
    PENUMBRA_CHECK(readback != VK_NULL_HANDLE, "SceneRenderer: no readback buffer");
    const auto* src = static_cast<const std::byte*>(m.pool->mapped(render::target::kReadback));
    const size_t pixels = size_t{o.width} * o.height;
    result.image.resize(pixels * 4);
    std::memcpy(result.image.data(), src + layout.color.offset, pixels * 4);
    for (size_t l = 0; l < prepared.settings.shadowLights.size(); ++l) {
        std::vector<float>& v = result.visibility.emplace_back(pixels);
        std::memcpy(v.data(), src + layout.visibility.offset + l * pixels * 4, pixels * 4);
    }
    for (auto [out, part] :
         {std::pair{&result.position, layout.position}, std::pair{&result.normal, layout.normal},
          std::pair{&result.faceNormal, layout.faceNormal}}) {
        out->resize(pixels * 3);
        const auto* rgba = reinterpret_cast<const float*>(src + part.offset);
        for (size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < 3; ++c)
                (*out)[3 * i + c] = rgba[4 * i + c];
    }
    if (layout.motion) { // w: 1 where a surface wrote it
        result.motion.resize(pixels * 3);
        const auto* rgba = reinterpret_cast<const float*>(src + layout.motion->offset);
        for (size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < 3; ++c)
                result.motion[3 * i + c] = rgba[4 * i + 3] != 0.0f
                                               ? rgba[4 * i + c]
                                               : std::numeric_limits<float>::quiet_NaN();
    }
    if (layout.colour) // the translucent layer's light per channel, a layer per light
        for (size_t l = 0; l < prepared.settings.shadowLights.size(); ++l) {
            std::vector<float>& rgb = result.transmittance.emplace_back(pixels * 3);
            const auto* rgba =
                reinterpret_cast<const float*>(src + layout.colour->offset + l * pixels * 16);
            for (size_t i = 0; i < pixels; ++i)
                for (int c = 0; c < 3; ++c)
                    rgb[3 * i + c] = rgba[4 * i + c];
        }
    return result;
}

SceneRenderer::RecordedFrame SceneRenderer::record(VkCommandBuffer_T* cmd,
                                                   const RenderOptions& options,
                                                   const FrameState& state, size_t slot,
                                                   vk::GpuTimer& timer, bool intermediates,
                                                   const ProgressFn& progress) {
    Impl& m = *mImpl;
    Impl::Prepared prepared = m.prepare(options, state, slot, progress, intermediates);
    prepared.settings.present = true;
    // Frames in flight share the targets: this frame's first writes wait for every command
    // submitted before it (the graph's barriers start from where the last frame left them).
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    m.pageInfo.renderedPerFrame.clear(); // this frame's alone: a viewer's frames never end
    if (prepared.settings.devicePages)   // its slot's last frame, done: the viewer waited for it
        m.readDevicePages(prepared);
    m.record(cmd, prepared, timer);
    if (prepared.settings.virtualMaps)
        prepared.result.virtualMaps = m.pageInfo;
    return {std::move(prepared.result), &m.outputs};
}

void SceneRenderer::trim() {
    mImpl->pool->releasePerFrame();
}

SceneRenderer::DeviceGeometry SceneRenderer::deviceGeometry() const {
    const Impl& m = *mImpl;
    VK_CHECK(vkDeviceWaitIdle(m.ctx().device())); // the last frame's skinning, done
    DeviceGeometry out;
    render::readGeometry(m.ctx(), m.gpu, m.scene.vertices.size(), out.vertices, out.positions,
                         out.previousPositions);
    return out;
}

VirtualPages SceneRenderer::virtualPages() const {
    const Impl& m = *mImpl;
    if (!m.pageCache)
        return {};
    VirtualPages pages = penumbra::virtualPages(m.pageLevels, *m.pageCache, m.pageRequests,
                                                m.pagesRendered, m.poolPagesPerSide);
    pages.info = m.pageInfo;
    return pages;
}

} // namespace penumbra
