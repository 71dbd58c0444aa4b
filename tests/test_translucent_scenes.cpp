// The translucent built-in scenes (docs/translucency.md, docs/scenes.md): builtin:glass's truth
// against its closed form (each pane's colour, the glass block's tint and attenuation, the lead
// and posts dark) under a sun, a spot and a point light; builtin:tree's truth grey and its crown
// stacked several leaves deep. CPU only: the G-buffer is a synthetic grid.
#include "penumbra/reference.h"
#include "plane_grid.h"
#include "reference/embree_scene.h"
#include "reference/sampling.h"
#include "scene/builtin_scenes.h"
#include "segment_box.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// Whether the segment surely meets the box (1), surely misses it (0), or passes within `margin`
// of its faces (nullopt).
std::optional<bool> crosses(glm::dvec3 p, glm::dvec3 d, double length, glm::dvec3 lo, glm::dvec3 hi,
                            double margin) {
    const bool grown = segmentMeetsBox(p, d, length, lo - margin, hi + margin);
    if (grown != segmentMeetsBox(p, d, length, lo + margin, hi - margin))
        return std::nullopt;
    return grown;
}

constexpr double kMargin = 0.02; // world units: a ray this close to an edge is not compared

struct GlassForm {
    glm::dvec3 through{1.0};
    bool pane = false, block = false;
};

// builtin:glass's closed form at ground point p for the ray along d (unit) within `length`.
std::optional<GlassForm> glassClosedForm(glm::dvec3 p, glm::dvec3 d, double length) {
    using namespace builtin;
    GlassForm out;
    glm::dvec2 lo(1e9), hi(-1e9);
    for (const PaneSpec& pane : kGlassPanes) {
        lo = glm::min(lo, glm::dvec2(pane.corner));
        hi = glm::max(hi, glm::dvec2(pane.corner) + double{kGlassPaneSize});
    }
    // The skylight's plane: a pane's colour, or a lead bar (a box around each pane edge).
    const double t = (kGlassHeight - p.y) / d.y;
    if (t > 0.0 && t < length) {
        const glm::dvec3 q = p + t * d;
        const double s = kGlassPaneSize, half = 0.5 * kGlassLead;
        // The bars' boxes reach half their thickness above and below the plane.
        const double reach = half + half * glm::length(glm::dvec2(d.x, d.z)) / d.y + kMargin;
        const bool inWindow =
            q.x > lo.x - reach && q.x < hi.x + reach && q.z > lo.y - reach && q.z < hi.y + reach;
        if (inWindow) {
            const double bx = std::abs(q.x - lo.x - s * std::round((q.x - lo.x) / s));
            const double bz = std::abs(q.z - lo.y - s * std::round((q.z - lo.y) / s));
            if (std::min(bx, bz) < reach)
                return std::nullopt; // on or beside the lead
            for (const PaneSpec& pane : kGlassPanes)
                if (q.x > pane.corner.x && q.x < pane.corner.x + s && q.z > pane.corner.y &&
                    q.z < pane.corner.y + s) {
                    out.through *= glm::dvec3(pane.colour);
                    out.pane = true;
                }
        }
    }
    const glm::dvec2 corners[] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
    for (const glm::dvec2 c : corners) {
        const glm::dvec3 half(0.5 * kGlassPost, 0.0, 0.5 * kGlassPost);
        const auto post = crosses(p, d, length, glm::dvec3(c.x, 0.0, c.y) - half,
                                  glm::dvec3(c.x, kGlassHeight, c.y) + half, kMargin);
        if (!post)
            return std::nullopt;
        if (*post)
            return GlassForm{.through = glm::dvec3(0.0)};
    }
    const GlassBlockSpec& b = kGlassBlock;
    if (std::abs(p.x - b.centre.x) < 0.5 * b.size + kMargin &&
        std::abs(p.z - b.centre.z) < 0.5 * b.size + kMargin)
        return std::nullopt; // under the block (a ray from inside crosses one face)
    const auto block = crosses(p, d, length, glm::dvec3(b.centre) - 0.5 * double{b.size},
                               glm::dvec3(b.centre) + 0.5 * double{b.size}, kMargin);
    if (!block)
        return std::nullopt;
    if (*block) { // in and out: the tint once, the attenuation over the thickness
        const glm::dvec3 attenuation(b.attenuationColor);
        out.through *= glm::dvec3(b.colour) *
                       glm::pow(attenuation, glm::dvec3(double{b.size} / b.attenuationDistance));
        out.block = true;
    }
    return out;
}

} // namespace

// Every ground point whose ray clears the lead's, the posts' and the block's edges: the truth is
// the pane's colour times the block's share, per channel, to float rounding.
TEST(TranslucentScenes, StainedGlassCastsEachPanesColour) {
    const Light lights[] = {
        {.name = "sun",
         .type = LightType::Directional,
         .direction = glm::normalize(builtin::kGlassSunDirection)},
        {.name = "spot",
         .type = LightType::Spot,
         .position = {-1.0f, 6.5f, -0.8f},
         .direction = glm::normalize(glm::vec3(1.5f, -6.5f, 1.0f)),
         .outerConeAngle = 1.2f},
        {.name = "point", .type = LightType::Point, .position = {0.3f, 5.0f, -0.2f}},
    };
    for (const Light& light : lights) {
        Scene scene = builtin::glass();
        scene.lights = {light};
        const RenderResult g = planeGrid(0.8f, 0.5f, 8.0f, 128);
        const ReferenceResult truth = computeReference(scene, g, {.samples = 1});
        ASSERT_EQ(truth.transmittance.size(), 1u) << light.name;
        size_t panes = 0, blocks = 0, compared = 0;
        double worst = 0.0;
        for (size_t i = 0; i < size_t{128} * 128; ++i) {
            const glm::dvec3 p(g.position[3 * i], 0.0, g.position[3 * i + 2]);
            const LightCone cone = coneTowards(light, p);
            const std::optional<GlassForm> want =
                glassClosedForm(p, cone.axis, distanceToLight(cone, p, cone.axis));
            if (!want)
                continue;
            ++compared;
            panes += want->pane;
            blocks += want->block;
            for (int c = 0; c < 3; ++c)
                worst = std::max(
                    worst, std::abs(truth.transmittance[0][3 * i + size_t(c)] - want->through[c]));
        }
        std::printf("%s: %zu points compared, %zu under a pane, %zu through the block, worst "
                    "%.2e\n",
                    light.name.c_str(), compared, panes, blocks, worst);
        EXPECT_GT(compared, 12000u) << light.name;
        EXPECT_GT(panes, 1000u) << light.name;
        EXPECT_GT(blocks, 100u) << light.name;
        EXPECT_LT(worst, 1e-5) << light.name;
    }
}

