// SceneRenderer::repose (issue 59): the same scene at another time drawn by the renderer that
// drew the last pose. What it draws of the new pose equals a fresh renderer's image of it for
// every light type (geometry, bounds, a light's nearest surface and the distance field measured
// again), and a frame that continues the last one keeps only what it should: the page requests
// (one frame late, as they always are), and of the old pose's pages those that nothing moved over.
#include "analytic_scenes.h"
#include "gpu_fixture.h"
#include "penumbra/error.h"

#include <algorithm>
#include <cstring>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// The pose after: every caster (what stands above the ground) lifted and slid, so the scene's
// bounds grow, and a positioned light moved.
Scene moved(Scene scene) {
    for (Vertex& v : scene.vertices)
        if (v.position.y > 1e-3f)
            v.position += glm::vec3(0.25f, 0.4f, -0.1f);
    for (Light& l : scene.lights)
        if (l.type != LightType::Directional)
            l.position += glm::vec3(0.3f, 0.2f, 0.0f);
    return scene;
}

// The pose after, with the lights and the scene's bounds as they were: the casters slid a little
// over the ground (which spans the bounds), so no light's pages change but for what moved.
Scene slid(Scene scene) {
    for (Vertex& v : scene.vertices)
        if (v.position.y > 1e-3f)
            v.position.x += 0.1f;
    return scene;
}

RenderOptions options(Technique technique, bool virtualMaps = false) {
    RenderOptions o{
        .width = 160, .height = 120, .shadowMapSize = 512, .frames = 1, .technique = technique};
    if (technique == Technique::Sdf)
        o.parameters.set("sdf.resolution", "48");
    if (virtualMaps)
        o.parameters.set("virtual.enabled", "1");
    return o;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

} // namespace

// Reposed, a renderer draws what a renderer made for the new pose draws, bit for bit, for every
// light type and for a technique that traces the scene's distance field; continuing the last
// frame changes nothing for a technique that keeps nothing between frames.
TEST_F(FrameTest, ARenderedPoseReposedDrawsAsAFreshRendererOfTheNewPose) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Scene before = restingObjects(light);
        const Scene after = moved(before);
        ASSERT_GT(after.bounds().max.y, before.bounds().max.y) << "the bounds must grow";
        for (const Technique technique : {Technique::Pcf, Technique::Sdf}) {
            const RenderOptions o = options(technique);
            SceneRenderer fresh(sharedRenderer(), after);
            const RenderResult want = fresh.render(o);
            SceneRenderer reposed(sharedRenderer(), before);
            const RenderResult old = reposed.render(o);
            reposed.repose(after);
            const RenderResult rested = reposed.render(o);
            const RenderResult continued = reposed.render(o, {.continues = true});
            // Reposed and continued at once: a field built again counts in this frame's cost.
            reposed.repose(before);
            const RenderResult back = reposed.render(o, {.continues = true});
            const auto build =
                std::find_if(back.passes.begin(), back.passes.end(),
                             [](const PassTime& p) { return p.pass == "sdf_build"; });
            if (technique == Technique::Sdf) {
                ASSERT_NE(build, back.passes.end());
                EXPECT_EQ(build->medianMs, back.field->buildGpuMs);
                EXPECT_GT(build->medianMs, 0.0);
            } else {
                EXPECT_EQ(build, back.passes.end());
            }
            const std::string what =
                light.name + ", technique " + std::to_string(static_cast<uint32_t>(technique));
            EXPECT_FALSE(sameBits(old.visibility[0], want.visibility[0])) << what;
            EXPECT_TRUE(sameBits(rested.visibility[0], want.visibility[0])) << what;
            EXPECT_TRUE(sameBits(continued.visibility[0], want.visibility[0])) << what;
            EXPECT_TRUE(sameBits(rested.position, want.position)) << what;
            EXPECT_EQ(rested.exposure, want.exposure) << what;
            EXPECT_EQ(rested.lights.front().views.front().nearPlane,
                      want.lights.front().views.front().nearPlane)
                << what;
        }
    }
}

