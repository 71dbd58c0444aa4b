// The `temporal` layer (issue 61): at rest it averages the frames it kept, each frame's samples
// turned (so the frames differ); a cut starts it again; the camera's motion reprojects it; a
// surface uncovered starts afresh (depth and normal); the clamp keeps a moving shadow from
// trailing. Every light type.
#include "analytic_scenes.h"
#include "gpu_fixture.h"
#include "penumbra/error.h"
#include "scene/mesh_builder.h"
#include "temporal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kWidth = 96, kHeight = 72;

// The layer's options; the reset rule off unless asked (the tests of the clamp and the blend).
RenderOptions temporal(Technique technique, int frames, std::string clamp = "none",
                       std::string reset = "0") {
    RenderOptions o{.width = kWidth,
                    .height = kHeight,
                    .shadowMapSize = 512,
                    .frames = 1,
                    .technique = technique};
    o.parameters.set("temporal.frames", std::to_string(frames));
    o.parameters.set("temporal.clamp", clamp);
    o.parameters.set("temporal.reset", reset);
    return o;
}

// One frame after the last, no warm-up (what a played scene draws).
RenderResult next(SceneRenderer& renderer, const RenderOptions& o,
                  SceneRenderer::FrameState state = {}) {
    state.continues = true;
    return renderer.render(o, state);
}

// Two renderers of one scene drawn frame by frame together: `raw` keeps nothing
// (temporal.frames=1: its frames, their samples turned as the other's, are what the layer
// blends), `kept` the history.
struct TwoRenderers {
    TwoRenderers(const Scene& scene, const RenderOptions& options)
        : raw(sharedRenderer(), scene), kept(sharedRenderer(), scene), single(options),
          averaged(options) {
        single.parameters.set("temporal.frames", "1");
    }
    struct Frames {
        RenderResult frame, mean;
    };
    Frames next(SceneRenderer::FrameState state = {}) {
        Frames f{.frame = ::next(raw, single, state)};
        f.mean = ::next(kept, averaged, state);
        return f;
    }
    void repose(const Scene& scene) {
        raw.repose(scene);
        kept.repose(scene);
    }
    SceneRenderer raw, kept;
    RenderOptions single, averaged;
};

// `scene` with every vertex above `above` moved by `by`.
Scene movedAbove(const Scene& scene, float above, glm::vec3 by) {
    Scene moved = scene;
    for (Vertex& v : moved.vertices)
        if (v.position.y > above)
            v.position += by;
    return moved;
}

double largestDifference(const std::vector<float>& a, const std::vector<float>& b) {
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::isfinite(a[i]) || std::isfinite(b[i]))
            worst = std::max(worst, std::isfinite(a[i]) && std::isfinite(b[i])
                                        ? std::abs(double(a[i]) - double(b[i]))
                                        : 1e9);
    return worst;
}

// Pixels that differ by more than `by`, or where one is a surface and the other not.
size_t differing(const std::vector<float>& a, const std::vector<float>& b, double by) {
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i)
        n += std::isfinite(a[i]) != std::isfinite(b[i]) ||
             (std::isfinite(a[i]) && std::abs(double(a[i]) - double(b[i])) > by);
    return n;
}

} // namespace

