// The maps a pass that evaluates a technique binds (render::FilteredBindings): every map its
// module lists, in the slot shadows::visibilitySlots gives it, the depth map and the placeholder
// in the rest; then on the device, through the probe's slot reads, that each slot holds the map
// it should (a technique whose own map is not its depth map, and one whose map holds integers).
#include "gpu_fixture.h"
#include "penumbra/renderer.h"
#include "render/frame.h"
#include "render/frame_targets.h"
#include "shadows/technique.h"

#include <cmath>

using namespace penumbra;
using namespace penumbra::test;

TEST_F(FrameTest, EachListedMapIsBoundInItsSlotAndTheRestHoldStandIns) {
    const shadows::TechniqueModule module{
        .info = {.name = "two maps"},
        .maps = {{.name = "near", .format = shadows::MapFormat::R32F},
                 {.name = "counts", .format = shadows::MapFormat::R32UI},
                 {.name = "far", .format = shadows::MapFormat::RG32F}},
        .visibilityMaps = {"far", "counts", "near"}};
    const render::ResourceId depth = 1, placeholder = 9, depthPlaceholder = 8;
    const auto named = [](std::string_view name) -> render::ResourceId {
        return name == shadows::kDepthMap ? 1 : name == "near" ? 2 : name == "counts" ? 3 : 4;
    };
    const render::FilteredBindings bound = render::FilteredBindings::of(
        module, ParameterValues{}, depth, {placeholder, depthPlaceholder}, named);
    // It reads no depth map: its first float map in the float slots it leaves, and the depth
    // placeholder for the comparison sampler.
    EXPECT_EQ(bound.floats, (std::array<render::ResourceId, TECH_MAX_MAPS>{4, 2, 4, 4}));
    EXPECT_EQ(bound.integers, (std::array<render::ResourceId, TECH_MAX_MAPS>{3, 9, 9, 9}));
    EXPECT_EQ(bound.compare, depthPlaceholder);
    // Listing the depth map (or no float map) keeps it in the slots left and for comparison.
    shadows::TechniqueModule withDepth = module;
    withDepth.visibilityMaps = {"near", std::string_view(shadows::kDepthMap)};
    const render::FilteredBindings both = render::FilteredBindings::of(
        withDepth, ParameterValues{}, depth, {placeholder, depthPlaceholder}, named);
    EXPECT_EQ(both.floats, (std::array<render::ResourceId, TECH_MAX_MAPS>{2, 1, 1, 1}));
    EXPECT_EQ(both.compare, depth);
    withDepth.visibilityMaps = {"counts"};
    const render::FilteredBindings integersOnly = render::FilteredBindings::of(
        withDepth, ParameterValues{}, depth, {placeholder, depthPlaceholder}, named);
    EXPECT_EQ(integersOnly.floats, (std::array<render::ResourceId, TECH_MAX_MAPS>{1, 1, 1, 1}));
    EXPECT_EQ(integersOnly.compare, depth);
    // Without its own maps (virtual maps' pool): the depth map in every float slot.
    const render::FilteredBindings alone = render::FilteredBindings::of(
        module, ParameterValues{}, depth, {placeholder, depthPlaceholder}, nullptr);
    EXPECT_EQ(alone.floats, (std::array<render::ResourceId, TECH_MAX_MAPS>{1, 1, 1, 1}));
    EXPECT_EQ(alone.integers, (std::array<render::ResourceId, TECH_MAX_MAPS>{9, 9, 9, 9}));
    EXPECT_EQ(alone.compare, depth);
    // The pass uses each slot's resource, sampled.
    std::vector<render::Use> uses;
    bound.addUses(uses);
    for (render::ResourceId id : {2u, 3u, 4u, 8u, 9u})
        EXPECT_TRUE(std::any_of(uses.begin(), uses.end(),
                                [&](const render::Use& u) {
                                    return u.resource == id &&
                                           u.access == render::Access::ComputeSampled;
                                }))
            << "resource " << id;
}

