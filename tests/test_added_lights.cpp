// --add-light (src/scene/added_lights.cpp): what each kind takes, what it refuses and the light it
// makes, with the defaults a scene without lights gets.
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scene/interior.h"
#include "scene/mesh_builder.h"

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace penumbra;

namespace {

std::string refusal(std::string_view text) {
    try {
        parseAddedLight(text);
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), "--add-light") << text;
        return e.what();
    }
    return "";
}

// A ground 10 wide centred at the origin: the bounds' centre is (0, 0, 0).
Scene ground() {
    Scene scene;
    scene.name = "ground";
    MeshBuilder mb(scene);
    mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, mb.material("g", glm::vec3(0.5f)));
    return scene;
}

} // namespace

TEST(AddedLights, EachKindTakesItsOwnSettings) {
    const AddedLight sun = parseAddedLight("sun:dir=0,-2,1,angle=2.5,intensity=3,name=noon");
    EXPECT_EQ(sun.type, LightType::Directional);
    EXPECT_EQ(*sun.direction, glm::vec3(0, -2, 1));
    EXPECT_EQ(*sun.angleDegrees, 2.5f);
    EXPECT_EQ(*sun.intensity, 3.0f);
    EXPECT_EQ(sun.name, "noon");
    EXPECT_EQ(sun.text, "sun:dir=0,-2,1,angle=2.5,intensity=3,name=noon");

    const AddedLight spot = parseAddedLight("spot:pos=1,4,-2,dir=0,-1,0,cone=30,radius=0.25");
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(*spot.position, glm::vec3(1, 4, -2));
    EXPECT_EQ(*spot.direction, glm::vec3(0, -1, 0));
    EXPECT_EQ(*spot.coneDegrees, 30.0f);
    EXPECT_EQ(*spot.radius, 0.25f);
    EXPECT_FALSE(spot.intensity.has_value());

    const AddedLight point = parseAddedLight("point:radius=0.5,pos=-1e-3,2,3");
    EXPECT_EQ(point.type, LightType::Point);
    EXPECT_EQ(*point.position, glm::vec3(-1e-3f, 2, 3)) << "keys in any order";
    EXPECT_EQ(*point.radius, 0.5f);
}

TEST(AddedLights, MalformedTextIsRefusedNamingWhatIsWrong) {
    const std::pair<const char*, const char*> cases[] = {
        {"point", "no KIND:"},
        {"lamp:pos=0,1,0", "'lamp' is not sun, spot or point"},
        {"sun:", "empty item"},
        {"sun:angle=2", "needs dir="},
        {"spot:pos=0,3,0", "needs dir="},
        {"spot:dir=0,-1,0", "needs pos="},
        {"point:dir=0,-1,0,pos=0,1,0", "takes no 'dir'"},
        {"sun:dir=0,-1,0,cone=20", "takes no 'cone'"},
        {"sun:dir=0,-1,0,radius=1", "takes no 'radius'"},
        {"point:pos=0,1", "three numbers"},
        {"point:pos=0,1,2,3", "three numbers"},
        {"point:pos=0,1,x", "'x' is not a finite number"},
        {"point:pos=0,1,inf", "'inf' is not a finite number"},
        {"point:pos=0,1,1e400", "'1e400' is not a finite number"},
        {"point:pos=0,1,1e30", "'1e30' is past 1e+15 in magnitude"},
        {"point:pos=0,1,-1e16", "'-1e16' is past 1e+15 in magnitude"},
        {"point:pos=0,1,0x", "'0x' is not a finite number"},
        {"point:pos=0,1,0,", "empty item"},
        {"point:pos=0,1,0,,radius=1", "empty item"},
        {"point:pos=0,1,0,pos=1,1,1", "given twice"},
        {"point:pos=0,1,0,radius=-0.1", "radius must be at least 0"},
        {"point:pos=0,1,0,intensity=0", "intensity must be above 0"},
        {"point:pos=0,1,0,name=", "name is empty"},
        {"sun:dir=0,0,0", "non-zero length"},
        {"sun:dir=0,-1,0,angle=30.5", "0 to 30 degrees"},
        {"spot:pos=0,3,0,dir=0,-1,0,cone=0", "half-angle"},
        {"spot:pos=0,3,0,dir=0,-1,0,cone=89.5", "half-angle"},
        {"sun:0,-1,0", "has no key="},
        {"sun:dir=0,-1,0,angle=1,2", "one value"},
    };
    for (const auto& [text, why] : cases)
        EXPECT_NE(refusal(text).find(why), std::string::npos) << text << ": " << refusal(text);
    EXPECT_EQ(refusal("sun:dir=0,-1,0,angle=30"), "") << "30 degrees is the largest sun";
    EXPECT_EQ(refusal("spot:pos=0,3,0,dir=0,-1,0,cone=89"), "");
    EXPECT_EQ(refusal("point:pos=0,1,0,radius=0"), "") << "a point-like light";
}