// At rest, with nothing clamped, frame k shows the mean of the k frames so far (up to
// temporal.frames): the frames themselves are what a renderer with temporal.frames=1 draws (it
// keeps nothing), the same sample turns frame by frame. Floats: k roundings of a blend each, 1e-5.
// The frames differ (each turns its samples), and a cut starts the mean again.
TEST_F(LayerTest, AtRestTheTemporalLayerAveragesTheFramesItKept) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        Light sized = light;
        if (sized.type == LightType::Directional)
            sized.angularDiameter = 2.0f;
        else
            sized.radius = 0.15f;
        const Scene scene = sphereOverPlane(sized);
        // Any depth passes (nothing moves): after the cut only the cleared history's length (0)
        // keeps its zeros out.
        RenderOptions averaged = temporal(Technique::Pcss, 64);
        averaged.parameters.set("temporal.depthTolerance", "1");
        TwoRenderers both(scene, averaged);
        std::vector<double> sum;
        size_t changed = 0;
        std::vector<float> last;
        for (int k = 1; k <= 6; ++k) {
            const bool cut = k == 5;
            const auto [frame, mean] = both.next({.cut = cut});
            const std::vector<float>& v = frame.visibility[0];
            if (cut)
                sum.assign(v.size(), 0.0);
            sum.resize(v.size(), 0.0);
            if (!last.empty())
                changed += differing(v, last, 1e-3);
            last = v;
            const int count = cut ? 1 : k > 5 ? k - 4 : k;
            std::vector<float> want(v.size());
            for (size_t i = 0; i < v.size(); ++i) {
                sum[i] += v[i];
                want[i] = float(sum[i] / count);
            }
            EXPECT_LE(largestDifference(mean.visibility[0], want), 1e-5)
                << light.name << ", frame " << k;
        }
        EXPECT_GT(changed, size_t{20}) << light.name << ": the frames turned no sample";
    }
}

