// The host's placement of skinned vertices (placeSkinnedVertices), the reference the GPU's `skin`
// pass is checked against: positions and normals worked by hand for a translated, a scaled and a
// mirrored joint, and what checkSkinning refuses.
#include "penumbra/error.h"
#include "penumbra/scene.h"

#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace penumbra;

namespace {

constexpr float kFloat = 1e-6f;

// One skinned vertex at bind position `p` with normal `n`, on joints `joints` with `weights`.
Scene oneVertex(glm::vec3 p, glm::vec3 n, std::vector<glm::mat4> joints,
                std::vector<float> weights) {
    Scene s;
    s.name = "skinned";
    s.vertices.push_back({.position = glm::vec3(9.0f), .normal = {1, 0, 0}, .material = 0});
    s.vertices.push_back({.position = glm::vec3(7.0f), .normal = {1, 0, 0}, .material = 0});
    s.skinning.joints = std::move(joints);
    for (uint32_t k = 0; k < weights.size(); ++k)
        s.skinning.influences.push_back({.joint = k, .weight = weights[k]});
    s.skinning.vertices.push_back({.vertex = 1,
                                   .firstInfluence = 0,
                                   .influenceCount = static_cast<uint32_t>(weights.size()),
                                   .position = p,
                                   .normal = n});
    return s;
}

void expectNear(glm::vec3 got, glm::vec3 want, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], kFloat) << what << " component " << c;
}

} // namespace

// A quarter of a joint that moves by (4, 0, 0) and three quarters of one that scales x by 3:
// the matrices blend, then place the point; the normal goes by the blend's inverse transpose.
TEST(Skinning, APositionByTheBlendOfItsJointsAndANormalByItsInverseTranspose) {
    const glm::mat4 moved = glm::translate(glm::mat4(1.0f), {4, 0, 0});
    const glm::mat4 stretched = glm::scale(glm::mat4(1.0f), {3, 1, 1});
    Scene s = oneVertex({1, 2, 3}, {1, 1, 0}, {moved, stretched}, {0.25f, 0.75f});
    placeSkinnedVertices(s);
    // Blend: x scaled by 0.25 + 0.75 x 3 = 2.5, moved by 0.25 x 4 = 1.
    expectNear(s.vertices[1].position, {1 * 2.5f + 1, 2, 3}, "position");
    // Inverse transpose of diag(2.5, 1, 1): diag(0.4, 1, 1); (1, 1, 0) -> (0.4, 1, 0), made unit.
    expectNear(s.vertices[1].normal, glm::normalize(glm::vec3(0.4f, 1, 0)), "normal");
    expectNear(s.vertices[0].position, glm::vec3(9.0f), "an unskinned vertex stays");
    expectNear(s.vertices[0].normal, {1, 0, 0}, "an unskinned normal stays");
}

// Weights that do not sum to 1 count over their sum; a mirroring joint keeps the normal on the
// side the surface faces (the inverse transpose of x -> -x flips x, and no more).
TEST(Skinning, WeightsCountOverTheirSumAndAMirrorFlipsTheNormalWithTheSurface) {
    const glm::mat4 up = glm::translate(glm::mat4(1.0f), {0, 2, 0});
    Scene s = oneVertex({1, 0, 0}, {0, 0, 5}, {glm::mat4(1.0f), up}, {2.0f, 2.0f});
    placeSkinnedVertices(s);
    expectNear(s.vertices[1].position, {1, 1, 0}, "halfway up");
    expectNear(s.vertices[1].normal, {0, 0, 1}, "unit");
    const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), {-1, 1, 1});
    Scene m = oneVertex({1, 0, 0}, {1, 0, 0}, {mirror}, {1.0f});
    placeSkinnedVertices(m);
    expectNear(m.vertices[1].position, {-1, 0, 0}, "mirrored");
    expectNear(m.vertices[1].normal, {-1, 0, 0}, "facing out of the mirrored surface");
}

// A joint that squashes everything to a point leaves no direction: the normal is (0, 1, 0), as
// the loader's rule for a normal without one.
TEST(Skinning, ANormalWithNoDirectionLeftPointsUp) {
    Scene s = oneVertex({1, 2, 3}, {1, 0, 0}, {glm::mat4(0.0f)}, {1.0f});
    s.skinning.joints[0][3][3] = 1.0f;
    placeSkinnedVertices(s);
    expectNear(s.vertices[1].position, {0, 0, 0}, "squashed");
    expectNear(s.vertices[1].normal, {0, 1, 0}, "up");
    Scene z = oneVertex({1, 2, 3}, {0, 0, 0}, {glm::mat4(1.0f)}, {1.0f});
    placeSkinnedVertices(z);
    expectNear(z.vertices[1].normal, {0, 1, 0}, "a zero normal");
}

TEST(Skinning, CheckRefusesWhatTheGpuCouldNotRead) {
    const auto refused = [](const std::function<void(Scene&)>& edit, const std::string& why) {
        Scene s = oneVertex({0, 0, 0}, {0, 1, 0}, {glm::mat4(1.0f), glm::mat4(1.0f)}, {0.5f, 0.5f});
        EXPECT_NO_THROW(checkSkinning(s));
        edit(s);
        try {
            checkSkinning(s);
            ADD_FAILURE() << "accepted: " << why;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("skinned"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
        EXPECT_THROW(placeSkinnedVertices(s), InputError) << why;
    };
    refused([](Scene& s) { s.skinning.vertices[0].vertex = 2; }, "vertex 2 is past the 2 vertices");
    refused([](Scene& s) { s.skinning.vertices.push_back(s.skinning.vertices[0]); },
            "vertex 1 is skinned twice");
    refused([](Scene& s) { s.skinning.vertices[0].influenceCount = 0; }, "influences [0, 0)");
    refused([](Scene& s) { s.skinning.vertices[0].influenceCount = 3; },
            "influences [0, 3) are not within the 2");
    refused([](Scene& s) { s.skinning.vertices[0].firstInfluence = 1; }, "influences [1, 3)");
    refused([](Scene& s) { s.skinning.influences[1].joint = 2; }, "joint 2 is past the 2 joints");
    refused(
        [](Scene& s) {
            s.skinning.influences[0].weight = 0.0f;
            s.skinning.influences[1].weight = 0.0f;
        },
        "its weights sum to 0");
    // The last vertex and the last influence are in range.
    Scene edge = oneVertex({0, 0, 0}, {0, 1, 0}, {glm::mat4(1.0f), glm::mat4(1.0f)}, {0.5f, 0.5f});
    edge.skinning.vertices[0].firstInfluence = 1;
    edge.skinning.vertices[0].influenceCount = 1;
    EXPECT_NO_THROW(checkSkinning(edge));
}
