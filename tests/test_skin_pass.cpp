// The `skin` pass (issue 59): skinned vertices placed on the GPU in the first frame after each
// pose, where the host placed them (placeSkinnedVertices) to within what float arithmetic allows,
// before anything of that frame draws them, for every light type; and only then.
#include "analytic_scenes.h"
#include "gpu_fixture.h"
#include "penumbra/error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstring>
#include <random>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr double kUnit = 0x1p-24; // a float's unit roundoff

RenderOptions small(Technique technique = Technique::Hard) {
    return {.width = 160, .height = 120, .shadowMapSize = 512, .frames = 1, .technique = technique};
}

glm::dmat4 absolute(const glm::mat4& m) {
    glm::dmat4 a(0.0);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            a[c][r] = std::abs(double(m[c][r]));
    return a;
}

// |a| x |b|'s bound: each component of a x b is a difference of two products.
glm::dvec3 crossBound(glm::dvec3 a, glm::dvec3 b) {
    return {a.y * b.z + a.z * b.y, a.z * b.x + a.x * b.z, a.x * b.y + a.y * b.x};
}

// Every skinned vertex as the device holds it against the host's placement. The skin pass sums
// n weighted joint matrices in float (each entry n roundings) and the n weights (n more), scales
// by the sum's reciprocal (a division within 2.5 ulp, Vulkan says, and a multiply), then
// multiplies by the point (4 more); adds and multiplies are correctly rounded, so a coordinate
// is within (2n + 10) u of the sum of its terms' magnitudes over the weights' sum (twice that). The
// normal's cofactors are products of two such entries (4n + 12 roundings of the magnitudes), and
// made unit it moves by at most twice its error over its length (plus normalize's few ulps).
// Unskinned vertices, and the positions buffer against the vertices, are bit for bit.
void expectPlacedAsTheHost(const Scene& host, const SceneRenderer::DeviceGeometry& device,
                           const std::string& what) {
    ASSERT_EQ(device.vertices.size(), host.vertices.size()) << what;
    std::vector<bool> skinned(host.vertices.size(), false);
    size_t wrongPositions = 0, wrongNormals = 0;
    for (const SkinnedVertex& sv : host.skinning.vertices) {
        skinned[sv.vertex] = true;
        const double n = sv.influenceCount;
        glm::dmat4 magnitude(0.0), blend(0.0);
        double total = 0.0;
        for (uint32_t k = sv.firstInfluence; k < sv.firstInfluence + sv.influenceCount; ++k) {
            const SkinInfluence& influence = host.skinning.influences[k];
            magnitude += double(influence.weight) * absolute(host.skinning.joints[influence.joint]);
            blend += double(influence.weight) * glm::dmat4(host.skinning.joints[influence.joint]);
            total += double(influence.weight);
        }
        magnitude /= total;
        blend /= total;
        const Vertex &got = device.vertices[sv.vertex], &want = host.vertices[sv.vertex];
        const glm::dvec3 terms(magnitude * glm::dvec4(glm::abs(glm::dvec3(sv.position)), 1.0));
        for (int c = 0; c < 3; ++c)
            wrongPositions += !(std::abs(double(got.position[c]) - double(want.position[c])) <=
                                2.0 * (2.0 * n + 10.0) * kUnit * terms[c] + 1e-30);
        const glm::dvec3 bind(sv.normal), a0(magnitude[0]), a1(magnitude[1]), a2(magnitude[2]);
        const glm::dvec3 bound = crossBound(a1, a2) * std::abs(bind.x) +
                                 crossBound(a2, a0) * std::abs(bind.y) +
                                 crossBound(a0, a1) * std::abs(bind.z);
        const glm::dvec3 exact = glm::transpose(glm::inverse(glm::dmat3(blend))) * bind *
                                 std::abs(glm::determinant(glm::dmat3(blend)));
        const double tolerance =
            2.0 * (4.0 * n + 12.0) * kUnit * glm::length(bound) / glm::length(exact) + 8.0 * kUnit;
        wrongNormals +=
            !(glm::length(glm::dvec3(got.normal) - glm::dvec3(want.normal)) <= tolerance);
        EXPECT_EQ(device.positions[sv.vertex], got.position) << what << ": positions buffer";
    }
    EXPECT_EQ(wrongPositions, 0u) << what << ": coordinates past the float bound, of "
                                  << host.skinning.vertices.size() << " vertices";
    EXPECT_EQ(wrongNormals, 0u) << what << ": normals past the float bound";
    size_t unskinnedDiffer = 0;
    for (size_t v = 0; v < host.vertices.size(); ++v)
        if (!skinned[v])
            unskinnedDiffer +=
                std::memcmp(&device.vertices[v], &host.vertices[v], sizeof(Vertex)) != 0 ||
                device.positions[v] != host.vertices[v].position;
    EXPECT_EQ(unskinnedDiffer, 0u) << what << ": unskinned vertices changed";
}