// Hard shadows (the same every frame) under a spot while the camera pans over the plane: the
// history follows each pixel's surface, so the layer shows what the frame shows but where a
// pixel's reprojected footprint straddles a shadow's edge or a silhouette. Without reprojection
// the plane's depth at a pixel stays the same, so its history passes for the pixel's and the
// shadow's edge trails by the pan (some 5 pixels a frame).
TEST_F(LayerTest, TheTemporalLayerFollowsTheCamera) {
    const Scene scene = sphereOverPlane(sharpSpot());
    // Across the image plane (its depths kept), right and then up: the history is read where
    // each pixel's surface was, in x and in y.
    const Camera start = scene.cameras.front();
    const glm::vec3 forward = glm::normalize(start.target - start.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    for (const glm::vec3 step : {0.4f * right, 0.4f * up}) {
        TwoRenderers both(scene, temporal(Technique::Hard, 64));
        Camera camera = start;
        size_t worst = 0, surface = 0;
        for (int k = 0; k < 6; ++k) {
            const auto [frame, mean] = both.next({.camera = camera});
            worst = std::max(worst, differing(mean.visibility[0], frame.visibility[0], 0.25));
            surface = std::count_if(frame.visibility[0].begin(), frame.visibility[0].end(),
                                    [](float v) { return std::isfinite(v); });
            camera.position += step; // some 5 pixels a frame
            camera.target += step;
        }
        EXPECT_LT(worst, surface / 50) << "of " << surface << " surface pixels";
    }
}

// A plate floating 1 above the plane under a sun moves along x by the shadow's offset, the camera
// still: where it uncovers the plane, that plane lies in its new shadow (0), while the plate's
// top was lit (1). Those pixels take no history from the plate (their depth differs, by 1 in 8
// along the view) and show what the frame shows.
TEST_F(LayerTest, ASurfaceUncoveredStartsAfresh) {
    Scene scene;
    scene.name = "a plate over a plane";
    MeshBuilder mb(scene);
    const float g = 20.0f, h = 1.0f, r = 0.8f;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("plane", {0.7f, 0.7f, 0.7f}));
    mb.quad({-r, h, r}, {r, h, r}, {r, h, -r}, {-r, h, -r},
            mb.material("plate", {0.7f, 0.3f, 0.2f}));
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = glm::normalize(glm::vec3(-0.6f, -1.0f, 0.0f))});
    scene.cameras.push_back({.name = "above",
                             .position = {0.0f, 6.0f, 5.0f},
                             .target = {0.0f, 0.0f, 0.0f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    TwoRenderers both(scene, temporal(Technique::Hard, 64));
    RenderResult before;
    for (int k = 0; k < 3; ++k)
        before = both.next().frame;
    both.repose(movedAbove(scene, 0.5f, {0.6f, 0.0f, 0.0f}));
    const auto [frame, mean] = both.next();
    size_t uncovered = 0, shadowed = 0, wrong = 0;
    for (size_t i = 0; i < size_t{kWidth} * kHeight; ++i) {
        const bool wasPlate = before.position[3 * i + 1] > 0.5f;
        const bool isPlane = std::abs(frame.position[3 * i + 1]) < 1e-4f;
        if (!wasPlate || !isPlane)
            continue;
        ++uncovered;
        shadowed += frame.visibility[0][i] < 0.5f;
        wrong += std::abs(mean.visibility[0][i] - frame.visibility[0][i]) > 0.25f;
    }
    EXPECT_GT(shadowed, uncovered / 4) << "the plate's new shadow falls where it was";
    EXPECT_GT(uncovered, size_t{30});
    EXPECT_LE(wrong, uncovered / 20) << "of " << uncovered << " pixels the plate uncovered";
}

// A moving caster's shadow under a point light, the history long: without a clamp its old place
// stays dark for many frames; the neighbourhood's range lets it go at once (pixels far from the
// shadow's edge see only lit neighbours).
TEST_F(LayerTest, TheClampKeepsAMovingShadowFromTrailing) {
    Scene scene = sphereOverPlane(sharpPoint());
    scene.cameras.front().position = {0.0f, 2.0f, 5.0f}; // low: the plane's far edge and the sky
    scene.cameras.front().target = {0.0f, 0.5f, -3.0f};
    const auto trail = [&](const std::string& clamp) {
        TwoRenderers both(scene, temporal(Technique::Hard, 64, clamp));
        for (int k = 0; k < 4; ++k)
            both.next();
        both.repose(movedAbove(scene, 0.1f, {0.0f, 0.0f, 0.5f}));
        const auto [frame, mean] = both.next();
        size_t background = 0, undefined = 0;
        for (size_t i = 0; i < frame.visibility[0].size(); ++i) {
            background += std::isnan(frame.visibility[0][i]);
            undefined += std::isnan(mean.visibility[0][i]) != std::isnan(frame.visibility[0][i]);
        }
        EXPECT_GT(background, size_t{100}) << clamp << ": the sky in view";
        EXPECT_EQ(undefined, 0u) << clamp << ": a surface's visibility undefined (the sky's NaN)";
        return differing(mean.visibility[0], frame.visibility[0], 0.25);
    };
    const size_t unclamped = trail("none"), minmax = trail("minmax"), variance = trail("variance");
    EXPECT_GT(unclamped, size_t{100});
    EXPECT_LT(minmax, unclamped / 2);
    EXPECT_LT(variance, unclamped / 2);
}

// The history holds for one technique and one set of parameters (its key): another parameter,
// even one that changes nothing the frame draws, and the next frame starts again from itself.
TEST_F(LayerTest, AnotherParameterStartsTheHistoryAgain) {
    const Scene scene = sphereOverPlane(sharpSun());
    RenderOptions averaged = temporal(Technique::Pcf, 64);
    averaged.parameters.set("pcf.filter", "poisson");
    TwoRenderers both(scene, averaged);
    for (int k = 0; k < 3; ++k)
        both.next();
    both.averaged.parameters.set("temporal.gamma", "2"); // no clamp: nothing else changes
    const auto [frame, restarted] = both.next();
    EXPECT_EQ(largestDifference(restarted.visibility[0], frame.visibility[0]), 0.0);
}

// The sphere rises against the sky under a point light, every history texel let through (any
// depth, any normal): where a pixel's history straddles the old silhouette, the sky's texels hold
// nothing (cleared, length 0) and weigh nothing; the lit sphere stays lit.
TEST_F(LayerTest, TheSkyHoldsNoHistory) {
    Scene scene = sphereOverPlane(sharpPoint());
    scene.cameras.front().position = {0.0f, 2.0f, 5.0f}; // low: the sphere's top against the sky
    scene.cameras.front().target = {0.0f, 0.5f, -3.0f};
    RenderOptions averaged = temporal(Technique::Hard, 64);
    averaged.parameters.set("temporal.depthTolerance", "1");
    averaged.parameters.set("temporal.normalTolerance", "-1");
    TwoRenderers both(scene, averaged);
    RenderResult before;
    for (int k = 0; k < 3; ++k)
        before = both.next().frame;
    both.repose(movedAbove(scene, 0.1f, {0.0f, 0.1f, 0.0f}));
    const auto [frame, mean] = both.next();
    size_t edge = 0, wrong = 0;
    for (size_t i = 0; i < size_t{kWidth} * kHeight; ++i) {
        const size_t x = i % kWidth, y = i / kWidth;
        if (x == 0 || y == 0 || x + 1 == kWidth || y + 1 == kHeight ||
            !(frame.visibility[0][i] > 0.5f) || frame.position[3 * i + 1] < 0.1f)
            continue;       // the lit sphere's pixels ...
        bool bySky = false; // ... next to the sky before
        for (const size_t j : {i - 1, i + 1, i - kWidth, i + kWidth, i})
            bySky = bySky || std::isnan(before.visibility[0][j]);
        if (!bySky)
            continue;
        ++edge;
        wrong += std::abs(mean.visibility[0][i] - frame.visibility[0][i]) > 0.1f;
    }
    EXPECT_GT(edge, size_t{10});
    EXPECT_LE(wrong, edge / 4) << "of " << edge << " lit pixels by the old silhouette";
}

// Hard shadows (noise-free: at rest each frame the same) from a sphere moving every frame, the
// camera still, nothing clamped: the history of a plane pixel has no spread over time, so
// wherever this frame's visibility changed the reset rule starts it again and the layer shows
// this frame exactly. But where the history may be a single frame (the pixel just uncovered, or
// its neighbourhood's visibility just changed): that one also weighs its neighbourhood's spread
// and may lag a frame. Without the rule (temporal.reset=0) the old shadow trails. Every light.
TEST_F(LayerTest, TheResetRuleLetsANoiseFreeShadowMoveWithoutTrailing) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        const Scene scene = sphereOverPlane(light);
        for (const std::string reset : {"2", "0"}) {
            TwoRenderers both(scene, temporal(Technique::Hard, 64, "none", reset));
            double worst = 0.0;
            size_t trailing = 0, changed = 0, compared = 0;
            RenderResult last;
            std::vector<char> afresh; // the last frame started the pixel's history
            for (int k = 0; k < 7; ++k) {
                both.repose(movedAbove(scene, 0.3f, {0.12f * float(std::max(k - 1, 0)), 0, 0}));
                const auto [frame, mean] = both.next();
                const std::vector<float>& v = frame.visibility[0];
                std::vector<char> startsNow(v.size(), 1);
                for (size_t i = 0; i < v.size(); ++i) {
                    const bool plane = std::abs(frame.position[3 * i + 1]) < 1e-4f;
                    if (!plane || last.visibility.empty())
                        continue; // the plane's pixels (their motion is none) after a frame
                    const bool wasPlane = std::abs(last.position[3 * i + 1]) < 1e-4f;
                    const bool change = std::abs(last.visibility[0][i] - v[i]) > 0.5f;
                    bool nearChange = false; // the neighbourhood's mean may have moved
                    const size_t x = i % kWidth, y = i / kWidth;
                    for (size_t yy = y - (y > 0); yy <= std::min<size_t>(y + 1, kHeight - 1); ++yy)
                        for (size_t xx = x - (x > 0); xx <= std::min<size_t>(x + 1, kWidth - 1);
                             ++xx)
                            nearChange =
                                nearChange || std::abs(last.visibility[0][yy * kWidth + xx] -
                                                       v[yy * kWidth + xx]) > 1e-3f;
                    startsNow[i] = !wasPlane || nearChange;
                    changed += wasPlane && change;
                    const double error = std::abs(mean.visibility[0][i] - v[i]);
                    trailing += error > 0.25;
                    if (!afresh.empty() && !afresh[i])
                        worst = std::max(worst, error), ++compared;
                }
                last = frame;
                afresh = startsNow;
            }
            EXPECT_GT(changed, size_t{60}) << light.name << ": the shadow hardly moved";
            EXPECT_GT(compared, size_t{2} * kWidth * kHeight) << light.name;
            if (reset == "2")
                EXPECT_LE(worst, 1e-6) << light.name;
            else
                EXPECT_GT(trailing, size_t{60}) << light.name;
        }
    }
}