// The views a pass is given: each slot's own resource, in its slot of TECH_MAP or TECH_TABLE.
TEST_F(FrameTest, EverySlotIsWrittenWithItsOwnResourcesView) {
    render::ResourcePool pool(sharedRenderer().context());
    render::FrameGraph graph(pool, render::FrameSizes{.width = 1, .height = 1});
    render::FilteredBindings bound;
    for (size_t k = 0; k < TECH_MAX_MAPS; ++k)
        for (const bool integer : {false, true}) {
            const render::ResourceId id = graph.declare(
                render::ImageDecl{.name = (integer ? "table " : "map ") + std::to_string(k),
                                  .size = render::SizeClass::Fixed,
                                  .format = integer ? VK_FORMAT_R32_UINT : VK_FORMAT_R32_SFLOAT,
                                  .usage = VK_IMAGE_USAGE_SAMPLED_BIT});
            (integer ? bound.integers : bound.floats)[k] = id;
        }
    bound.compare = graph.declare(render::depthPlaceholderDecl());
    graph.plan(); // the images exist from here
    const render::PassContext c{.cmd = VK_NULL_HANDLE, .graph = graph};
    vk::PushDescriptors descriptors;
    bound.write(descriptors, c, VK_NULL_HANDLE, VK_NULL_HANDLE);
    std::span<const VkWriteDescriptorSet> writes = descriptors.writes();
    ASSERT_EQ(writes.size(), 3u);
    EXPECT_EQ(writes.back().dstBinding, TECH_COMPARE);
    EXPECT_EQ(writes.back().pImageInfo[0].imageView, graph.image(bound.compare).view());
    writes = writes.first(2);
    for (const VkWriteDescriptorSet& w : writes) {
        ASSERT_TRUE(w.dstBinding == TECH_MAP || w.dstBinding == TECH_TABLE);
        ASSERT_EQ(w.descriptorCount, TECH_MAX_MAPS) << "the array whole";
        const auto& ids = w.dstBinding == TECH_MAP ? bound.floats : bound.integers;
        for (size_t k = 0; k < TECH_MAX_MAPS; ++k)
            EXPECT_EQ(w.pImageInfo[k].imageView, graph.image(ids[k]).view())
                << "binding " << w.dstBinding << " slot " << k;
    }
}

TEST_F(FilterTest, TheDeviceSeesEachMapInTheSlotItsModuleGaveIt) {
    constexpr uint32_t kSize = 16;
    std::vector<float> depth(kSize * kSize);
    for (uint32_t t = 0; t < depth.size(); ++t)
        depth[t] = 0.2f + 0.6f * static_cast<float>(t) / static_cast<float>(depth.size());
    std::vector<FilterProbe> probes;
    std::vector<float> under; // the depth texel under each probe
    for (uint32_t y : {1u, 6u, 13u})
        for (uint32_t x : {0u, 7u, 15u}) {
            probes.push_back({.uv = (glm::vec2(x, y) + 0.5f) / static_cast<float>(kSize)});
            under.push_back(depth[y * kSize + x]);
        }
    Renderer& renderer = sharedRenderer();
    // esm lists its exponentials and reads no depth map: every float slot holds them.
    const std::vector<glm::vec4> esm = renderer.probeTechnique(
        Technique::Esm, ParameterValues{}, depth, kSize, probes, ProbeLight{.readSlots = 1});
    // smrt lists its bounds, integers: the depth map in every float slot, the bounds (each the
    // far or near end of the 2x2 depth texels below it) in the first integer slot.
    const std::vector<glm::vec4> smrtFloats = renderer.probeTechnique(
        Technique::Smrt, ParameterValues{}, depth, kSize, probes, ProbeLight{.readSlots = 1});
    const std::vector<glm::vec4> smrtIntegers = renderer.probeTechnique(
        Technique::Smrt, ParameterValues{}, depth, kSize, probes, ProbeLight{.readSlots = 2});
    for (size_t i = 0; i < probes.size(); ++i) {
        const float d = under[i];
        EXPECT_TRUE(std::isfinite(esm[i].x) && esm[i].x != d) << "probe " << i;
        EXPECT_EQ(esm[i].y, esm[i].x) << "probe " << i;
        EXPECT_EQ(esm[i].z, esm[i].x) << "probe " << i;
        EXPECT_EQ(esm[i].w, esm[i].x) << "probe " << i;
        EXPECT_EQ(smrtFloats[i], glm::vec4(d)) << "probe " << i;
        const glm::uvec2 block = glm::uvec2(probes[i].uv * float(kSize)) / 2u * 2u;
        float least = 1.0f, most = 0.0f;
        for (uint32_t dy = 0; dy < 2; ++dy)
            for (uint32_t dx = 0; dx < 2; ++dx) {
                const float texel = depth[(block.y + dy) * kSize + block.x + dx];
                least = std::min(least, texel);
                most = std::max(most, texel);
            }
        EXPECT_TRUE(smrtIntegers[i].x == least || smrtIntegers[i].x == most)
            << "probe " << i << ": " << smrtIntegers[i].x << " not " << least << " or " << most;
    }
}

