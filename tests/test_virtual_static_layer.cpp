// Virtual maps' static layer (virtual.staticLayer; docs/techniques.md, "Static and dynamic
// casters"): a page under a caster that moved before keeps the casters no pose has moved in a
// second pool, copied back under the moving ones. Every light type, frame by frame against a
// renderer made fresh on each pose and against the same poses without the layer: the same bits;
// the pages that kept their layer counted; a caster's first move draws the layers again.
#include "analytic_scenes.h"
#include "penumbra/error.h"
#include "truth_fixture.h"

#include <cstring>
#include <numeric>

using namespace penumbra;
using namespace penumbra::test;

namespace {

RenderOptions options(bool staticLayer) {
    RenderOptions o{.width = 320,
                    .height = 240,
                    .shadowMapSize = 1024,
                    .frames = 1,
                    .technique = Technique::Pcf};
    o.parameters.set("virtual.enabled", "1");
    o.parameters.set("virtual.staticLayer", staticLayer ? "1" : "0");
    return o;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

uint32_t sum(const std::vector<uint32_t>& v) {
    return std::accumulate(v.begin(), v.end(), 0u);
}

// `scene` with the vertices from `first` to `last` moved by `by`.
Scene moved(Scene scene, size_t first, size_t last, glm::vec3 by) {
    for (size_t v = first; v < last; ++v)
        scene.vertices[v].position += by;
    return scene;
}

// restingObjects under `light` with three small balls beside them, and the poses the tests step
// through: ball A slides three times; C slides for the first time; B for the first time while C
// slides again (a first move among triangles before a caster that moved already); then A again.
struct Balls {
    std::vector<Scene> poses;
    std::vector<bool> firstMove; // poses[i] moves a caster no earlier pose moved
};
Balls balls(const Light& light) {
    Scene start = restingObjects(light);
    const size_t a = start.vertices.size();
    MeshBuilder(start).sphere({-1.2f, 0.9f, -1.0f}, 0.25f, 1);
    const size_t b = start.vertices.size();
    MeshBuilder(start).sphere({1.3f, 0.8f, 0.9f}, 0.2f, 1);
    const size_t c = start.vertices.size();
    MeshBuilder(start).sphere({-0.6f, 1.0f, 1.2f}, 0.2f, 1);
    const size_t end = start.vertices.size();
    Balls t{.poses = {start}, .firstMove = {false}};
    auto step = [&](std::vector<std::pair<size_t, size_t>> ranges, glm::vec3 by, bool firstMove) {
        Scene next = t.poses.back();
        for (const auto& [first, last] : ranges)
            next = moved(next, first, last, by);
        t.poses.push_back(std::move(next));
        t.firstMove.push_back(firstMove);
    };
    step({{a, b}}, {0.25f, 0.0f, 0.1f}, true);
    step({{a, b}}, {0.2f, 0.05f, 0.1f}, false);
    step({{a, b}}, {-0.1f, 0.0f, 0.25f}, false);
    step({{c, end}}, {0.2f, 0.0f, -0.2f}, true);
    step({{b, c}, {c, end}}, {-0.2f, 0.0f, -0.15f}, true);
    step({{a, b}}, {0.15f, 0.0f, 0.0f}, false);
    return t;
}

} // namespace

TEST_F(VirtualTest, AStaticLayerGivesTheSameBitsAndRedrawsOnlyWhatMoved) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Balls t = balls(light);
        SceneRenderer layered(sharedRenderer(), t.poses[0]), whole(sharedRenderer(), t.poses[0]);
        layered.render(options(true));
        whole.render(options(false));
        for (size_t i = 1; i < t.poses.size(); ++i) {
            layered.repose(t.poses[i]);
            whole.repose(t.poses[i]);
            const RenderResult got = layered.render(options(true));
            const RenderResult without = whole.render(options(false));
            const VirtualMapInfo& pages = *got.virtualMaps;
            const uint32_t rendered = sum(pages.renderedPerFrame);
            std::printf("%s, pose %zu: %u pages rendered, %u of the last frame's %u kept their "
                        "static layer\n",
                        light.name.c_str(), i, rendered, pages.staticHeld, pages.rendered);
            EXPECT_EQ(rendered, sum(without.virtualMaps->renderedPerFrame)) << light.name << i;
            EXPECT_EQ(without.virtualMaps->staticHeld, 0u) << light.name << i;
            EXPECT_EQ(pages.poolBytes, 2 * without.virtualMaps->poolBytes) << light.name << i;
            // The pose's pages render in the first frame: its warm-up; the timed one is cached.
            EXPECT_EQ(pages.renderedPerFrame.back(), 0u) << light.name << i;
            SceneRenderer fresh(sharedRenderer(), t.poses[i]);
            const RenderResult want = fresh.render(options(false));
            EXPECT_TRUE(sameBits(got.visibility[0], want.visibility[0])) << light.name << i;
            EXPECT_TRUE(sameBits(without.visibility[0], want.visibility[0])) << light.name << i;
        }
    }
}