// The layer against its CPU reference (its own mirror of the reprojection, of the read's length
// and of the reset rule's thresholds, and temporalStep), frame by frame: soft shadows (pcss, its
// samples turned each frame) from a sphere moving, then still, the minmax clamp, the reset rule
// on and off. The camera looks almost straight down (every plane texel passes the depth test for
// its neighbours, the sphere's none) and keeps still, or pans and dollies (sub-pixel motion in x
// and y, the plane 3% nearer a frame: the history read bilinearly where the motion vectors say,
// its depth then not its depth now). The reference steps each plane pixel's history from the
// frames a renderer that keeps nothing draws. Floats: a blend's roundings, 1e-5; a decision
// within 1e-4 of its threshold (a reset, the nearest texel, a length rounded, or within 1e-6 of
// the taps' spread) may go either way on another device, and its pixel (and the pixels whose
// history reads it) are not followed from then on.
TEST_F(LayerTest, TheLayerStepsAsItsCpuReferenceDoes) {
    struct Case {
        float reset;
        bool cameraMoves;
    };
    for (const Case c : {Case{3.0f, false}, Case{0.0f, false}, Case{3.0f, true}}) {
        size_t tapResets = 0, neighbourhoodResets = 0, clamped = 0, blended = 0, between = 0,
               shortened = 0;
        for (Light light : {sharpSun(), sharpSpot(), sharpPoint()}) {
            if (light.type == LightType::Directional)
                light.angularDiameter = 3.0f;
            else
                light.radius = 0.2f;
            Scene scene = sphereOverPlane(light);
            Camera camera = scene.cameras.front();
            camera.position = {0.0f, 9.0f, 1.0f};
            camera.target = {0.0f, 0.0f, 0.0f};
            RenderOptions options =
                temporal(Technique::Pcss, 8, "minmax", c.reset > 0.0f ? "3" : "0");
            options.motion = true;
            TwoRenderers both(scene, options);
            const gpu::TemporalParams params{.frames = 8,
                                             .clampMode = TEMPORAL_CLAMP_MINMAX,
                                             .gamma = 1.0f,
                                             .depthTolerance = 0.02f,
                                             .normalTolerance = 0.9f,
                                             .reset = c.reset};
            const size_t pixels = size_t{kWidth} * kHeight;
            std::vector<glm::vec3> history(pixels, glm::vec3(0.0f));
            std::vector<char> wasPlane(pixels, 0), followed(pixels, 1);
            size_t compared = 0, wrong = 0;
            // Whether a decision `over` its threshold by this much may go either way.
            const auto undecided = [](float over) { return std::abs(over) < 1e-4f; };
            const auto inside = [](glm::ivec2 t) {
                return t.x >= 0 && t.y >= 0 && t.x < int(kWidth) && t.y < int(kHeight);
            };
            const auto at = [](glm::ivec2 t) { return size_t(t.y) * kWidth + size_t(t.x); };
            for (int k = 0; k < 12; ++k) {
                both.repose(movedAbove(scene, 0.3f, {0.1f * float(std::min(k, 6)), 0.0f, 0.0f}));
                const auto [frame, mean] = both.next({.camera = camera});
                if (c.cameraMoves) { // 0.4 and 0.3 pixels or so, and 3% nearer
                    camera.position += glm::vec3(0.013f, -0.27f, 0.011f);
                    camera.target += glm::vec3(0.013f, 0.0f, 0.011f);
                }
                const std::vector<float>& v = frame.visibility[0];
                ASSERT_EQ(mean.motion.size(), 3 * pixels);
                std::vector<glm::vec3> stepped(pixels, glm::vec3(0.0f));
                std::vector<char> isPlane(pixels, 0), nowFollowed(pixels, 1);
                for (size_t i = 0; i < pixels; ++i)
                    isPlane[i] = std::abs(frame.position[3 * i + 1]) < 1e-4f;
                for (size_t i = 0; i < pixels; ++i) {
                    if (!isPlane[i])
                        continue; // not followed: the sphere's history is not the plane's
                    const glm::ivec2 p(int(i % kWidth), int(i / kWidth));
                    float lo = v[i], hi = v[i], sum = 0.0f, squares = 0.0f, n = 0.0f;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx)
                            if (const glm::ivec2 q = p + glm::ivec2(dx, dy); inside(q)) {
                                const float w = v[at(q)];
                                lo = std::min(lo, w), hi = std::max(hi, w);
                                sum += w, squares += w * w, n += 1.0f;
                            }
                    const glm::vec4 around(lo, hi, sum / n, squares / n);
                    const float spatial = std::max(around.w - around.z * around.z, 0.0f);
                    // Where the plane was, by its motion vector.
                    const glm::vec2 there = glm::vec2(p) + 0.5f -
                                            glm::vec2(mean.motion[3 * i], mean.motion[3 * i + 1]) -
                                            0.5f;
                    const glm::ivec2 nearest(glm::floor(there + 0.5f)), base(glm::floor(there));
                    const glm::vec2 f = there - glm::vec2(base);
                    bool follow = std::abs(f.x - 0.5f) > 1e-4f && std::abs(f.y - 0.5f) > 1e-4f;
                    // The plane's texels around the nearest (paired with this frame at the same
                    // offset): the residuals' noise and the neighbourhoods' means.
                    float historySum = 0.0f, currentSum = 0.0f, residuals = 0.0f, squares2 = 0.0f,
                          pairs = 0.0f;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const glm::ivec2 q = p + glm::ivec2(dx, dy),
                                             t = nearest + glm::ivec2(dx, dy);
                            if (!inside(q) || !inside(t) || !wasPlane[at(t)])
                                continue;
                            const float r = v[at(q)] - history[at(t)].x;
                            historySum += history[at(t)].x, currentSum += v[at(q)];
                            residuals += r, squares2 += r * r, pairs += 1.0f;
                            follow = follow && followed[at(t)];
                        }
                    const float mr = pairs > 0.0f ? residuals / pairs : 0.0f;
                    const float noise =
                        pairs < 2.0f ? 0.0f : std::max(squares2 / pairs - mr * mr, 0.0f);
                    EXPECT_EQ(noise, gpu::residualNoise(residuals, squares2, pairs));
                    // The deviations allowed: the history's spread pooled with a prior (for a
                    // texel the neighbourhood's variance, for the neighbourhoods' means the
                    // residuals'), and the gradient over the distance read from `there`.
                    const auto deviations = [&](glm::vec3 h, float prior) {
                        const float spread = std::max(h.y - h.x * h.x, 0.0f);
                        return params.reset *
                               std::sqrt((h.z * spread + TEMPORAL_PRIOR_FRAMES * prior) /
                                         (h.z + TEMPORAL_PRIOR_FRAMES));
                    };
                    const auto allowance = [&](glm::vec2 from) {
                        return glm::length(from - there) * std::sqrt(1.5f * spatial) +
                               TEMPORAL_RESET_FLOOR;
                    };
                    // The history: bilinear over the plane's texels around `there` that this
                    // frame agrees with ...
                    glm::vec3 kept(0.0f);
                    float weight = 0.0f;
                    std::vector<glm::vec3> taps; // weight, mean, length
                    for (int tap = 0; tap < 4; ++tap) {
                        const glm::ivec2 t = base + glm::ivec2(tap & 1, tap >> 1);
                        if (!inside(t) || !wasPlane[at(t)])
                            continue;
                        const float w =
                            (tap & 1 ? f.x : 1.0f - f.x) * (tap >> 1 ? f.y : 1.0f - f.y);
                        if (w == 0.0f)
                            continue; // (the shader's test of it changes nothing)
                        const glm::vec3 h = history[at(t)];
                        follow = follow && followed[at(t)];
                        if (params.reset > 0.0f) {
                            const float over = std::abs(v[i] - h.x) - deviations(h, spatial) -
                                               allowance(glm::vec2(t));
                            follow = follow && !undecided(over);
                            if (over > 0.0f) {
                                tapResets += follow;
                                continue;
                            }
                        }
                        weight += w;
                        taps.emplace_back(w, h.x, h.z);
                        kept += w * glm::vec3(h.x, h.y - h.x * h.x, h.z);
                    }
                    glm::vec3 h(0.0f);
                    if (weight > 1e-3f) {
                        kept /= weight;
                        h = glm::vec3(kept.x, kept.y + kept.x * kept.x, kept.z);
                        // ... its length shortened by how much the taps differ beyond what
                        // their noise would (each tap's share w (1 - w) / its length) ...
                        float spread = 0.0f, noiseShare = 0.0f;
                        for (const glm::vec3& tap : taps) {
                            const float share = tap.x / weight;
                            spread += share * (tap.y - kept.x) * (tap.y - kept.x);
                            noiseShare += share * (1.0f - share) / tap.z;
                        }
                        const float length = gpu::resampledLength(h, spread, noiseShare, spatial);
                        between += follow && taps.size() > 1;
                        // (the shader's spread, E[m^2] - E[m]^2, may be off by float rounding:
                        // a length that rounds otherwise within 1e-6 of it is not followed)
                        const auto rounded = [&](float d) {
                            return std::floor(gpu::resampledLength(h, std::max(spread + d, 0.0f),
                                                                   noiseShare, spatial) +
                                              0.5f);
                        };
                        follow = follow && rounded(-1e-6f) == rounded(1e-6f) &&
                                 std::abs(length - std::floor(length) - 0.5f) > 1e-4f;
                        h.z = std::floor(length + 0.5f);
                        blended += follow && kept.z != std::floor(kept.z);
                        shortened += follow && h.z < std::floor(kept.z + 0.5f);
                    }
                    // ... if the neighbourhood's mean agrees with the history's.
                    if (h.z >= 0.5f && params.reset > 0.0f && pairs >= 1.0f) {
                        const float over = std::abs(currentSum / pairs - historySum / pairs) -
                                           deviations(h, noise) / std::sqrt(pairs) -
                                           allowance(glm::vec2(nearest));
                        follow = follow && !undecided(over);
                        if (over > 0.0f)
                            h = glm::vec3(0.0f), neighbourhoodResets += follow;
                    }
                    clamped += follow && h.z >= 0.5f && (h.x < lo || h.x > hi);
                    stepped[i] = gpu::temporalStep(params, h, v[i], around);
                    nowFollowed[i] = follow;
                    if (!follow)
                        continue;
                    ++compared;
                    wrong += std::abs(mean.visibility[0][i] - stepped[i].x) > 1e-5f;
                }
                history = stepped;
                wasPlane = isPlane;
                followed = nowFollowed;
            }
            EXPECT_EQ(wrong, 0u) << light.name << ", of " << compared << " pixel-frames";
            EXPECT_GT(compared, size_t{12} * pixels / (c.cameraMoves ? 3 : 2)) << light.name;
        }
        if (c.reset > 0.0f) {
            EXPECT_GT(tapResets, size_t{50}) << "no texel disagreed";
            EXPECT_GT(neighbourhoodResets, size_t{500}) << "no neighbourhood did";
        } else {
            EXPECT_EQ(tapResets + neighbourhoodResets, 0u);
            EXPECT_GT(clamped, size_t{100}) << "the clamp never held a history";
        }
        if (c.cameraMoves) {
            EXPECT_GT(blended, size_t{1000}) << "no history blended texels of other lengths";
            EXPECT_GT(shortened, size_t{1000}) << "no read between texels shortened a history";
            EXPECT_LT(shortened, between) << "every read between texels shortened its history";
        }
    }
}