// The tree's leaves are BLEND without transmission: every channel keeps the same light. Where
// the crown shades the ground, rays cross several leaves (the stacks the order-independent
// technique is for) and the light is partial, neither all nor none.
TEST(TranslucentScenes, TheTreesLeavesStackGrey) {
    const Scene scene = builtin::tree();
    const RenderResult g = planeGrid(0.9f, 0.5f, 5.0f, 96);
    const ReferenceResult truth = computeReference(scene, g, {.samples = 16});
    ASSERT_EQ(truth.transmittance.size(), 1u);
    const EmbreeScene embree(scene, "threads=1");
    const glm::vec3 down = glm::normalize(builtin::kTreeSunDirection);
    std::vector<size_t> leaves;
    size_t partial = 0, trunk = 0;
    for (size_t i = 0; i < size_t{96} * 96; ++i) {
        const float* t = &truth.transmittance[0][3 * i];
        EXPECT_EQ(t[0], t[1]);
        EXPECT_EQ(t[1], t[2]);
        const glm::vec3 p(g.position[3 * i], 0.0f, g.position[3 * i + 2]);
        const EmbreeScene::SurfacesAlong along =
            embree.surfacesAlong(p, -down, 1e-3f, std::numeric_limits<float>::infinity());
        trunk += along.opaque < std::numeric_limits<float>::infinity();
        if (along.opaque < std::numeric_limits<float>::infinity() || along.translucent.empty())
            continue; // the trunk's shadow, or open sky
        leaves.push_back(along.translucent.size());
        partial += t[0] > 0.02f && t[0] < 0.98f;
    }
    ASSERT_GT(leaves.size(), 1500u);
    std::nth_element(leaves.begin(), leaves.begin() + long(leaves.size() / 2), leaves.end());
    const size_t median = leaves[leaves.size() / 2];
    std::printf("%zu points under the crown: median %zu leaves on a ray, %zu partly lit\n",
                leaves.size(), median, partial);
    EXPECT_GE(median, 3u);
    EXPECT_GT(trunk, 20u);                     // the trunk and branches are opaque
    for (const float h : {0.5f, 1.0f, 1.5f}) { // the trunk's own shadow, h up it
        const glm::vec3 p = -h * down / down.y;
        EXPECT_LT(embree
                      .surfacesAlong({p.x, 0.0f, p.z}, -down, 1e-3f,
                                     std::numeric_limits<float>::infinity())
                      .opaque,
                  std::numeric_limits<float>::infinity())
            << h;
    }
    EXPECT_GT(partial, leaves.size() / 2);
}

// Every edge of every pane has its lead bar: straight up from under an edge's middle, nothing
// passes; up through the pane the pane's colour does, once, through the diagonal its two
// triangles share too.
TEST(TranslucentScenes, EveryPaneIsFramedInLead) {
    using namespace builtin;
    const Scene scene = glass();
    const EmbreeScene embree(scene, "threads=1");
    const float s = kGlassPaneSize, below = kGlassHeight - 0.2f;
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const float far = std::numeric_limits<float>::infinity();
    for (const PaneSpec& pane : kGlassPanes) {
        const glm::vec2 a = pane.corner, m = pane.corner + 0.5f * s;
        for (const glm::vec3 edge : {glm::vec3(a.x, below, m.y), glm::vec3(a.x + s, below, m.y),
                                     glm::vec3(m.x, below, a.y), glm::vec3(m.x, below, a.y + s)})
            EXPECT_EQ(embree.transmittance(edge, up, 0.0f, far), glm::vec3(0.0f))
                << pane.name << " at " << edge.x << ", " << edge.z;
        EXPECT_EQ(embree.transmittance({m.x + 0.13f, below, m.y + 0.21f}, up, 0.0f, far),
                  pane.colour)
            << pane.name;
        // Through its middle, on the diagonal its two triangles share: the pane once.
        EXPECT_EQ(embree.transmittance({m.x, below, m.y}, up, 0.0f, far), pane.colour)
            << pane.name << ", through the diagonal";
    }
}

// Both are named as every built-in scene is.
TEST(TranslucentScenes, AreBuiltIn) {
    EXPECT_EQ(loadScene("builtin:glass").triangleCount(), builtin::glass().triangleCount());
    EXPECT_EQ(loadScene("builtin:tree").triangleCount(), builtin::tree().triangleCount());
    EXPECT_TRUE(builtin::glass().hasTranslucentCasters());
    EXPECT_EQ(builtin::glass().lights.at(0).direction,
              glm::normalize(builtin::kGlassSunDirection)); // the closed form's sun
    EXPECT_TRUE(builtin::tree().hasTranslucentCasters());
}
