// What the frame graph (src/render/frame_graph.h) refuses, every frame, as programmer errors that
// name the pass and the resource: a read of what nothing wrote, a write nobody reads, a pass
// that contradicts its own uses, a late pass, a name declared twice unlike, a timed pass without
// its cost group.
#include "frame_graph_passes.h"
#include "penumbra/error.h"

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

TEST_F(FrameTest, ReadingWhatNothingWroteIsAProgrammerError) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            ResourcePool pool(context());
            FrameGraph graph(pool, kSizes);
            const ResourceId image = graph.declare(screenImage("never written"));
            graph.addPass(pass("read", Phase::PerLight, {{image, Access::ComputeSampled}}));
            graph.plan();
        },
        "reads never written, which no earlier pass writes");
}

// The reads and writes are checked every frame, not only a resource's first: last frame's
// contents of a per-frame image are not there to read, a persistent one's only while its key
// holds; a read of what only a later pass writes (a cycle through the phases) and a write
// nothing kept reads are errors too.
TEST_F(FrameTest, ReadsAndWritesAreCheckedEveryFrame) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto frames = [](Lifetime lifetime, bool secondWrites, uint64_t secondKey) {
        ResourcePool pool(context());
        for (int frame = 0; frame < 2; ++frame) {
            FrameGraph graph(pool, kSizes);
            ImageDecl decl = screenImage("image", lifetime);
            decl.key = frame == 0 ? 1 : secondKey;
            const ResourceId image = graph.declare(decl);
            const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
            if (frame == 0 || secondWrites)
                graph.addPass(pass("write", Phase::ScreenSpace, {{image, Access::ComputeWrite}}));
            graph.addPass(pass("read", Phase::PerLight,
                               {{image, Access::ComputeSampled}, {out, Access::ComputeWrite}}));
            context().submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd, nullptr); });
        }
    };
    frames(Lifetime::PerFrame, true, 1);
    frames(Lifetime::Persistent, false, 1); // its key kept its contents
    EXPECT_DEATH(frames(Lifetime::PerFrame, false, 1), "reads image, which no earlier pass writes");
    EXPECT_DEATH(frames(Lifetime::Persistent, false, 2), "reads image, which no earlier pass");
    const auto oneFrame = [](Phase writer, bool read) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image"));
        const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
        graph.addPass(
            pass("write", writer, {{image, Access::ComputeWrite}, {out, Access::ComputeWrite}}));
        if (read)
            graph.addPass(pass("read", Phase::ScreenSpace,
                               {{image, Access::ComputeSampled}, {out, Access::ComputeReadWrite}}));
        graph.plan();
    };
    oneFrame(Phase::LightSpace, true);
    EXPECT_DEATH(oneFrame(Phase::PerLight, true), "reads image, which only a later pass writes");
    EXPECT_DEATH(oneFrame(Phase::LightSpace, false), "writes image, which no later pass reads");
    // A read-write is a read: of nothing, when it comes first; and its write needs a reader.
    const auto readWrite = [](bool written, bool readAfter) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image"));
        const ResourceId out = graph.declare(screenImage("out", Lifetime::Persistent));
        if (written)
            graph.addPass(pass("write", Phase::ScreenSpace, {{image, Access::ComputeWrite}}));
        graph.addPass(pass("layer", Phase::PerLight,
                           {{image, Access::ComputeReadWrite}, {out, Access::ComputeWrite}}));
        if (readAfter)
            graph.addPass(pass("read", Phase::Composite,
                               {{image, Access::ComputeSampled}, {out, Access::ComputeReadWrite}}));
        graph.plan();
    };
    readWrite(true, true);
    EXPECT_DEATH(readWrite(false, true), "\"layer\" reads image, which no earlier pass writes");
    EXPECT_DEATH(readWrite(true, false), "\"layer\" writes image, which no later pass reads");
}