// The camera dollies toward the plane (each pixel's surface nearer, its depth then not its depth
// now) and pans right and up the image (motion in x and in y), pcss's samples turning each frame,
// the reset rule on: the plane's history follows, so the layer shows an average of frames and not
// the frame itself. Were the history tested against this frame's depth, or read from a mirrored
// place, it would start again (or be dropped by the rule) and show each frame as it is.
TEST_F(LayerTest, TheHistoryFollowsADollyAndAPan) {
    Light light = sharpSpot();
    light.radius = 0.2f;
    const Scene scene = sphereOverPlane(light);
    TwoRenderers both(scene, temporal(Technique::Pcss, 16, "minmax", "2"));
    Camera camera = scene.cameras.front();
    size_t averaged = 0, plane = 0;
    for (int k = 0; k < 6; ++k) {
        const auto [frame, mean] = both.next({.camera = camera});
        if (k >= 3)
            for (size_t i = 0; i < frame.visibility[0].size(); ++i) {
                if (!(std::abs(frame.position[3 * i + 1]) < 1e-4f) ||
                    !(frame.visibility[0][i] > 0.05f && frame.visibility[0][i] < 0.95f))
                    continue; // the plane's penumbrae, where pcss's frames differ
                ++plane;
                averaged += std::abs(mean.visibility[0][i] - frame.visibility[0][i]) > 1e-4f;
            }
        // 3% nearer a frame (more than temporal.depthTolerance), and some 0.6 pixels right and
        // 3 up the image: a history read mirrored in y lands on other depths, and is dropped.
        const glm::vec3 forward = glm::normalize(camera.target - camera.position);
        const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
        const glm::vec3 aside = 0.05f * right + 0.25f * glm::cross(right, forward);
        camera.position += 0.25f * forward + aside;
        camera.target += aside;
    }
    EXPECT_GT(plane, size_t{100});
    EXPECT_GT(averaged, plane / 2) << "of " << plane << " penumbra pixels on the plane";
}

