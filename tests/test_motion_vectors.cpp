// The G-buffer's motion vectors (issue 61): each pixel's motion since the frame before, for the
// camera, for rigidly posed vertices (a new pose uploaded) and for skinned ones (placed by the
// `skin` pass), against where the host says the pixel's surface was; none for a pose drawn
// again, a first frame or a cut; and nothing made where nobody asked.
#include "analytic_scenes.h"
#include "core/projection.h"
#include "gpu_fixture.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <functional>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr uint32_t kWidth = 160, kHeight = 120;

RenderOptions withMotion(bool motion = true) {
    return {.width = kWidth,
            .height = kHeight,
            .shadowMapSize = 512,
            .frames = 1,
            .technique = Technique::Hard,
            .motion = motion};
}

glm::dmat4 viewProjOf(const Camera& camera) {
    return glm::dmat4(cameraProjection(camera, float(kWidth) / float(kHeight))) *
           glm::dmat4(lookAt(camera.position, camera.target, camera.up));
}

// Where `world` lands under `viewProj`, in pixels, and its NDC depth (gbuffer.frag's pixelOf).
glm::dvec3 pixelOf(const glm::dmat4& viewProj, glm::dvec3 world) {
    const glm::dvec4 clip = viewProj * glm::dvec4(world, 1.0);
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return {(ndc.x * 0.5 + 0.5) * kWidth, (ndc.y * 0.5 + 0.5) * kHeight, ndc.z};
}

// Every pixel's motion against where the host says its surface was (`was`: the pixel's world
// position now, read back, to where it was; the frame's camera `now`, the one before `before`).
// The position read back is the depth buffer's (D32) reconstruction, within a few float ulps of
// the rasterized point; both ends are projected in float on the device. On these scenes (a few
// units across, 160 pixels wide) that is well under 1e-3 px; 0.01 px, with 1e-5 of the motion
// for its own rounding, stays far below the pixel or more that a wrong matrix, sign or vertex
// moves it. The depth then: NDC z to 1e-5 (a relative change of 1e-5 in distance at most).
// Background pixels are NaN in both.
struct Expected {
    size_t checked = 0, wrong = 0, wrongDepth = 0, wrongBackground = 0;
    double worst = 0.0;
};
Expected compareMotion(const RenderResult& r, const glm::dmat4& before,
                       const std::function<glm::dvec3(glm::dvec3)>& was) {
    Expected e;
    EXPECT_EQ(r.motion.size(), size_t{kWidth} * kHeight * 3);
    for (size_t i = 0; i < size_t{kWidth} * kHeight; ++i) {
        const glm::vec3 p = pixelVec(r.position, i), m = pixelVec(r.motion, i);
        if (!std::isfinite(p.x)) {
            e.wrongBackground += !std::isnan(m.x) || !std::isnan(m.y) || !std::isnan(m.z);
            continue;
        }
        const glm::dvec2 center(double(i % kWidth) + 0.5, double(i / kWidth) + 0.5);
        const glm::dvec3 then = pixelOf(before, was(glm::dvec3(p)));
        const glm::dvec2 want = center - glm::dvec2(then);
        const double off = glm::length(glm::dvec2(m) - want);
        e.worst = std::max(e.worst, off);
        e.wrong += !(off <= 0.01 + 1e-5 * glm::length(want));
        e.wrongDepth += !(std::abs(double(m.z) - then.z) <= 1e-5 * std::abs(then.z) + 1e-7);
        ++e.checked;
    }
    return e;
}

void expectMotion(const RenderResult& r, const glm::dmat4& before,
                  const std::function<glm::dvec3(glm::dvec3)>& was, const std::string& what) {
    const Expected e = compareMotion(r, before, was);
    EXPECT_GT(e.checked, size_t{kWidth} * kHeight / 4) << what;
    EXPECT_EQ(e.wrong, 0u) << what << ": worst " << e.worst << " px off, of " << e.checked;
    EXPECT_EQ(e.wrongDepth, 0u) << what << ": the depth then";
    EXPECT_EQ(e.wrongBackground, 0u) << what << ": background not NaN";
}

