// --add-light: a light from the command line, for assets without the lights a user wants (a sun
// over a model, a bulb in a room). "KIND:key=value,..." with vectors as three numbers after their
// key: sun:dir=0,-1,0.5,angle=2; spot:pos=0,4,0,dir=0,-1,0,cone=30,radius=0.2; point:pos=1,3,0.
// orbit=SECONDS turns one about the vertical through about=X,Y,Z over time (a light that moves
// without a glTF animation).
#include "penumbra/error.h"
#include "penumbra/scene.h"

#include <fmt/format.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>
#include <set>

namespace penumbra {
namespace {

constexpr std::string_view kOption = "--add-light";
// A turn in under a millisecond moves a light further between frames than any shadow follows.
constexpr float kMinOrbitSeconds = 1e-3f;

[[noreturn]] void refuse(std::string_view text, const std::string& why) {
    throw InputError(std::string(kOption),
                     fmt::format("'{}': {} (KIND:key=value,...: sun:dir=X,Y,Z[,angle=DEG], "
                                 "spot:pos=X,Y,Z,dir=X,Y,Z[,cone=DEG][,radius=R], "
                                 "point:pos=X,Y,Z[,radius=R]; all take intensity=, name= and "
                                 "orbit=SECONDS, spot and point about=X,Y,Z)",
                                 text, why));
}

double number(std::string_view text, const std::string& part) {
    char* end = nullptr;
    const double value = std::strtod(part.c_str(), &end);
    // Past double's range strtod gives infinity; below it, a number near zero (both ERANGE).
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(value))
        refuse(text, fmt::format("'{}' is not a finite number", part));
    if (std::abs(value) > kMaxCoordinate) // what a scene's coordinates may reach
        refuse(text, fmt::format("'{}' is past {:g} in magnitude", part, kMaxCoordinate));
    return value;
}

} // namespace

AddedLight parseAddedLight(std::string_view text) {
    const size_t colon = text.find(':');
    if (colon == std::string_view::npos)
        refuse(text, "no KIND: before the settings");
    const std::string kind(text.substr(0, colon));
    AddedLight light{.text = std::string(text)};
    if (kind == "sun")
        light.type = LightType::Directional;
    else if (kind == "spot")
        light.type = LightType::Spot;
    else if (kind == "point")
        light.type = LightType::Point;
    else
        refuse(text, fmt::format("'{}' is not sun, spot or point", kind));

    // key=value items; an item without '=' continues the previous key's numbers (X,Y,Z).
    std::vector<std::string> items;
    for (std::string_view rest = text.substr(colon + 1);;) {
        const size_t comma = rest.find(',');
        items.emplace_back(rest.substr(0, comma));
        if (comma == std::string_view::npos)
            break;
        rest = rest.substr(comma + 1);
    }
    std::map<std::string, std::vector<std::string>> values;
    std::string key;
    for (const std::string& item : items) {
        if (item.empty())
            refuse(text, "an empty item between commas");
        const size_t eq = item.find('=');
        if (eq != std::string::npos) {
            key = item.substr(0, eq);
            if (values.count(key))
                refuse(text, fmt::format("'{}' is given twice", key));
            values[key].push_back(item.substr(eq + 1));
        } else if (key.empty()) {
            refuse(text, fmt::format("'{}' has no key=", item));
        } else {
            values[key].push_back(item);
        }
    }
    const std::set<std::string> allowed =
        light.type == LightType::Directional
            ? std::set<std::string>{"dir", "angle", "intensity", "name", "orbit"}
        : light.type == LightType::Spot
            ? std::set<std::string>{"pos",       "dir",  "cone",  "radius",
                                    "intensity", "name", "orbit", "about"}
            : std::set<std::string>{"pos", "radius", "intensity", "name", "orbit", "about"};
    for (const auto& [k, v] : values) {
        if (!allowed.count(k))
            refuse(text, fmt::format("a {} light takes no '{}'", kind, k));
        const size_t count = k == "pos" || k == "dir" || k == "about" ? 3 : 1;
        if (v.size() != count)
            refuse(text, fmt::format("'{}' takes {}", k,
                                     count == 3 ? "three numbers X,Y,Z" : "one value"));
    }
    const auto vector = [&](const std::string& k) -> std::optional<glm::vec3> {
        if (!values.count(k))
            return std::nullopt;
        const std::vector<std::string>& v = values[k];
        return glm::vec3(number(text, v[0]), number(text, v[1]), number(text, v[2]));
    };
    const auto scalar = [&](const std::string& k) -> std::optional<float> {
        if (!values.count(k))
            return std::nullopt;
        return static_cast<float>(number(text, values[k][0]));
    };
    light.position = vector("pos");
    light.direction = vector("dir");
    light.angleDegrees = scalar("angle");
    light.coneDegrees = scalar("cone");
    light.radius = scalar("radius");
    light.intensity = scalar("intensity");
    light.orbitSeconds = scalar("orbit");
    light.orbitCentre = vector("about");
    if (values.count("name"))
        light.name = values["name"][0];
    if (light.type != LightType::Point && !light.direction)
        refuse(text, "it needs dir=X,Y,Z, the direction its light travels");
    if (light.type != LightType::Directional && !light.position)
        refuse(text, "it needs pos=X,Y,Z");
    if (light.direction && !(glm::length(*light.direction) > 1e-12f))
        refuse(text, "dir needs a non-zero length");
    if (light.angleDegrees && !(*light.angleDegrees >= 0.0f && *light.angleDegrees <= 30.0f))
        refuse(text, "angle is the sun's angular diameter, 0 to 30 degrees");
    if (light.coneDegrees && !(*light.coneDegrees > 0.0f && *light.coneDegrees <= 89.0f))
        refuse(text, "cone is the spot's half-angle, above 0 and at most 89 degrees");
    if (light.radius && !(*light.radius >= 0.0f))
        refuse(text, "radius must be at least 0");
    if (light.intensity && !(*light.intensity > 0.0f))
        refuse(text, "intensity must be above 0");
    if (values.count("name") && light.name.empty())
        refuse(text, "name is empty");
    if (light.orbitSeconds && !(std::abs(*light.orbitSeconds) >= kMinOrbitSeconds))
        refuse(text, fmt::format("orbit is the seconds one turn takes: at least {:g} in "
                                 "magnitude (negative turns the other way)",
                                 kMinOrbitSeconds));
    if (light.orbitCentre && !light.orbitSeconds)
        refuse(text, "about= is the centre of an orbit=; it needs one");
    return light;
}

