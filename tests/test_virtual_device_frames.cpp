// Virtual pages decided on the device within the frame (virtual.deviceDecides;
// src/render/page_decision_passes.h, page_draw_passes.h): the same shadows as the host's
// decisions for every light type and for alpha-tested casters, with one warm-up frame instead of
// two; a camera, light or caster that moves shows in its first frame (no pop-in, where the host's
// decisions, a frame late, read coarser pages); a moved caster re-renders only the pages under
// it; a pool that lost its contents renders every page again.
#include "analytic_scenes.h"
#include "gpu_fixture.h"
#include "page_passes.h"
#include "penumbra/error.h"

#include <cmath>
#include <cstring>
#include <numeric>

using namespace penumbra;
using namespace penumbra::test;

namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;
const Sets kHost{{"virtual.enabled", "1"}};
const Sets kDevice{{"virtual.enabled", "1"}, {"virtual.deviceDecides", "1"}};
// The casters' fixed bias, ten times its default constant (the default, adaptive, biases
// receivers alone): the page draws' own bias then decides what casts, and a sign slip shows as
// acne across lit surfaces.
const Sets kHostBiased{
    {"virtual.enabled", "1"}, {"bias.mode", "fixed"}, {"bias.constant", "0.005"}};
const Sets kDeviceBiased{{"virtual.enabled", "1"},
                         {"virtual.deviceDecides", "1"},
                         {"bias.mode", "fixed"},
                         {"bias.constant", "0.005"}};

RenderOptions options(const Sets& sets, uint32_t frames = 1) {
    RenderOptions o{.width = 320,
                    .height = 240,
                    .shadowMapSize = 1024,
                    .frames = frames,
                    .technique = Technique::Hard};
    for (const auto& [key, value] : sets)
        o.parameters.set(key, value);
    return o;
}

uint32_t sum(const std::vector<uint32_t>& v) {
    return std::accumulate(v.begin(), v.end(), 0u);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Pixels (of those `want` covers) whose visibility differs, over every light.
size_t differing(const RenderResult& got, const RenderResult& want) {
    size_t n = 0;
    for (size_t l = 0; l < want.visibility.size(); ++l)
        for (size_t i = 0; i < want.visibility[l].size(); ++i) {
            const float a = got.visibility[l][i], b = want.visibility[l][i];
            n += !std::isnan(b) && !(std::abs(a - b) <= 1e-6f);
        }
    return n;
}

size_t covered(const RenderResult& r) {
    size_t n = 0;
    for (const std::vector<float>& v : r.visibility)
        for (float x : v)
            n += !std::isnan(x);
    return n;
}

// builtin:foliage's alpha-tested canopy under its sun and a spot above it: masked casters drawn
// by both pipelines (orthographic and perspective pages).
Scene foliageUnderSpot() {
    Scene scene = builtin::foliage();
    const glm::vec3 centre = 0.5f * (builtin::kCanopyMin + builtin::kCanopyMax);
    scene.lights.push_back({.name = "spot",
                            .type = LightType::Spot,
                            .position = centre + glm::vec3(0.5f, 3.0f, 0.5f),
                            .direction = glm::normalize(glm::vec3(-0.1f, -1.0f, -0.1f)),
                            .intensity = 40.0f,
                            .outerConeAngle = 0.9f});
    return scene;
}

} // namespace