TEST(AddedLights, TheLightsTheyMakeAndTheirDefaults) {
    Scene scene = ground();
    scene.lights = {defaultSun()};
    scene.defaultLight = true;
    SceneEdits edits;
    for (const char* text :
         {"sun:dir=0,-1,1", "spot:pos=0,4,0,dir=0,-1,0", "point:pos=3,4,0,radius=0.2,name=bulb"})
        edits.addedLights.push_back(parseAddedLight(text));
    applySceneEdits(scene, edits);
    ASSERT_EQ(scene.lights.size(), 3u) << "the default light is replaced";
    EXPECT_FALSE(scene.defaultLight);
    const Light& sun = scene.lights[0];
    EXPECT_EQ(sun.name, "directional (--add-light 1)");
    EXPECT_NEAR(glm::length(sun.direction - glm::normalize(glm::vec3(0, -1, 1))), 0.0f, 1e-6f);
    EXPECT_EQ(sun.intensity, 2.0f) << "as --sun-dir's sun";
    EXPECT_EQ(sun.angularDiameter, 0.0f);
    const Light& spot = scene.lights[1];
    EXPECT_EQ(spot.name, "spot (--add-light 2)");
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_NEAR(spot.outerConeAngle, glm::quarter_pi<float>(), 1e-6f);
    EXPECT_NEAR(spot.innerConeAngle, 0.8f * glm::quarter_pi<float>(), 1e-6f);
    // As bright at the scene's centre, 4 units below, as the default sun: 2 = I / 4^2.
    EXPECT_NEAR(spot.intensity, 32.0f, 1e-4f);
    const Light& bulb = scene.lights[2];
    EXPECT_EQ(bulb.name, "bulb");
    EXPECT_EQ(bulb.position, glm::vec3(3, 4, 0));
    EXPECT_EQ(bulb.radius, 0.2f);
    EXPECT_NEAR(bulb.intensity, 2.0f * 25.0f, 1e-4f) << "5 units from the centre";
    EXPECT_EQ(scene.edits.addedLights.size(), 3u);

    // Added to a scene's own lights; a name it has already is refused.
    Scene lit = ground();
    lit.lights = {{.name = "bulb", .type = LightType::Point, .position = {0, 2, 0}}};
    SceneEdits again;
    again.addedLights.push_back(parseAddedLight("point:pos=1,1,1"));
    applySceneEdits(lit, again);
    EXPECT_EQ(lit.lights.size(), 2u);
    EXPECT_EQ(lit.lights[0].name, "bulb");
    again.addedLights.push_back(parseAddedLight("point:pos=1,2,1,name=bulb"));
    try {
        Scene copy = ground();
        copy.lights = {{.name = "bulb", .type = LightType::Point}};
        applySceneEdits(copy, again);
        ADD_FAILURE() << "a second light named bulb";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), "--add-light");
        EXPECT_NE(std::string(e.what()).find("already has a light named 'bulb'"),
                  std::string::npos);
    }
}