// A render that does not continue the last draws temporal.frames warm-up frames first, so its
// timed frame is near the steady state: against the mean of 48 frames a renderer drew in turn,
// a fresh render with temporal.frames=16 (the mean of 17 frames, their samples turned) is well
// closer than one frame alone (about 1/4 of its difference; 1/sqrt(2) were it to warm up once).
TEST_F(LayerTest, AFreshRenderWarmsUpToItsSteadyState) {
    Light light = sharpSpot();
    light.radius = 0.2f;
    const Scene scene = sphereOverPlane(light);
    SceneRenderer played(sharedRenderer(), scene);
    RenderResult converged;
    for (int k = 0; k < 48; ++k)
        converged = next(played, temporal(Technique::Pcss, 64, "none", "0"));
    const auto rmseFromConverged = [&](int frames) {
        SceneRenderer fresh(sharedRenderer(), scene);
        const RenderResult r = fresh.render(temporal(Technique::Pcss, frames, "none", "0"));
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < r.visibility[0].size(); ++i)
            if (std::isfinite(r.visibility[0][i]))
                sum += std::pow(double(r.visibility[0][i]) - converged.visibility[0][i], 2.0), ++n;
        return std::sqrt(sum / double(n));
    };
    const double oneFrame = rmseFromConverged(1), warmed = rmseFromConverged(16);
    EXPECT_GT(oneFrame, 1e-3) << "pcss's frames differ";
    EXPECT_LT(warmed, 0.5 * oneFrame) << warmed << " against " << oneFrame;
}