// The host's decisions and the device's draw the same pages with the same shadows: for a sun, a
// spot, a point light (six faces) and alpha-tested casters under a sun and a spot. Rasterizing a
// page through the pool's viewport rather than its own rounds vertices differently: at most a
// pixel in a thousand may differ (measured: none on the resting objects, 5 of 57,600 on
// foliage). The device renders in the frame that asks: one warm-up frame, every page in it.
TEST_F(VirtualTest, PagesDecidedOnTheDeviceShadowAsTheHostsDo) {
    std::vector<Scene> scenes;
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()})
        scenes.push_back(restingObjects(light));
    scenes.push_back(foliageUnderSpot());
    for (const Scene& s : scenes) {
        const std::string name = s.lights.back().name + (s.lights.size() > 1 ? " (foliage)" : "");
        SceneRenderer host(sharedRenderer(), s), device(sharedRenderer(), s);
        const RenderResult want = host.render(options(kHostBiased, 2));
        const RenderResult got = device.render(options(kDeviceBiased, 2));
        ASSERT_TRUE(got.virtualMaps) << name;
        const VirtualMapInfo& d = *got.virtualMaps;
        const VirtualMapInfo& h = *want.virtualMaps;
        const size_t differ = differing(got, want), pixels = covered(want);
        std::printf("%s: %u pages resident (host %u), %zu of %zu pixels differ\n", name.c_str(),
                    d.resident, h.resident, differ, pixels);
        EXPECT_LE(differ * 1000, pixels) << name;
        EXPECT_EQ(d.resident, h.resident) << name;
        EXPECT_EQ(d.requested, h.requested) << name;
        EXPECT_EQ(d.cached, d.requested) << name << ": the timed frames render nothing";
        ASSERT_EQ(d.renderedPerFrame.size(), 3u) << name << ": one warm-up, two timed frames";
        EXPECT_EQ(d.renderedPerFrame[0], d.resident) << name << ": every page in the first";
        EXPECT_GT(d.resident, 0u) << name;
        EXPECT_EQ(d.renderedPerFrame[1] + d.renderedPerFrame[2], 0u) << name;
        EXPECT_EQ(d.dropped, 0u) << name;
    }
}

// A camera that moves in (its pixels ask for finer pages) and aside, then a light that moves, show
// in their first frame: it equals a fresh renderer's steady image of the new view; the old view's
// pages stay resident beside the new ones, a moved light's go. The host's decisions, a frame
// behind, render fewer pages in the camera's frame and read coarser ones where the new ones are
// missing (pop-in; with hard shadows 11, 15 and 2 pixels on lavapipe): the scenario asks for
// pages the frame before did not.
TEST_F(VirtualTest, OnTheDeviceAMoveShowsInItsFirstFrame) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Scene s = restingObjects(light);
        Camera moved = s.camera("");
        // Halfway in (its pixels read finer levels) and aside.
        const glm::vec3 aside =
            0.3f * glm::normalize(glm::cross(moved.target - moved.position, glm::vec3(0, 1, 0)));
        moved.position = 0.5f * (moved.position + moved.target) + aside;
        moved.target += aside;
        std::vector<Light> lights = s.lights;
        if (light.type == LightType::Directional)
            lights[0].direction =
                glm::normalize(lights[0].direction + glm::vec3(0.05f, 0.0f, 0.0f));
        else
            lights[0].position += glm::vec3(0.1f, 0.0f, 0.05f);
        size_t popIn[2] = {0, 0};
        uint32_t pages[2] = {0, 0};
        for (const bool onDevice : {false, true}) {
            const RenderOptions o = options(onDevice ? kDevice : kHost);
            const char* path = onDevice ? "device" : "host";
            SceneRenderer scene(sharedRenderer(), s);
            scene.render(o);
            // The camera alone.
            const RenderResult turned = scene.render(o, {.camera = moved, .continues = true});
            SceneRenderer fresh(sharedRenderer(), s);
            const RenderResult steady = fresh.render(o, {.camera = moved});
            popIn[onDevice] = differing(turned, steady);
            pages[onDevice] = sum(turned.virtualMaps->renderedPerFrame);
            std::printf("%s, %s: the first frame after the camera moved differs from the steady "
                        "one in %zu of %zu pixels (%u pages rendered)\n",
                        light.name.c_str(), path, popIn[onDevice], covered(steady),
                        pages[onDevice]);
            if (!onDevice)
                continue;
            // The pages of the view before stay resident beside the new view's.
            EXPECT_GT(turned.virtualMaps->resident, steady.virtualMaps->resident) << light.name;
            EXPECT_LE(popIn[1] * 1000, covered(steady)) << light.name;
            EXPECT_EQ(turned.virtualMaps->cached + pages[1] + turned.virtualMaps->dropped,
                      turned.virtualMaps->requested)
                << light.name;
            // Then the light: its pages go, this frame's are drawn.
            const RenderResult lit =
                scene.render(o, {.camera = moved, .lights = lights, .continues = true});
            SceneRenderer freshLit(sharedRenderer(), s);
            const RenderResult steadyLit = freshLit.render(o, {.camera = moved, .lights = lights});
            const size_t litPopIn = differing(lit, steadyLit);
            std::printf("%s, %s: the first frame after the light moved differs in %zu pixels\n",
                        light.name.c_str(), path, litPopIn);
            EXPECT_LE(litPopIn * 1000, covered(steadyLit)) << light.name;
            EXPECT_EQ(lit.virtualMaps->resident, steadyLit.virtualMaps->resident) << light.name;
        }
        // The host renders what the frame before asked for; the device what this one asks for.
        EXPECT_GT(pages[1], pages[0]) << light.name << ": the move asks for new pages";
    }
}