// A ground, a sphere and a tube over it, every vertex of the two skinned to 1 to 6 of 5 joints
// drawn from `seed` (turned, stretched unevenly, one mirrored, moved), with weights of any sum.
Scene randomSkin(uint32_t seed, const Light& light) {
    Scene scene;
    scene.name = "random skin " + std::to_string(seed);
    MeshBuilder mb(scene);
    mb.quad({-6, 0, 6}, {6, 0, 6}, {6, 0, -6}, {-6, 0, -6},
            mb.material("ground", {0.6f, 0.6f, 0.6f}));
    const size_t first = scene.vertices.size();
    const uint32_t red = mb.material("skinned", {0.7f, 0.3f, 0.2f});
    mb.sphere({0.0f, 1.2f, 0.0f}, 0.6f, red, 16, 10);
    mb.tube({-1.0f, 0.5f, 0.8f}, {1.0f, 1.5f, 0.8f}, 0.2f, red, 12);
    std::mt19937 random(seed);
    auto uniform = [&](float lo, float hi) {
        return std::uniform_real_distribution<float>(lo, hi)(random);
    };
    for (int j = 0; j < 5; ++j) {
        const glm::vec3 axis = glm::normalize(glm::vec3(uniform(-1, 1), uniform(-1, 1), 1.0f));
        glm::mat4 m = glm::translate(
            glm::mat4(1.0f), {uniform(-0.3f, 0.3f), uniform(0, 0.4f), uniform(-0.3f, 0.3f)});
        m = glm::rotate(m, uniform(-0.8f, 0.8f), axis);
        m = glm::scale(
            m, {j == 4 ? -1.0f : uniform(0.7f, 1.3f), uniform(0.7f, 1.3f), uniform(0.7f, 1.3f)});
        scene.skinning.joints.push_back(m);
    }
    for (size_t v = first; v < scene.vertices.size(); ++v) {
        const auto count = static_cast<uint32_t>(1 + random() % 6);
        const auto start = static_cast<uint32_t>(scene.skinning.influences.size());
        for (uint32_t k = 0; k < count; ++k) // the mirrored joint light, so no blend folds flat
            scene.skinning.influences.push_back(
                {.joint = static_cast<uint32_t>(random() % 5),
                 .weight = uniform(0.05f, 2.0f) * (k == 0 ? 4.0f : 1.0f)});
        std::sort(scene.skinning.influences.begin() + start, scene.skinning.influences.end(),
                  [](const SkinInfluence& a, const SkinInfluence& b) { return a.joint < b.joint; });
        scene.skinning.vertices.push_back({.vertex = static_cast<uint32_t>(v),
                                           .firstInfluence = start,
                                           .influenceCount = count,
                                           .position = scene.vertices[v].position,
                                           .normal = scene.vertices[v].normal});
    }
    placeSkinnedVertices(scene);
    scene.lights.push_back(light);
    scene.cameras.push_back({.name = "above",
                             .position = {0.5f, 6.0f, 6.0f},
                             .target = {0.0f, 0.8f, 0.0f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 50.0f});
    return scene;
}

bool hasPass(const RenderResult& r, std::string_view name) {
    return std::any_of(r.passes.begin(), r.passes.end(),
                       [&](const PassTime& p) { return p.pass == name; });
}

// Pixels whose visibility of light `l` differs by more than a half.
double differing(const RenderResult& a, const RenderResult& b, size_t l) {
    size_t n = 0;
    for (size_t i = 0; i < a.visibility[l].size(); ++i)
        n += std::abs(a.visibility[l][i] - b.visibility[l][i]) > 0.5f;
    return double(n) / double(a.visibility[l].size());
}

} // namespace