// A technique's map declared with history: two versions in the pool (and in the memory counted),
// last frame's named `<map> (previous)` wherever the module names maps, and only for such maps.
TEST_F(FrameTest, ATechniquesMapWithHistoryIsReadByItsPreviousName) {
    const shadows::TechniqueModule module{
        .info = {.name = "temporal"},
        .maps = {{.name = "plain", .format = shadows::MapFormat::R32F},
                 {.name = "kept", .format = shadows::MapFormat::R32F, .history = true}},
        .visibilityMaps = {"kept", "kept (previous)"}};
    const ParameterValues defaults;
    const std::vector<render::ImageDecl> decls = render::shadowMapDecls(module, defaults, {});
    ASSERT_EQ(decls.size(), 3u);
    EXPECT_EQ(decls[0].lifetime, render::Lifetime::PerFrame) << "the depth map keeps no history";
    EXPECT_EQ(decls[1].lifetime, render::Lifetime::PerFrame);
    EXPECT_EQ(decls[2].lifetime, render::Lifetime::History);
    const render::FrameSizes sizes{.shadowMapSize = 64, .shadowViews = 3};
    EXPECT_EQ(render::ResourcePool::bytesOf(decls[2], sizes),
              2 * render::ResourcePool::bytesOf(decls[1], sizes))
        << "both versions counted";
    render::BufferDecl buffer{
        .name = "b", .size = render::SizeClass::Fixed, .bytes = 64, .usage = 0};
    const uint64_t once = render::ResourcePool::bytesOf(buffer, sizes);
    buffer.lifetime = render::Lifetime::History;
    EXPECT_EQ(render::ResourcePool::bytesOf(buffer, sizes), 2 * once) << "a buffer's too";

    render::ResourcePool pool(sharedRenderer().context());
    render::FrameGraph graph(pool, sizes);
    render::FrameResources r;
    r.depthMap = graph.declare(decls[0]);
    r.declareOwnMaps(graph, module, std::span(decls).subspan(1));
    const render::ResourceId kept = r.named(module, "kept");
    EXPECT_EQ(r.named(module, "kept (previous)"), graph.previous(kept));
    EXPECT_NE(r.named(module, "kept (previous)"), kept);
    const shadows::VisibilitySlots slots = shadows::visibilitySlots(module, defaults);
    EXPECT_EQ(slots.floats[0], "kept");
    EXPECT_EQ(slots.floats[1], "kept (previous)");
    EXPECT_EQ(slots.floats[2], "kept") << "no depth map read: the first map in the slots left";

    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(r.named(module, "plain (previous)"),
                 "technique temporal keeps no history of 'plain'");
    shadows::TechniqueModule without = module;
    without.visibilityMaps = {"plain (previous)"};
    EXPECT_DEATH(shadows::visibilitySlots(without, defaults),
                 "reads last frame's plain, declared without history");
}
