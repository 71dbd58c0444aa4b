// A technique's map kept with history, as its post passes see it (MapDecl::history,
// PostPassPush::size.w): shaders/history_average.comp averages this frame's value (the depth map,
// cleared to a value per frame) with last frame's average, and starts again where the graph says
// last frame's version holds nothing: the first frame, views that moved (historyKeyOf), a cut.
#include "frame_clears.h"
#include "gpu_fixture.h"
#include "render/frame.h"
#include "render/frame_targets.h"
#include "render/pipelines.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/sync.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

namespace {

constexpr uint32_t kMapSize = 4;
const FrameSizes kSizes{.width = 1, .height = 1, .shadowMapSize = kMapSize, .shadowViews = 1};

const shadows::TechniqueModule kAveraging{
    .info = {.name = "averaging"},
    .maps = {{.name = "average", .format = shadows::MapFormat::R32F, .history = true}},
    .postPasses = {{.shader = "history_average.comp",
                    .inputs = {shadows::kDepthMap, "average (previous)"},
                    .outputs = {"average"}}}};

std::vector<ShadowView> viewsAt(float x) {
    LightProjection projection;
    projection.viewProj = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f));
    return {{.light = 0, .projection = projection}};
}

struct Harness {
    const vk::Context& ctx = sharedRenderer().context();
    ResourcePool pool{ctx};
    FramePipelines pipelines{ctx};
    vk::Buffer params =
        vk::createBuffer(ctx, TECHNIQUE_BLOCK_BYTES, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                         vk::MemoryUse::Upload, "params");
    vk::Buffer views =
        vk::createBuffer(ctx, sizeof(gpu::ShadowViewData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                         vk::MemoryUse::Upload, "views");
    vk::SamplerHandle nearest = vk::createSampler(ctx, {});

    // One frame: the depth map cleared to `depth`, the module's post pass, the average read back
    // (every texel, which must agree).
    float frame(float depth, const std::vector<ShadowView>& shadowViews) {
        FrameGraph graph(pool, kSizes);
        std::vector<ImageDecl> decls = shadowMapDecls(kAveraging, ParameterValues{}, shadowViews);
        decls[1].usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT; // read back by this test
        FrameResources r;
        r.depthMap = graph.declare(decls[0]);
        r.declareOwnMaps(graph, kAveraging, std::span(decls).subspan(1));
        r.params = graph.importBuffer("params", params.get());
        r.views = graph.importBuffer("views", views.get());
        const ResourceId average = r.named(kAveraging, "average");
        const ResourceId host =
            graph.declare(BufferDecl{.name = "host",
                                     .size = SizeClass::Fixed,
                                     .bytes = kMapSize * kMapSize * sizeof(float),
                                     .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     .memory = vk::MemoryUse::Readback});
        graph.addPass({.name = "shadow",
                       .cost = CostGroup::ShadowMaps,
                       .phase = Phase::LightSpace,
                       .uses = {{r.depthMap, Access::DepthAttachment}},
                       .record = [&](PassContext& c) {
                           clearThrough(c.cmd, c.image(r.depthMap).layer(0), {kMapSize, kMapSize},
                                        true, depth);
                       }});
        const FrameInputs inputs{
            .views = views.get(), .params = params.get(), .nearest = nearest.get()};
        addPostPasses(graph, pipelines, kAveraging, ParameterValues{}, 1, inputs, r);
        graph.addPass({.name = "",
                       .phase = Phase::Readback,
                       .uses = {{average, Access::TransferRead}, {host, Access::TransferWrite}},
                       .record = [&](PassContext& c) {
                           vk::copyImageToBuffer(c.cmd, c.image(average).get(), c.buffer(host));
                       }});
        graph.plan();
        ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        std::vector<float> read(size_t{kMapSize} * kMapSize);
        std::memcpy(read.data(), pool.mapped("host"), read.size() * sizeof(float));
        for (float v : read)
            EXPECT_EQ(v, read.front()) << "every texel alike";
        return read.front();
    }
};

} // namespace

TEST_F(FrameTest, APostPassKnowsWhetherLastFramesMapHoldsItsContents) {
    Harness h;
    const std::vector<ShadowView> here = viewsAt(0.0f), moved = viewsAt(0.5f);
    EXPECT_FLOAT_EQ(h.frame(0.1f, here), 0.1f) << "the first frame: no history";
    const float second = 0.5f * (0.3f + 0.1f);
    EXPECT_FLOAT_EQ(h.frame(0.3f, here), second) << "last frame's average, said held";
    EXPECT_FLOAT_EQ(h.frame(0.5f, here), 0.5f * (0.5f + second));
    EXPECT_FLOAT_EQ(h.frame(0.5f, moved), 0.5f) << "views that moved drop the history";
    EXPECT_FLOAT_EQ(h.frame(0.1f, moved), 0.5f * (0.1f + 0.5f));
    h.pool.invalidateHistory();
    EXPECT_FLOAT_EQ(h.frame(0.7f, moved), 0.7f) << "a cut drops it";
    EXPECT_FLOAT_EQ(h.frame(0.9f, moved), 0.5f * (0.9f + 0.7f));
}

// The key of a map kept with history follows the views' projections and lights; other maps are
// keyed by nothing (their contents never outlive a frame).
TEST(FrameHistoryKey, FollowsEachViewsProjectionAndLight) {
    const std::vector<ImageDecl> here = shadowMapDecls(kAveraging, ParameterValues{}, viewsAt(0));
    ASSERT_EQ(here.size(), 2u);
    EXPECT_EQ(here[0].key, 0u);
    EXPECT_EQ(here[1].lifetime, Lifetime::History);
    EXPECT_EQ(here[1].key, historyKeyOf(viewsAt(0)));
    EXPECT_EQ(historyKeyOf(viewsAt(0)), historyKeyOf(viewsAt(0)));
    EXPECT_NE(historyKeyOf(viewsAt(0)), historyKeyOf(viewsAt(1e-6f)));
    std::vector<ShadowView> otherLight = viewsAt(0);
    otherLight[0].light = 1;
    EXPECT_NE(historyKeyOf(otherLight), historyKeyOf(viewsAt(0)));
    std::vector<ShadowView> perspective = viewsAt(0);
    perspective[0].projection.perspective = true;
    EXPECT_NE(historyKeyOf(perspective), historyKeyOf(viewsAt(0)));
    std::vector<ShadowView> two = viewsAt(0);
    two.push_back(two.front());
    EXPECT_NE(historyKeyOf(two), historyKeyOf(viewsAt(0))) << "a view more";
}