// A small caster that moves re-renders only the pages it was and is over (under 5% of those
// resident, as on the host), in the frame it moved; the image equals a fresh renderer's of the
// new pose. A render without virtual maps frees the pool: the next one renders every page again
// and shows what the first did.
TEST_F(VirtualTest, OnTheDeviceAMovedCasterRendersOnlyThePagesItCovers) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const auto [before, after] = slidBall(light);
        SceneRenderer scene(sharedRenderer(), before);
        const RenderOptions o = options(kDevice);
        const RenderResult old = scene.render(o);
        scene.repose(after);
        const RenderResult moved = scene.render(o, {.continues = true});
        const uint32_t rendered = sum(moved.virtualMaps->renderedPerFrame);
        std::printf("%s: %u pages resident, %u rendered in the frame the ball moved\n",
                    light.name.c_str(), moved.virtualMaps->resident, rendered);
        EXPECT_GT(rendered, 0u) << light.name;
        EXPECT_LE(rendered * 20, moved.virtualMaps->resident) << light.name;
        SceneRenderer fresh(sharedRenderer(), after);
        const RenderResult want = fresh.render(o);
        EXPECT_FALSE(sameBits(old.visibility[0], want.visibility[0])) << light.name;
        EXPECT_TRUE(sameBits(moved.visibility[0], want.visibility[0])) << light.name;
        EXPECT_EQ(sum(scene.render(o, {.continues = true}).virtualMaps->renderedPerFrame), 0u)
            << light.name << ": drawn once, they stay";
        // The pool freed by a frame without virtual maps.
        scene.render(options({}));
        const RenderResult again = scene.render(o);
        EXPECT_EQ(again.virtualMaps->renderedPerFrame.front(), again.virtualMaps->resident)
            << light.name << ": a new pool holds nothing";
        EXPECT_TRUE(sameBits(again.visibility[0], want.visibility[0])) << light.name;
    }
}

