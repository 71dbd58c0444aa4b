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