// Random skins, every light type: before the first frame the device holds the skinned vertices
// in bind space; after it, where the host put them. A second seed's joints reposed onto the same
// renderer are placed too.
TEST_F(FrameTest, TheSkinPassPlacesEveryVertexWhereTheHostDoesToFloatRounding) {
    const std::array<Light, 3> lights{sharpSun(), sharpSpot(), sharpPoint()};
    for (uint32_t seed = 1; seed <= 3; ++seed) {
        const Scene scene = randomSkin(seed, lights[seed - 1]);
        SceneRenderer renderer(sharedRenderer(), scene);
        const SceneRenderer::DeviceGeometry unplaced = renderer.deviceGeometry();
        size_t inBindSpace = 0;
        for (const SkinnedVertex& sv : scene.skinning.vertices)
            inBindSpace += unplaced.vertices[sv.vertex].position == sv.position &&
                           unplaced.vertices[sv.vertex].normal == sv.normal;
        EXPECT_EQ(inBindSpace, scene.skinning.vertices.size()) << "seed " << seed;
        renderer.render(small());
        expectPlacedAsTheHost(renderer.scene(), renderer.deviceGeometry(),
                              "seed " + std::to_string(seed));
        // The same skin on other joints: only the joints go up, and the next frame places them.
        Scene other = scene;
        other.skinning.joints = randomSkin(seed + 10, lights[0]).skinning.joints;
        placeSkinnedVertices(other);
        renderer.repose(other);
        renderer.render(small(), {.continues = true});
        expectPlacedAsTheHost(renderer.scene(), renderer.deviceGeometry(),
                              "seed " + std::to_string(seed) + " reposed");
    }
}

// A pose whose bind data moved too (a morph target blended under a skin), one with other
// weights, and one where an unskinned vertex moved (a rigid node): each is drawn where the host
// put it.
TEST_F(FrameTest, AReposeWithMovedBindDataOrUnskinnedVerticesPlacesThemToo) {
    const Scene scene = randomSkin(7, sharpSun());
    SceneRenderer renderer(sharedRenderer(), scene);
    renderer.render(small());
    Scene morphed = scene;
    for (SkinnedVertex& sv : morphed.skinning.vertices)
        sv.position += glm::vec3(0.0f, 0.05f * sv.position.x, 0.0f);
    placeSkinnedVertices(morphed);
    renderer.repose(morphed);
    renderer.render(small(), {.continues = true});
    expectPlacedAsTheHost(renderer.scene(), renderer.deviceGeometry(), "bind data moved");
    Scene reweighted = morphed; // other weights: a skin of its own
    for (SkinInfluence& influence : reweighted.skinning.influences)
        influence.weight = 1.0f;
    placeSkinnedVertices(reweighted);
    renderer.repose(reweighted);
    renderer.render(small(), {.continues = true});
    expectPlacedAsTheHost(renderer.scene(), renderer.deviceGeometry(), "weights changed");
    Scene rigid = reweighted;
    rigid.vertices[0].position.y -= 0.01f; // a ground corner
    renderer.repose(rigid);
    renderer.render(small(), {.continues = true});
    expectPlacedAsTheHost(renderer.scene(), renderer.deviceGeometry(), "a ground corner moved");
}

