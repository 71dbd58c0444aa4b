// The frame graph's order within a phase (src/render/frame_order.cpp): by what passes read and
// write, whatever order the code added them in. Each case has a pass ("late") declared after the
// ones that need it, so that declaration order alone would be wrong; the graph's checks (a read
// of what no earlier pass wrote is fatal) would then abort the plan.
#include "gpu_fixture.h"
#include "render/frame_graph.h"

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

namespace {

const FrameSizes kSizes{.width = 4, .height = 4};

ImageDecl image(std::string name) {
    return {.name = std::move(name),
            .size = SizeClass::Screen,
            .format = VK_FORMAT_R32_SFLOAT,
            .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
            .lifetime = Lifetime::Persistent}; // outlives the frame: nothing culled
}

void add(FrameGraph& graph, std::string name, std::vector<Use> uses,
         Phase phase = Phase::PerLight) {
    graph.addPass({.name = std::move(name),
                   .cost = CostGroup::PerPixel,
                   .phase = phase,
                   .uses = std::move(uses),
                   .record = [](PassContext&) {}});
}

std::vector<std::string> order(FrameGraph& graph) {
    std::vector<std::string> names;
    for (const PlannedPass& p : graph.plan())
        names.push_back(graph.passes()[p.pass].name);
    return names;
}

using Names = std::vector<std::string>;

} // namespace

TEST_F(FrameTest, APassRunsAfterWhatItReadsWhereverItWasAdded) {
    ResourcePool pool(sharedRenderer().context());
    FrameGraph graph(pool, kSizes);
    const ResourceId b = graph.declare(image("b")), c = graph.declare(image("c"));
    add(graph, "third", {{c, Access::ComputeSampled}});
    add(graph, "other", {});
    add(graph, "second", {{b, Access::ComputeSampled}, {c, Access::ComputeWrite}});
    add(graph, "first", {{b, Access::ComputeWrite}});
    add(graph, "earlier phase", {}, Phase::GBuffer);
    EXPECT_EQ(order(graph), (Names{"earlier phase", "other", "first", "second", "third"}));
}

TEST_F(FrameTest, AReadComesAfterTheWriteDeclaredBeforeIt) {
    ResourcePool pool(sharedRenderer().context());
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(image("a")), z = graph.declare(image("z"));
    add(graph, "write", {{a, Access::ComputeWrite}, {z, Access::ComputeSampled}});
    add(graph, "read", {{a, Access::ComputeSampled}});
    add(graph, "late", {{z, Access::ComputeWrite}});
    EXPECT_EQ(order(graph), (Names{"late", "write", "read"}));
}

TEST_F(FrameTest, WritesKeepTheirDeclaredOrder) {
    ResourcePool pool(sharedRenderer().context());
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(image("a")), z = graph.declare(image("z"));
    add(graph, "first", {{a, Access::ComputeWrite}, {z, Access::ComputeSampled}});
    add(graph, "second", {{a, Access::ComputeReadWrite}});
    add(graph, "late", {{z, Access::ComputeWrite}});
    EXPECT_EQ(order(graph), (Names{"late", "first", "second"}));
}

TEST_F(FrameTest, AWriteWaitsForTheReadsOfWhatCameBefore) {
    ResourcePool pool(sharedRenderer().context());
    FrameGraph graph(pool, kSizes);
    const ResourceId a = graph.declare(image("a")), z = graph.declare(image("z"));
    add(graph, "write", {{a, Access::ComputeWrite}});
    add(graph, "read", {{a, Access::ComputeSampled}, {z, Access::ComputeSampled}});
    add(graph, "rewrite", {{a, Access::ComputeReadWrite}});
    add(graph, "late", {{z, Access::ComputeWrite}});
    EXPECT_EQ(order(graph), (Names{"write", "late", "read", "rewrite"}));
}

TEST_F(FrameTest, PassesThatReadWhatEachOtherWriteAreACycle) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto cycle = [] {
        ResourcePool pool(sharedRenderer().context());
        FrameGraph graph(pool, kSizes);
        const ResourceId x = graph.declare(image("x")), y = graph.declare(image("y"));
        add(graph, "a", {{x, Access::ComputeSampled}, {y, Access::ComputeWrite}});
        add(graph, "b", {{y, Access::ComputeSampled}, {x, Access::ComputeWrite}});
        graph.plan();
    };
    EXPECT_DEATH(cycle(), "passes \"a\", \"b\" read what each other writes \\(a cycle\\)");
    // Across phases the phase order stands: a read of what only a later phase writes.
    const auto tooEarly = [] {
        ResourcePool pool(sharedRenderer().context());
        FrameGraph graph(pool, kSizes);
        const ResourceId x = graph.declare(BufferDecl{.name = "x",
                                                      .size = SizeClass::Fixed,
                                                      .bytes = 16,
                                                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                      .lifetime = Lifetime::Persistent});
        add(graph, "write", {{x, Access::ComputeWrite}});
        add(graph, "read", {{x, Access::ComputeRead}}, Phase::LightSpace);
        graph.plan();
    };
    EXPECT_DEATH(tooEarly(), "reads x, which only a later pass writes");
}