// No motion at all: every surface pixel's is exactly zero (the same projection at both ends).
size_t movingPixels(const RenderResult& r) {
    size_t n = 0;
    for (size_t i = 0; i < size_t{kWidth} * kHeight; ++i)
        n += std::isfinite(r.motion[3 * i]) &&
             (r.motion[3 * i] != 0.0f || r.motion[3 * i + 1] != 0.0f);
    return n;
}

bool onSphere(glm::vec3 v) {
    return v.y > 0.1f; // sphereOverPlane's sphere: its lowest point is 0.5 above the plane
}

Scene sphereMovedBy(Scene scene, glm::vec3 by) {
    for (Vertex& v : scene.vertices)
        if (onSphere(v.position))
            v.position += by;
    return scene;
}

} // namespace

// The camera alone moves: every pixel's motion is where its point lands now minus where the last
// camera saw it; the same camera again, and a cut, have none.
TEST_F(ShadowTest, MotionVectorsFollowTheCamera) {
    const Scene scene = sphereOverPlane(sharpSun());
    SceneRenderer renderer(sharedRenderer(), scene);
    const Camera first = scene.cameras.front();
    const RenderResult rest = renderer.render(withMotion(), {.camera = first});
    EXPECT_EQ(movingPixels(rest), 0u) << "a first frame";
    Camera second = first;
    second.position += glm::vec3(0.4f, -0.3f, 0.2f);
    second.target += glm::vec3(-0.2f, 0.1f, 0.0f);
    const RenderResult moved = renderer.render(withMotion(), {.camera = second, .continues = true});
    expectMotion(
        moved, viewProjOf(first), [](glm::dvec3 p) { return p; }, "camera moved");
    EXPECT_GT(movingPixels(moved), size_t{kWidth} * kHeight / 4);
    const RenderResult again = renderer.render(withMotion(), {.camera = second, .continues = true});
    EXPECT_EQ(movingPixels(again), 0u) << "the same camera again";
    Camera third = second;
    third.position.x += 1.0f;
    const RenderResult cut =
        renderer.render(withMotion(), {.camera = third, .cut = true, .continues = true});
    EXPECT_EQ(movingPixels(cut), 0u) << "a cut";
    // A render with warm-up frames: its frames after the first draw the same camera again.
    const RenderResult warmed = renderer.render(withMotion(), {.camera = first});
    EXPECT_EQ(movingPixels(warmed), 0u) << "after a warm-up frame";
}

// A pose uploaded anew (rigid vertices) under a spot: the sphere's pixels moved by the pose's
// offset, the plane's by nothing; with the camera moving too, both add. Two poses with no frame
// between them: the motion is from the last frame drawn, not from the pose never drawn.
TEST_F(ShadowTest, MotionVectorsFollowRigidPosesFromTheLastFrameDrawn) {
    const Scene scene = sphereOverPlane(sharpSpot());
    SceneRenderer renderer(sharedRenderer(), scene);
    const Camera camera = scene.cameras.front();
    const glm::dmat4 viewProj = viewProjOf(camera);
    renderer.render(withMotion(), {.camera = camera});
    const glm::vec3 step{0.15f, 0.05f, -0.1f};
    renderer.repose(sphereMovedBy(scene, step));
    const auto sphereWas = [&](glm::dvec3 offset) {
        return [offset](glm::dvec3 p) { return onSphere(glm::vec3(p)) ? p - offset : p; };
    };
    const RenderResult moved = renderer.render(withMotion(), {.camera = camera, .continues = true});
    expectMotion(moved, viewProj, sphereWas(glm::dvec3(step)), "the sphere moved");
    const Expected still = compareMotion(moved, viewProj, [](glm::dvec3 p) { return p; });
    EXPECT_GT(still.wrong, 100u) << "the sphere's pixels should move";
    // Two poses, one never drawn; the camera moves too.
    renderer.repose(sphereMovedBy(scene, 2.0f * step));
    renderer.repose(sphereMovedBy(scene, 3.0f * step));
    Camera other = camera;
    other.position += glm::vec3(-0.3f, 0.2f, 0.1f);
    const RenderResult both = renderer.render(withMotion(), {.camera = other, .continues = true});
    expectMotion(both, viewProj, sphereWas(glm::dvec3(2.0f * step)), "two poses and the camera");
    const RenderResult again = renderer.render(withMotion(), {.camera = other, .continues = true});
    EXPECT_EQ(movingPixels(again), 0u) << "the same pose and camera again";
}