// The counts of the frame that renders a pose's pages: a render of one frame with no warm-up
// (a continuing frame) renders the requests of the frame before on the new pose. Its pages are
// those under what moved, in their places (with their layers unless a caster moved for the first
// time), and those the moved casters' own surfaces ask for anew (placed afresh: the pool's
// growth, nothing evicted).
TEST_F(VirtualTest, OnlyAFirstMoveDrawsTheStaticLayersAgain) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Balls t = balls(light);
        SceneRenderer layered(sharedRenderer(), t.poses[0]);
        RenderOptions o = options(true);
        uint32_t resident = layered.render(o).virtualMaps->resident;
        for (size_t i = 1; i < t.poses.size(); ++i) {
            layered.repose(t.poses[i]);
            const RenderResult got = layered.render(o, {.continues = true});
            const VirtualMapInfo& pages = *got.virtualMaps;
            std::printf("%s, pose %zu: %u rendered, %u kept their static layer (%u requested, %u "
                        "cached, %u resident)\n",
                        light.name.c_str(), i, pages.rendered, pages.staticHeld, pages.requested,
                        pages.cached, pages.resident);
            ASSERT_EQ(pages.renderedPerFrame.size(), 1u);
            ASSERT_EQ(pages.evicted, 0u);
            EXPECT_GT(pages.rendered, 0u) << light.name << i;
            if (t.firstMove[i]) {
                EXPECT_EQ(pages.staticHeld, 0u) << light.name << i;
            } else {
                EXPECT_GT(pages.staticHeld, 0u) << light.name << i;
                EXPECT_EQ(pages.staticHeld, pages.rendered - (pages.resident - resident))
                    << light.name << i;
            }
            resident = pages.resident;
        }
    }
}

// The layer turned off and on again between poses: the static pool made anew holds no layer, so
// the cache starts again; the images are those of the same poses without the layer throughout
// (the same pages in the same places of the pool).
TEST_F(VirtualTest, TurningTheLayerOffAndOnAgainKeepsNoOldLayer) {
    const Light light = sharpSun();
    const Balls t = balls(light);
    SceneRenderer toggled(sharedRenderer(), t.poses[0]), whole(sharedRenderer(), t.poses[0]);
    const std::vector<bool> layerOn{true, true, true, false, true, true, true};
    for (size_t i = 0; i < t.poses.size(); ++i) {
        if (i > 0) {
            toggled.repose(t.poses[i]);
            whole.repose(t.poses[i]);
        }
        const RenderResult got = toggled.render(options(layerOn[i]));
        const RenderResult want = whole.render(options(false));
        EXPECT_TRUE(sameBits(got.visibility[0], want.visibility[0])) << i;
    }
}

// With the device's decisions there is no static layer: the default is dropped, an explicit one
// refused naming the parameter.
TEST_F(VirtualTest, TheDevicesDecisionsKeepNoStaticLayer) {
    const Scene scene = restingObjects(sharpSpot());
    SceneRenderer renderer(sharedRenderer(), scene);
    RenderOptions o = options(true);
    o.parameters = {};
    o.parameters.set("virtual.enabled", "1");
    o.parameters.set("virtual.deviceDecides", "1");
    const RenderResult got = renderer.render(o);
    EXPECT_EQ(got.virtualMaps->staticHeld, 0u);
    RenderOptions plain = o;
    plain.parameters.set("virtual.staticLayer", "0");
    EXPECT_EQ(got.virtualMaps->poolBytes, renderer.render(plain).virtualMaps->poolBytes);
    o.parameters.set("virtual.staticLayer", "1");
    try {
        renderer.render(o);
        ADD_FAILURE() << "an explicit static layer on the device's decisions was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("virtual.staticLayer"), std::string::npos) << e.what();
    }
}
