// Scene control from the command line and the defaults for scenes without lights or cameras
// (issue 16): what each edit changes, what it refuses, and the interior rule of scene/interior.h.
#include "generated_scenes.h"
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scene/gltf_loader.h"
#include "scene/interior.h"
#include "scene/mesh_builder.h"
#include "scratch_dir.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// The message of the InputError `f` throws ("" when it throws none).
template <typename F>
std::string refusal(F f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

Scene threeLights() {
    Scene scene;
    scene.name = "three lights";
    MeshBuilder mb(scene);
    mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, mb.material("ground", glm::vec3(0.5f)));
    scene.lights = {{.name = "key", .type = LightType::Spot, .position = {0, 4, 0}},
                    {.name = "bulb", .type = LightType::Point, .position = {1, 2, 1}},
                    {.name = "sun", .type = LightType::Directional}};
    return scene;
}

} // namespace

TEST(SceneEdits, ParsesVectorsStrictly) {
    EXPECT_EQ(parseVector3("1,-2.5,3e2", "--sun-dir"), glm::vec3(1.0f, -2.5f, 300.0f));
    for (const char* bad :
         {"1,2", "1,2,3,4", "a,b,c", "1,,3", "nan,0,0", "inf,0,0", "1e40,0,0", "1,2,3x", ""})
        EXPECT_NE(refusal([&] { parseVector3(bad, "--sun-dir"); }).find("--sun-dir"),
                  std::string::npos)
            << "'" << bad << "' must be refused";
    const NamedVector named = parseNamedVector3("lamp=post=0,1,2", "--light-pos");
    EXPECT_EQ(named.first, "lamp=post");
    EXPECT_EQ(named.second, glm::vec3(0, 1, 2));
    EXPECT_NE(refusal([] { parseNamedVector3("=0,1,2", "--light-pos"); }), "");
    EXPECT_NE(refusal([] { parseNamedVector3("lamp", "--light-pos"); }), "");
}

TEST(SceneEdits, SunDirReplacesTheDefaultLightElseAddsASun) {
    Scene withDefault = room(true);
    withDefault.lights = {defaultSun()};
    withDefault.defaultLight = true;
    applySceneEdits(withDefault, {.sunDirection = glm::vec3(0, -2, 1)});
    ASSERT_EQ(withDefault.lights.size(), 1u);
    EXPECT_EQ(withDefault.lights[0].type, LightType::Directional);
    EXPECT_NEAR(glm::length(withDefault.lights[0].direction - glm::normalize(glm::vec3(0, -2, 1))),
                0.0f, 1e-6f);
    EXPECT_FALSE(withDefault.defaultLight);

    Scene lit = threeLights();
    applySceneEdits(lit, {.sunDirection = glm::vec3(1, -1, 0)});
    ASSERT_EQ(lit.lights.size(), 4u);
    EXPECT_EQ(lit.lights[0].name, "key");
    EXPECT_EQ(lit.lights[3].type, LightType::Directional);
    EXPECT_EQ(lit.lights[3].name, "sun (--sun-dir)") << "the scene has a 'sun' already";
    EXPECT_NEAR(lit.lights[3].direction.x, std::sqrt(0.5f), 1e-6f);
    EXPECT_TRUE(lit.edits.sunDirection.has_value());

    EXPECT_NE(refusal([] {
                  Scene s = threeLights();
                  applySceneEdits(s, {.sunDirection = glm::vec3(0)});
              }).find("non-zero"),
              std::string::npos);
}