// Skinned vertices under a point light, every joint moved by one offset (so every skinned point
// moves by it): placed by the `skin` pass, whose frame first copies where they were. A skinned
// pose followed by a rigid one before any frame: still from the last frame drawn.
TEST_F(ShadowTest, MotionVectorsFollowSkinnedPoses) {
    Scene scene = sphereOverPlane(sharpPoint());
    scene.skinning.joints = {glm::mat4(1.0f)};
    for (uint32_t v = 0; v < scene.vertices.size(); ++v)
        if (onSphere(scene.vertices[v].position)) {
            scene.skinning.vertices.push_back(
                {.vertex = v,
                 .firstInfluence = uint32_t(scene.skinning.influences.size()),
                 .influenceCount = 1,
                 .position = scene.vertices[v].position,
                 .normal = scene.vertices[v].normal});
            scene.skinning.influences.push_back({.joint = 0, .weight = 1.0f});
        }
    placeSkinnedVertices(scene);
    const auto posedBy = [&](glm::vec3 offset) {
        Scene posed = scene;
        posed.skinning.joints = {glm::translate(glm::mat4(1.0f), offset)};
        placeSkinnedVertices(posed);
        return posed;
    };
    SceneRenderer renderer(sharedRenderer(), scene);
    const Camera camera = scene.cameras.front();
    const glm::dmat4 viewProj = viewProjOf(camera);
    renderer.render(withMotion(), {.camera = camera});
    const std::vector<glm::vec3> drawn = renderer.deviceGeometry().positions;
    const glm::vec3 step{-0.1f, 0.08f, 0.12f};
    renderer.repose(posedBy(step));
    const RenderResult moved = renderer.render(withMotion(), {.camera = camera, .continues = true});
    const auto sphereWas = [&](glm::dvec3 offset) {
        return [offset](glm::dvec3 p) { return onSphere(glm::vec3(p)) ? p - offset : p; };
    };
    expectMotion(moved, viewProj, sphereWas(glm::dvec3(step)), "skinned");
    EXPECT_EQ(renderer.deviceGeometry().previousPositions, drawn)
        << "the previous positions are the last frame's, copied";
    // A skinned pose, then one uploaded anew (a weight changed, which places nothing elsewhere:
    // one influence a vertex), no frame between them.
    renderer.repose(posedBy(2.0f * step));
    Scene reweighted = posedBy(3.0f * step);
    reweighted.skinning.influences[reweighted.skinning.vertices.front().firstInfluence].weight =
        2.0f;
    renderer.repose(reweighted);
    const RenderResult both = renderer.render(withMotion(), {.camera = camera, .continues = true});
    expectMotion(both, viewProj, sphereWas(glm::dvec3(2.0f * step)),
                 "a skinned pose and an uploaded one");
    // An uploaded pose, then a skinned one (joints alone), no frame between them: the skinned
    // vertices the upload left in bind space are not where the last frame drew them.
    Scene uploaded = posedBy(4.0f * step);
    uploaded.skinning.influences[uploaded.skinning.vertices.front().firstInfluence].weight = 1.0f;
    renderer.repose(uploaded);
    Scene joints = posedBy(5.0f * step);
    renderer.repose(joints);
    const RenderResult after = renderer.render(withMotion(), {.camera = camera, .continues = true});
    expectMotion(after, viewProj, sphereWas(glm::dvec3(2.0f * step)),
                 "an uploaded pose and a skinned one");
}

// Nothing asked: no motion target, nothing read back; the same frame's pixels either way.
TEST_F(ShadowTest, MotionVectorsAreMadeOnlyWhenAsked) {
    const Scene scene = sphereOverPlane(sharpSun());
    SceneRenderer renderer(sharedRenderer(), scene);
    const RenderResult without = renderer.render(withMotion(false));
    EXPECT_TRUE(without.motion.empty());
    const RenderResult with = renderer.render(withMotion(true));
    EXPECT_EQ(with.image, without.image);
    EXPECT_EQ(with.visibility, without.visibility);
}