// The pass runs first in the first frame after a pose (a renderer's first frame is a warm-up),
// and in no other frame; its time is the frame's.
TEST_F(FrameTest, TheSkinPassRunsFirstInTheFrameAfterEachPoseAndInNoOther) {
    SceneRenderer renderer(sharedRenderer(), builtin::walker(0.2));
    const RenderResult rest = renderer.render(small());
    EXPECT_FALSE(hasPass(rest, "skin")) << "placed in the warm-up frame";
    renderer.repose(builtin::walker(0.4));
    const RenderResult moving = renderer.render(small(), {.continues = true});
    ASSERT_FALSE(moving.passes.empty());
    EXPECT_EQ(moving.passes.front().pass, "skin");
    EXPECT_EQ(moving.passes.front().cost, CostGroup::Frame);
    EXPECT_EQ(moving.passes.front().frameMs.size(), 1u);
    const RenderResult still = renderer.render(small(), {.continues = true});
    EXPECT_FALSE(hasPass(still, "skin")) << "the same pose again";
    // Three frames after a pose: the skin pass in the first alone, 0 in the others, so every
    // pass has a time a frame and the skin pass's median is the frames' (0).
    renderer.repose(builtin::walker(0.6));
    RenderOptions three = small();
    three.frames = 3;
    const RenderResult played = renderer.render(three, {.continues = true});
    ASSERT_EQ(played.passes.front().pass, "skin");
    EXPECT_GE(played.passes.front().frameMs.at(0), 0.0);
    EXPECT_EQ(played.passes.front().frameMs,
              (std::vector<double>{played.passes.front().frameMs[0], 0.0, 0.0}));
    EXPECT_EQ(played.passes.front().medianMs, 0.0);
    for (const PassTime& p : played.passes)
        EXPECT_EQ(p.frameMs.size(), 3u) << p.pass;
    const RenderResult again = renderer.render(small());
    EXPECT_FALSE(hasPass(again, "skin"));
    // A scene with nothing skinned has no skin pass.
    Scene unskinned = randomSkin(1, sharpSun());
    unskinned.skinning = {};
    SceneRenderer none(sharedRenderer(), unskinned);
    none.repose(unskinned);
    EXPECT_FALSE(hasPass(none.render(small(), {.continues = true}), "skin"));
}

// The walker in motion under each light type: the frame right after a pose (no warm-up) shadows
// as a renderer given the host's placement draws it, so the skinning ran before every draw.
TEST_F(FrameTest, AFrameAfterAPoseDrawsTheNewPoseInEveryPassForEveryLightType) {
    for (const Light& light : {sharpSun(), sharpSpot(), sharpPoint()}) {
        Scene before = builtin::walker(0.3), after = builtin::walker(0.8);
        before.lights = after.lights = {light};
        SceneRenderer moving(sharedRenderer(), before);
        const RenderResult old = moving.render(small());
        moving.repose(after);
        const RenderResult got = moving.render(small(), {.continues = true});
        Scene host = after;
        host.skinning = {};
        SceneRenderer fresh(sharedRenderer(), host);
        const RenderResult want = fresh.render(small());
        EXPECT_GT(differing(old, want, 0), 0.003) << light.name << ": the poses must differ";
        EXPECT_LT(differing(got, want, 0), 0.002) << light.name;
    }
}

// A skin the GPU could not read is refused before anything is uploaded.
TEST_F(FrameTest, ASkinOutOfRangeIsRefused) {
    Scene scene = randomSkin(2, sharpSun());
    scene.skinning.influences.back().joint = 5;
    EXPECT_THROW(SceneRenderer(sharedRenderer(), scene), InputError);
    SceneRenderer renderer(sharedRenderer(), randomSkin(2, sharpSun()));
    EXPECT_THROW(renderer.repose(scene), InputError);
}