TEST(AddedLights, AnOrbitTurnsALightAboutTheVerticalAtTheScenesTime) {
    const std::pair<const char*, const char*> refused[] = {
        {"point:pos=3,4,0,orbit=0", "at least 0.001 in magnitude"},
        {"point:pos=3,4,0,orbit=0.0009", "at least 0.001 in magnitude"},
        {"point:pos=3,4,0,orbit=soon", "'soon' is not a finite number"},
        {"point:pos=3,4,0,orbit=1,2", "one value"},
        {"point:pos=3,4,0,about=0,0,0", "about= is the centre of an orbit=; it needs one"},
        {"point:pos=3,4,0,orbit=4,about=0,0", "three numbers"},
        {"sun:dir=1,-1,0,orbit=4,about=0,0,0", "a sun light takes no 'about'"},
    };
    for (const auto& [text, why] : refused)
        EXPECT_NE(refusal(text).find(why), std::string::npos) << text << ": " << refusal(text);
    EXPECT_EQ(refusal("point:pos=3,4,0,orbit=-0.001"), "") << "the other way, at the limit";

    // The ground's centre is the origin. A quarter turn by the right-hand rule about +y takes
    // (x, z) to (z, -x).
    const auto place = [](std::optional<double> time, const std::string& text,
                          glm::vec3 shift = glm::vec3(0.0f)) {
        Scene scene = ground();
        for (Vertex& v : scene.vertices)
            v.position += shift;
        scene.time = time;
        SceneEdits edits;
        edits.addedLights.push_back(parseAddedLight(text));
        applySceneEdits(scene, edits);
        return scene.lights.back();
    };
    const auto near = [](glm::vec3 got, glm::vec3 want) { return glm::length(got - want) < 1e-5f; };
    EXPECT_TRUE(near(place(std::nullopt, "point:pos=3,4,0,orbit=8").position, {3, 4, 0}))
        << "at rest: time 0";
    EXPECT_TRUE(near(place(2.0, "point:pos=3,4,0,orbit=8").position, {0, 4, -3}));
    EXPECT_TRUE(near(place(10.0, "point:pos=3,4,0,orbit=8").position, {0, 4, -3}))
        << "a turn and a quarter";
    EXPECT_TRUE(near(place(4.0, "point:pos=3,4,0,orbit=8").position, {-3, 4, 0}));
    EXPECT_TRUE(near(place(2.0, "point:pos=3,4,0,orbit=-8").position, {0, 4, 3}));
    // About (1, _, 1): its height is the light's own.
    EXPECT_TRUE(near(place(1.0, "point:pos=3,4,1,orbit=4,about=1,9,1").position, {1, 4, -1}));
    EXPECT_NEAR(place(1.0, "point:pos=3,4,1,orbit=4,about=1,9,1").intensity,
                place(std::nullopt, "point:pos=3,4,1").intensity, 1e-3f)
        << "as bright as where it started, though nearer the centre now";
    // By default about the scene's centre, here (10, 0, 0).
    EXPECT_TRUE(near(place(2.0, "point:pos=13,4,0,orbit=8", {10, 0, 0}).position, {10, 4, -3}));
    // A spot turns its direction with it: aimed at the centre it stays aimed there.
    const Light spot = place(1.0, "spot:pos=3,4,0,dir=-3,-4,0,orbit=4");
    EXPECT_TRUE(near(spot.position, {0, 4, -3}));
    EXPECT_TRUE(near(spot.direction, glm::vec3(0, -4, 3) / 5.0f));
    EXPECT_NEAR(spot.intensity, place(std::nullopt, "spot:pos=3,4,0,dir=-3,-4,0").intensity, 1e-3f)
        << "as bright as where it started";
    // A sun turns its direction: (1, -1, 0) goes to (0, -1, -1).
    const Light sun = place(1.0, "sun:dir=1,-1,0,orbit=4");
    EXPECT_TRUE(near(sun.direction, glm::vec3(0, -1, -1) / std::sqrt(2.0f)));
    // A long time keeps its fraction of a turn.
    EXPECT_TRUE(near(place(4e6 + 1.0, "point:pos=3,4,0,orbit=4").position, {0, 4, -3}));
}

TEST(AddedLights, ATimeMovesAnOrbitOnAStillSceneWithoutAWarning) {
    std::vector<std::string> warnings;
    const Scene moving =
        loadScene("builtin:demo", {.warnings = &warnings, .time = 1.5, .lightsMove = true});
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_EQ(moving.time, 1.5);
    const Scene still = loadScene("builtin:demo", {.warnings = &warnings, .time = 1.5});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("the scene has no animations"), std::string::npos);
    EXPECT_EQ(still.time, 1.5);
}