// The memory check counts the layer's history: two versions (last frame's and this frame's) of
// an RGBA32UI texel a pixel and light, 32 bytes, whatever else the frame holds (the motion
// vectors on in both). A device of 1 MiB refuses both renders, naming what each needs.
TEST_F(LayerTest, TheMemoryCheckCountsTheHistory) {
    const Scene scene = sphereOverPlane(sharpSpot());
    setenv("PENUMBRA_DEVICE_MEMORY", "1048576", 1);
    const auto needs = [&](int frames) {
        RenderOptions o = temporal(Technique::Hard, frames);
        o.width = o.height = 4096;
        o.motion = true;
        try {
            sharedRenderer().check(scene, o);
        } catch (const InputError& e) {
            const std::string what = e.what();
            const size_t at = what.find("needs ");
            if (at != std::string::npos)
                return std::stod(what.substr(at + 6));
        }
        return -1.0;
    };
    const double without = needs(0), with = needs(16);
    unsetenv("PENUMBRA_DEVICE_MEMORY");
    ASSERT_GT(without, 0.0) << "refused, saying what it needs";
    // 2 x 16 bytes x 4096^2 = 0.5 GiB; the message gives hundredths of a GiB.
    EXPECT_NEAR(with - without, 0.5, 0.011);
}