// A pool too small for the view (64 pages): a still view keeps the pages it holds (the clear
// draws as many squares as pages rendered, not as pages missing); a camera that moves evicts the
// pages it no longer asks for, least recently used first, rather than dropping every new one.
TEST_F(VirtualTest, OnTheDeviceAFullPoolEvictsWhatTheViewLeft) {
    const Scene s = restingObjects(sharpSpot());
    const RenderOptions o = options({{"virtual.enabled", "1"},
                                     {"virtual.deviceDecides", "1"},
                                     {"virtual.pageSize", "32"},
                                     {"virtual.poolSize", "256"}});
    SceneRenderer scene(sharedRenderer(), s);
    const RenderResult before = scene.render(o);
    ASSERT_EQ(before.virtualMaps->resident, 64u);
    // Still: the pool holds what this view asked for first; the rest is dropped, nothing drawn
    // or cleared again.
    const RenderResult still = scene.render(o, {.continues = true});
    EXPECT_GT(still.virtualMaps->dropped, 0u);
    EXPECT_EQ(still.virtualMaps->rendered, 0u);
    EXPECT_TRUE(sameBits(still.visibility[0], before.visibility[0]));
    // The host's decisions hold the same pages in the same places (the same rules).
    RenderOptions onHost = o;
    onHost.parameters.set("virtual.deviceDecides", "0");
    SceneRenderer host(sharedRenderer(), s);
    const RenderResult hosted = host.render(onHost);
    EXPECT_EQ(hosted.virtualMaps->dropped, still.virtualMaps->dropped);
    EXPECT_LE(differing(still, hosted) * 1000, covered(hosted));
    Camera moved = s.camera("");
    moved.position += glm::vec3(1.5f, 0.0f, 0.0f);
    moved.target += glm::vec3(1.5f, 0.0f, 0.0f);
    const RenderResult after = scene.render(o, {.camera = moved, .continues = true});
    std::printf("a full pool of 64: %u requested, %u rendered, %u evicted, %u dropped\n",
                after.virtualMaps->requested, after.virtualMaps->rendered,
                after.virtualMaps->evicted, after.virtualMaps->dropped);
    EXPECT_GT(after.virtualMaps->evicted, 0u);
    EXPECT_EQ(after.virtualMaps->evicted, after.virtualMaps->rendered) << "every page was taken";
    EXPECT_EQ(after.virtualMaps->resident, 64u);
    for (float v : after.visibility[0])
        EXPECT_TRUE(std::isnan(v) || (v >= 0.0f && v <= 1.0f));
}

// One renderer switched between the host's decisions and the device's keeps no page the other
// drew over: host, device, host again, device again, each on a view the one before did not ask
// for, each equal to a fresh renderer's image with its own decisions.
TEST_F(VirtualTest, SwitchingWhoDecidesKeepsNoStalePage) {
    const Scene s = restingObjects(sharpSpot());
    const Camera first = s.camera("");
    Camera second = first;
    second.position = 0.5f * (first.position + first.target) + glm::vec3(0.4f, 0.0f, 0.0f);
    const RenderOptions host = options(kHost), device = options(kDevice);
    SceneRenderer scene(sharedRenderer(), s);
    scene.render(host, {.camera = first});
    scene.render(device, {.camera = second});
    const RenderResult hostAgain = scene.render(host, {.camera = first});
    const RenderResult deviceAgain = scene.render(device, {.camera = second});
    SceneRenderer freshHost(sharedRenderer(), s), freshDevice(sharedRenderer(), s);
    EXPECT_TRUE(
        sameBits(hostAgain.visibility[0], freshHost.render(host, {.camera = first}).visibility[0]));
    EXPECT_TRUE(sameBits(deviceAgain.visibility[0],
                         freshDevice.render(device, {.camera = second}).visibility[0]));
}

// A table past one dispatch's reach (PAGES_MOST_ENTRIES: 65535 workgroups of 128 entries) is
// refused before anything is drawn, naming the parameter and the way out; the host decides it.
TEST_F(VirtualTest, ATableBeyondTheDevicesReachIsRefusedUpFront) {
    // Two spots of 2048^2 pages and their mips: 11,184,810 entries, 1.33 times the reach.
    Scene s = restingObjects(sharpSpot());
    s.lights.push_back(sharpSpot());
    s.lights.back().name = "second spot";
    s.lights.back().position.x += 1.0f;
    RenderOptions o = options(kDevice);
    o.parameters.set("virtual.size", "32768");
    o.parameters.set("virtual.pageSize", "16");
    try {
        sharedRenderer().render(s, o);
        ADD_FAILURE() << "accepted a table of more than " << PAGES_MOST_ENTRIES << " entries";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), "virtual.deviceDecides");
        EXPECT_NE(std::string(e.what()).find("virtual.deviceDecides=0"), std::string::npos)
            << e.what();
    }
    o.parameters.set("virtual.deviceDecides", "0");
    o.width = 64;
    o.height = 48;
    EXPECT_TRUE(sharedRenderer().render(s, o).virtualMaps);
}