// A continuing frame has no warm-up: one frame drawn; its virtual pages are the ones the frame
// before asked for, those under what moved (or was removed) rendered again, the others cached.
TEST_F(VirtualTest, AContinuingFrameRendersTheRequestsOfTheLastOneAgainOnTheNewPose) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Scene before = restingObjects(light);
        SceneRenderer scene(sharedRenderer(), before);
        const RenderOptions o = options(Technique::Hard, true);
        const RenderResult rest = scene.render(o);
        ASSERT_TRUE(rest.virtualMaps);
        EXPECT_EQ(rest.virtualMaps->renderedPerFrame.size(), 3u) << "two warm-ups and one";
        EXPECT_EQ(rest.virtualMaps->rendered, 0u) << light.name << ": cached after warm-up";
        // The same pose again, continuing: its requests are the last frame's, all cached.
        const RenderResult same = scene.render(o, {.continues = true});
        EXPECT_EQ(same.virtualMaps->renderedPerFrame.size(), 1u) << light.name;
        EXPECT_EQ(same.virtualMaps->requested, rest.virtualMaps->requested) << light.name;
        EXPECT_EQ(same.virtualMaps->cached, same.virtualMaps->requested) << light.name;
        EXPECT_TRUE(sameBits(same.visibility[0], rest.visibility[0])) << light.name;
        // Reposed, under the same lights and bounds: the pages under what moved are drawn again,
        // the floor's beyond them stay.
        const Scene after = slid(before);
        ASSERT_EQ(after.bounds().min, before.bounds().min);
        ASSERT_EQ(after.bounds().max, before.bounds().max);
        scene.repose(after);
        const RenderResult moving = scene.render(o, {.continues = true});
        EXPECT_EQ(moving.virtualMaps->renderedPerFrame.size(), 1u) << light.name;
        EXPECT_GT(moving.virtualMaps->requested, 0u) << light.name;
        EXPECT_GT(moving.virtualMaps->rendered, 0u) << light.name;
        if (light.type == LightType::Directional) { // the bulb and the spot see every caster
            EXPECT_GT(moving.virtualMaps->cached, 0u) << "some floor away from every caster";
        }
        EXPECT_EQ(moving.virtualMaps->rendered + moving.virtualMaps->cached,
                  moving.virtualMaps->requested)
            << light.name;
        // A triangle removed: the pages it may have drawn into are drawn again, the others kept;
        // the pose draws as a fresh renderer draws it.
        Scene fewer = after;
        fewer.indices.resize(fewer.indices.size() - 3);
        scene.repose(fewer);
        const RenderResult removed = scene.render(o, {.continues = true});
        EXPECT_GT(removed.virtualMaps->cached, 0u) << light.name;
        EXPECT_EQ(removed.virtualMaps->rendered + removed.virtualMaps->cached,
                  removed.virtualMaps->requested)
            << light.name;
        // The next frame has the pages this pose's own pixels asked for.
        const RenderResult settled = scene.render(o, {.continues = true});
        SceneRenderer fresh(sharedRenderer(), fewer);
        EXPECT_TRUE(sameBits(settled.visibility[0], fresh.render(o).visibility[0])) << light.name;
    }
}

TEST_F(FrameTest, ReposeRefusesAnotherSceneAndOneWithNoTriangleLeft) {
    const Scene before = restingObjects(sharpSun());
    SceneRenderer scene(sharedRenderer(), before);
    Scene lit = before;
    lit.lights.push_back(sharpPoint());
    EXPECT_THROW(scene.repose(lit), InputError);
    Scene flat = before;
    for (Vertex& v : flat.vertices)
        v.position = glm::vec3(1.0f);
    EXPECT_THROW(scene.repose(flat), InputError);
    // Refused, it draws the scene it had.
    const RenderResult still = scene.render(options(Technique::Hard));
    SceneRenderer fresh(sharedRenderer(), before);
    EXPECT_TRUE(
        sameBits(still.visibility[0], fresh.render(options(Technique::Hard)).visibility[0]));
}

// trim frees what no later frame reads (the memory its frame made, but for a few small persistent
// buffers), and the next frame draws as if it had not: a plain technique's picture bit for bit,
// for every light type; a virtual map's page pool and cache kept
// (a continuing frame renders no page again).
TEST_F(FrameTest, TrimFreesPerFrameTargetsAndKeepsWhatTheNextFrameReads) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Scene scene = restingObjects(light);
        SceneRenderer plain(sharedRenderer(), scene);
        const uint64_t uploaded = sharedRenderer().deviceMemoryInUse().bytes;
        const RenderResult first = plain.render(options(Technique::Pcf));
        const uint64_t held = sharedRenderer().deviceMemoryInUse().bytes;
        plain.trim();
        const uint64_t trimmed = sharedRenderer().deviceMemoryInUse().bytes;
        // What the frame made is gone but for a tenth (a few small persistent buffers).
        EXPECT_LT(trimmed - uploaded, (held - uploaded) / 10) << light.name;
        const RenderResult next = plain.render(options(Technique::Pcf), {.continues = true});
        EXPECT_TRUE(sameBits(next.visibility[0], first.visibility[0])) << light.name;
        SceneRenderer paged(sharedRenderer(), scene);
        const RenderResult rest = paged.render(options(Technique::Hard, true));
        paged.trim();
        const RenderResult kept = paged.render(options(Technique::Hard, true), {.continues = true});
        ASSERT_TRUE(kept.virtualMaps);
        EXPECT_EQ(kept.virtualMaps->rendered, 0u) << light.name << ": the pool and cache kept";
        EXPECT_TRUE(sameBits(kept.visibility[0], rest.visibility[0])) << light.name;
    }
}
