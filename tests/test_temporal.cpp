// The `temporal` layer (issue 61): at rest it averages the frames it kept, each frame's samples
// turned (so the frames differ); a cut starts it again; the camera's motion reprojects it; a
// surface uncovered starts afresh (depth and normal); the clamp keeps a moving shadow from
// trailing. Every light type.
#include "analytic_scenes.h"
#include "gpu_fixture.h"
#include "scene/mesh_builder.h"

#include <cmath>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kWidth = 96, kHeight = 72;

RenderOptions temporal(Technique technique, int frames, std::string clamp = "none") {
    RenderOptions o{.width = kWidth,
                    .height = kHeight,
                    .shadowMapSize = 512,
                    .frames = 1,
                    .technique = technique};
    o.parameters.set("temporal.frames", std::to_string(frames));
    o.parameters.set("temporal.clamp", clamp);
    return o;
}

// One frame after the last, no warm-up (what a played scene draws).
RenderResult next(SceneRenderer& renderer, const RenderOptions& o,
                  SceneRenderer::FrameState state = {}) {
    state.continues = true;
    return renderer.render(o, state);
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
        SceneRenderer raw(sharedRenderer(), scene), kept(sharedRenderer(), scene);
        const RenderOptions single = temporal(Technique::Pcss, 1);
        // Any depth passes (nothing moves): after the cut only the cleared history's length (0)
        // keeps its zeros out.
        RenderOptions averaged = temporal(Technique::Pcss, 64);
        averaged.parameters.set("temporal.depthTolerance", "1");
        std::vector<double> sum;
        size_t changed = 0;
        std::vector<float> last;
        for (int k = 1; k <= 6; ++k) {
            const bool cut = k == 5;
            const RenderResult frame = next(raw, single, {.cut = cut});
            const RenderResult mean = next(kept, averaged, {.cut = cut});
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

// Hard shadows (the same every frame) under a spot while the camera pans along the plane: the
// history follows each pixel's surface, so the layer shows what the frame shows but where a
// pixel's reprojected footprint straddles a shadow's edge or a silhouette. Without reprojection
// the plane's depth at a pixel stays the same, so its history passes for the pixel's and the
// shadow's edge trails by the pan (some 5 pixels a frame).
TEST_F(LayerTest, TheTemporalLayerFollowsTheCamera) {
    const Scene scene = sphereOverPlane(sharpSpot());
    SceneRenderer raw(sharedRenderer(), scene), kept(sharedRenderer(), scene);
    const RenderOptions single = temporal(Technique::Hard, 1),
                        averaged = temporal(Technique::Hard, 64);
    Camera camera = scene.cameras.front();
    size_t worst = 0, surface = 0;
    for (int k = 0; k < 6; ++k) {
        const RenderResult frame = next(raw, single, {.camera = camera});
        const RenderResult mean = next(kept, averaged, {.camera = camera});
        worst = std::max(worst, differing(mean.visibility[0], frame.visibility[0], 0.25));
        surface = std::count_if(frame.visibility[0].begin(), frame.visibility[0].end(),
                                [](float v) { return std::isfinite(v); });
        camera.position.x += 0.4f; // some 5 pixels a frame
        camera.target.x += 0.4f;
    }
    EXPECT_LT(worst, surface / 50) << "of " << surface << " surface pixels";
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
    SceneRenderer raw(sharedRenderer(), scene), kept(sharedRenderer(), scene);
    const RenderOptions single = temporal(Technique::Hard, 1),
                        averaged = temporal(Technique::Hard, 64);
    RenderResult before;
    for (int k = 0; k < 3; ++k) {
        before = next(raw, single);
        next(kept, averaged);
    }
    Scene moved = scene;
    for (Vertex& v : moved.vertices)
        if (v.position.y > 0.5f)
            v.position.x += 0.6f;
    raw.repose(moved);
    kept.repose(moved);
    const RenderResult frame = next(raw, single), mean = next(kept, averaged);
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
        SceneRenderer raw(sharedRenderer(), scene), kept(sharedRenderer(), scene);
        const RenderOptions single = temporal(Technique::Hard, 1),
                            averaged = temporal(Technique::Hard, 64, clamp);
        for (int k = 0; k < 4; ++k) {
            next(raw, single);
            next(kept, averaged);
        }
        Scene moved = scene;
        for (Vertex& v : moved.vertices)
            if (v.position.y > 0.1f)
                v.position.z += 0.5f;
        raw.repose(moved);
        kept.repose(moved);
        const RenderResult frame = next(raw, single), mean = next(kept, averaged);
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
    SceneRenderer raw(sharedRenderer(), scene), kept(sharedRenderer(), scene);
    const RenderOptions single = temporal(Technique::Pcf, 1);
    RenderOptions averaged = temporal(Technique::Pcf, 64);
    averaged.parameters.set("pcf.filter", "poisson");
    RenderOptions singlePoisson = single;
    singlePoisson.parameters.set("pcf.filter", "poisson");
    for (int k = 0; k < 3; ++k) {
        next(raw, singlePoisson);
        next(kept, averaged);
    }
    averaged.parameters.set("temporal.gamma", "2"); // no clamp: nothing else changes
    const RenderResult frame = next(raw, singlePoisson), restarted = next(kept, averaged);
    EXPECT_EQ(largestDifference(restarted.visibility[0], frame.visibility[0]), 0.0);
}

// The sphere rises against the sky under a point light, every history texel let through (any
// depth, any normal): where a pixel's history straddles the old silhouette, the sky's texels hold
// nothing (cleared, length 0) and weigh nothing; the lit sphere stays lit.
TEST_F(LayerTest, TheSkyHoldsNoHistory) {
    Scene scene = sphereOverPlane(sharpPoint());
    scene.cameras.front().position = {0.0f, 2.0f, 5.0f}; // low: the sphere's top against the sky
    scene.cameras.front().target = {0.0f, 0.5f, -3.0f};
    SceneRenderer raw(sharedRenderer(), scene), kept(sharedRenderer(), scene);
    const RenderOptions single = temporal(Technique::Hard, 1);
    RenderOptions averaged = temporal(Technique::Hard, 64);
    averaged.parameters.set("temporal.depthTolerance", "1");
    averaged.parameters.set("temporal.normalTolerance", "-1");
    RenderResult before;
    for (int k = 0; k < 3; ++k) {
        before = next(raw, single);
        next(kept, averaged);
    }
    Scene moved = scene;
    for (Vertex& v : moved.vertices)
        if (v.position.y > 0.1f)
            v.position.y += 0.1f;
    raw.repose(moved);
    kept.repose(moved);
    const RenderResult frame = next(raw, single), mean = next(kept, averaged);
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