Light makeAddedLight(const AddedLight& added, const Scene& scene, size_t index) {
    Light l{.name = added.name.empty()
                        ? fmt::format("{} (--add-light {})", lightTypeName(added.type), index + 1)
                        : added.name,
            .type = added.type};
    if (added.direction)
        l.direction = glm::normalize(*added.direction);
    if (added.position)
        l.position = *added.position;
    if (added.orbitSeconds) {
        // About +y by the right-hand rule (x toward -z), the angle in double: a long time
        // keeps its fraction of a turn.
        const double turns = scene.time.value_or(0.0) / double(*added.orbitSeconds);
        const auto angle = static_cast<float>(2.0 * std::numbers::pi * (turns - std::floor(turns)));
        const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0)));
        // The axis is vertical: the centre's height is no matter, and the light's holds.
        const glm::vec3 centre = added.orbitCentre.value_or(scene.bounds().center());
        l.position = centre + turn * (l.position - centre);
        l.direction = turn * l.direction;
    }
    if (added.type == LightType::Directional) {
        l.intensity = added.intensity.value_or(2.0f); // as --sun-dir's
        l.angularDiameter = added.angleDegrees.value_or(0.0f);
        return l;
    }
    // Unless given: as bright at the scene's centre as the default sun is everywhere (the
    // intensity is per steradian at one unit, falling off with the square of the distance).
    // An orbit keeps its distance: the brightness of its place at time 0 holds.
    const float distance = std::max(glm::length(scene.bounds().center() - *added.position), 1e-3f);
    l.intensity = added.intensity.value_or(2.0f * distance * distance);
    l.radius = added.radius.value_or(0.0f);
    if (added.type == LightType::Spot) {
        l.outerConeAngle = glm::radians(added.coneDegrees.value_or(45.0f));
        l.innerConeAngle = 0.8f * l.outerConeAngle; // a soft rim
    }
    return l;
}

} // namespace penumbra