TEST(SceneEdits, LightPosAndDirMoveOnlyTheNamedLight) {
    Scene s = threeLights();
    applySceneEdits(s, {.lightPositions = {{"key", {1, 5, 2}}, {"bulb", {-1, 1, 0}}},
                        .lightDirections = {{"key", {0, -3, 0}}, {"sun", {1, -1, 1}}}});
    EXPECT_EQ(s.lights[0].position, glm::vec3(1, 5, 2));
    EXPECT_EQ(s.lights[0].direction, glm::vec3(0, -1, 0));
    EXPECT_EQ(s.lights[1].position, glm::vec3(-1, 1, 0));
    EXPECT_NEAR(glm::length(s.lights[2].direction - glm::normalize(glm::vec3(1, -1, 1))), 0.0f,
                1e-6f);
    EXPECT_EQ(s.lights[2].position, glm::vec3(0)) << "a sun has no position to move";

    const auto refused = [](SceneEdits e) {
        Scene scene = threeLights();
        return refusal([&] { applySceneEdits(scene, e); });
    };
    EXPECT_NE(refused({.lightPositions = {{"lamp", {0, 0, 0}}}}).find("no light named 'lamp'"),
              std::string::npos);
    EXPECT_NE(refused({.lightPositions = {{"lamp", {0, 0, 0}}}}).find("'key', 'bulb', 'sun'"),
              std::string::npos)
        << "the message lists the scene's lights";
    EXPECT_NE(refused({.lightPositions = {{"sun", {0, 1, 0}}}}).find("directional"),
              std::string::npos);
    EXPECT_NE(refused({.lightDirections = {{"bulb", {0, -1, 0}}}}).find("point light"),
              std::string::npos);
    EXPECT_NE(refused({.lightDirections = {{"key", {0, 0, 0}}}}).find("non-zero"),
              std::string::npos);
}

TEST(SceneEdits, CameraPosLookAtAndFovMakeTheFirstCamera) {
    Scene s = room(true);
    s.cameras.push_back({.name = "asset's own"});
    applySceneEdits(
        s,
        {.cameraPosition = glm::vec3(-8, 2, 5), .lookAt = glm::vec3(0, 1, 0), .fovDegrees = 30.0f});
    const Camera c = s.camera("");
    EXPECT_EQ(c.name, "command line");
    EXPECT_EQ(c.position, glm::vec3(-8, 2, 5));
    EXPECT_EQ(c.target, glm::vec3(0, 1, 0));
    EXPECT_NEAR(c.yfov, glm::radians(30.0f), 1e-6f);
    // The far plane holds the room's farthest corner, (10, 4, -6) here.
    EXPECT_GT(c.zfar, glm::length(glm::vec3(10, 4, -6) - c.position));
    EXPECT_LT(c.znear, 0.01f);
    EXPECT_GT(c.znear, 0.0f);
    EXPECT_EQ(s.camera("asset's own").name, "asset's own");

    Scene straightDown = room(true);
    applySceneEdits(straightDown,
                    {.cameraPosition = glm::vec3(0, 3.5f, 0), .lookAt = glm::vec3(0, 0, 0)});
    EXPECT_GT(glm::length(glm::cross(straightDown.cameras[0].up, glm::vec3(0, -1, 0))), 0.9f)
        << "looking straight down needs an up that is not the view axis";

    const auto refused = [](SceneEdits e) {
        Scene scene = room(true);
        return refusal([&] { applySceneEdits(scene, e); });
    };
    EXPECT_NE(refused({.cameraPosition = glm::vec3(1)}).find("go together"), std::string::npos);
    EXPECT_NE(refused({.fovDegrees = 40.0f}).find("go together"), std::string::npos);
    EXPECT_NE(refused({.cameraPosition = glm::vec3(1), .lookAt = glm::vec3(1)}).find("--look-at"),
              std::string::npos);
    for (float fov : {1.0f, 170.0f}) // the range's ends are accepted
        EXPECT_EQ(
            refused(
                {.cameraPosition = glm::vec3(0, 1, 5), .lookAt = glm::vec3(0), .fovDegrees = fov}),
            "")
            << fov;
    for (float fov : {0.0f, 0.5f, 0.999f, 170.01f, 175.0f})
        EXPECT_NE(
            refused(
                {.cameraPosition = glm::vec3(0, 1, 5), .lookAt = glm::vec3(0), .fovDegrees = fov})
                .find("--fov"),
            std::string::npos)
            << fov;
}