// Declarations that contradict themselves are programmer errors, named: one pass using a
// resource in two ways, a pass added after the plan, one name declared twice with different keys
// or shapes in a frame.
TEST_F(FrameTest, DeclarationsThatContradictThemselvesAreFatal) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto twoUses = [](Access second) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image"));
        graph.addPass(pass("write", Phase::ScreenSpace, {{image, Access::ComputeWrite}}));
        graph.addPass(
            pass("read", Phase::Composite, {{image, Access::ComputeSampled}, {image, second}}));
        graph.plan();
    };
    twoUses(Access::ComputeSampled); // the same use listed twice: one barrier, no error
    EXPECT_DEATH(twoUses(Access::ComputeRead), "pass read uses image in two ways");
    const auto late = [] {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image", Lifetime::Persistent));
        graph.addPass(pass("write", Phase::ScreenSpace, {{image, Access::ComputeWrite}}));
        graph.plan();
        graph.addPass(pass("late", Phase::Composite, {{image, Access::ComputeSampled}}));
    };
    EXPECT_DEATH(late(), "a pass added after the frame was planned");
    const auto twice = [](ImageDecl second) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        ImageDecl first = screenImage("image", Lifetime::Persistent);
        first.key = 1;
        graph.declare(first);
        graph.declare(second);
    };
    ImageDecl same = screenImage("image", Lifetime::Persistent);
    same.key = 1;
    twice(same); // declared twice alike: the same resource
    ImageDecl otherKey = same;
    otherKey.key = 2;
    EXPECT_DEATH(twice(otherKey), "image declared twice with different keys");
    ImageDecl otherFormat = same;
    otherFormat.format = VK_FORMAT_R32G32_SFLOAT;
    EXPECT_DEATH(twice(otherFormat), "image declared twice differently");
}

// A pass's cost group is part of its declaration: a timed pass without one, or an untimed one
// with one, is a programmer error the plan reports every frame.
TEST_F(FrameTest, ATimedPassDeclaresItsCostGroupAndAnUntimedOneNone) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const auto planned = [](std::string name, std::optional<CostGroup> cost) {
        ResourcePool pool(context());
        FrameGraph graph(pool, kSizes);
        const ResourceId image = graph.declare(screenImage("image", Lifetime::Persistent));
        graph.addPass({.name = std::move(name),
                       .cost = cost,
                       .phase = Phase::PerLight,
                       .uses = {{image, Access::ComputeWrite}},
                       .record = [](PassContext&) {}});
        graph.plan();
    };
    EXPECT_DEATH(planned("visibility", std::nullopt), "visibility\" is timed but declares no");
    EXPECT_DEATH(planned("", CostGroup::ShadowMaps), "is untimed but declares a cost group");
    planned("visibility", CostGroup::PerPixel); // and these plan
    planned("", std::nullopt);
}

// An image past the device's largest is refused as the user's error, naming what sets its size:
// the option for every shadow view's map, the image's own name for the others.
TEST_F(FrameTest, AnImagePastTheDevicesLargestNamesWhatSizesIt) {
    const uint32_t limit = context().limits().maxImageDimension2D;
    for (const bool shadowView : {false, true}) {
        ResourcePool pool(context());
        FrameGraph graph(pool, shadowView ? FrameSizes{.shadowMapSize = limit + 1, .shadowViews = 1}
                                          : FrameSizes{.width = limit + 1, .height = 2});
        ImageDecl decl = screenImage("wide");
        if (shadowView)
            decl.size = SizeClass::ShadowView;
        const ResourceId image = graph.declare(decl);
        graph.markOutput(image);
        graph.addPass(pass("write", Phase::LightSpace, {{image, Access::ComputeWrite}}));
        try {
            graph.plan();
            ADD_FAILURE() << "an image of " << limit + 1 << " texels a side was made";
        } catch (const InputError& e) {
            EXPECT_EQ(e.subject(), shadowView ? "--shadow-map-size" : "wide");
            EXPECT_NE(std::string(e.what()).find(std::to_string(limit)), std::string::npos)
                << e.what();
        }
    }
}
