// Scene control from the command line (issue 16): the edits change the loaded scene itself, so
// that render, the ground truth, the report and stats.json all see the same lights and camera.
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "scene/first_picture.h"
#include "scene/framing.h"
#include "scene/interior.h"
#include "scene/mesh_builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace penumbra {
namespace {

constexpr std::pair<ViewChoice, std::string_view> kViewChoiceNames[] = {
    {ViewChoice::Auto, "auto"},
    {ViewChoice::Exterior, "exterior"},
    {ViewChoice::Interior, "interior"}};

std::string lightNames(const Scene& scene) {
    std::string names;
    for (const Light& l : scene.lights)
        names += (names.empty() ? "'" : ", '") + l.name + "'";
    return names.empty() ? "none" : names;
}

Light& lightNamed(Scene& scene, const std::string& name, const char* option) {
    for (Light& l : scene.lights)
        if (l.name == name)
            return l;
    throw InputError(option, fmt::format("scene '{}' has no light named '{}' (lights: {})",
                                         scene.name, name, lightNames(scene)));
}

glm::vec3 unitDirection(const glm::vec3& d, const char* option) {
    if (!(glm::length(d) > 1e-12f))
        throw InputError(option, "a direction needs a non-zero length");
    return glm::normalize(d);
}

} // namespace

glm::vec3 parseVector3(std::string_view text, std::string_view option) {
    glm::vec3 v(0.0f);
    std::string rest(text);
    for (int i = 0; i < 3; ++i) {
        const size_t comma = rest.find(',');
        if ((i < 2) != (comma != std::string::npos))
            throw InputError(std::string(option),
                             fmt::format("'{}' is not three numbers X,Y,Z", text));
        const std::string part = rest.substr(0, comma);
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(part.c_str(), &end);
        if (part.empty() || end != part.c_str() + part.size() || errno == ERANGE ||
            !std::isfinite(value) || std::abs(value) > kMaxCoordinate)
            throw InputError(std::string(option),
                             fmt::format("'{}' is not three finite numbers X,Y,Z", text));
        v[i] = static_cast<float>(value);
    }
    return v;
}

NamedVector parseNamedVector3(std::string_view text, std::string_view option) {
    const size_t eq = text.rfind('=');
    if (eq == std::string_view::npos || eq == 0)
        throw InputError(std::string(option), fmt::format("'{}' is not NAME=X,Y,Z", text));
    return {std::string(text.substr(0, eq)), parseVector3(text.substr(eq + 1), option)};
}

bool SceneEdits::empty() const {
    return !sunDirection && lightPositions.empty() && lightDirections.empty() && !cameraPosition &&
           !lookAt && !fovDegrees && addedLights.empty() && !view && !ground && !noGround &&
           !doubleSided;
}

ViewChoice parseViewChoice(std::string_view text) {
    for (const auto& [choice, name] : kViewChoiceNames)
        if (name == text)
            return choice;
    throw InputError("--view", fmt::format("'{}' is not auto, exterior or interior", text));
}

std::string_view viewChoiceName(ViewChoice choice) {
    for (const auto& [c, name] : kViewChoiceNames)
        if (c == choice)
            return name;
    return "auto";
}

void addGround(Scene& scene, std::string_view material) {
    const Bounds s = subjectBounds(scene);
    const glm::vec3 c = s.center();
    // Three times its largest extent: a tall model's shadow is as long as it is tall. A subject
    // of no size (one point) gets a ground of 2e-3; any other, however small, its own.
    const float longest = std::max({s.extent().x, s.extent().y, s.extent().z});
    const float half = longest > 0.0f ? 1.5f * longest : 1e-3f;
    const float y = s.min.y;
    MeshBuilder mb(scene);
    mb.quad({c.x - half, y, c.z + half}, {c.x + half, y, c.z + half}, {c.x + half, y, c.z - half},
            {c.x - half, y, c.z - half}, mb.material(std::string(material), glm::vec3(0.6f)));
}

void applySceneEdits(Scene& scene, const SceneEdits& e) {
    if (e.view) {
        scene.cameras.insert(scene.cameras.begin(), automaticCamera(scene, *e.view));
        if (scene.defaultLight) // the stand-in light follows the view it was placed for
            scene.lights.front() = defaultLightFor(scene, scene.cameras.front(),
                                                   scene.cameras.front().name == "auto (interior)");
    }
    if (e.ground && e.noGround)
        throw InputError("--no-ground", "--ground and --no-ground contradict each other");
    if (e.ground && !scene.automaticGround) // after the framing: the view is of the subject
        addGround(scene);
    if (e.doubleSided)
        for (Material& m : scene.materials)
            m.doubleSided = true;
    if (e.sunDirection) {
        const glm::vec3 direction = unitDirection(*e.sunDirection, "--sun-dir");
        if (scene.defaultLight)
            scene.lights.clear(); // the loader's stand-in: --sun-dir replaces it
        const bool taken = std::any_of(scene.lights.begin(), scene.lights.end(),
                                       [](const Light& l) { return l.name == "sun"; });
        scene.lights.push_back({.name = taken ? "sun (--sun-dir)" : "sun",
                                .type = LightType::Directional,
                                .direction = direction,
                                .intensity = 2.0f});
        scene.defaultLight = false;
    }
    for (size_t i = 0; i < e.addedLights.size(); ++i) {
        if (scene.defaultLight)
            scene.lights.clear(); // the loader's stand-in: an added light replaces it
        scene.defaultLight = false;
        Light light = makeAddedLight(e.addedLights[i], scene, i);
        if (std::any_of(scene.lights.begin(), scene.lights.end(),
                        [&](const Light& l) { return l.name == light.name; }))
            throw InputError("--add-light", fmt::format("scene '{}' already has a light named "
                                                        "'{}' (lights: {})",
                                                        scene.name, light.name, lightNames(scene)));
        scene.lights.push_back(std::move(light));
    }
    for (const auto& [name, position] : e.lightPositions) {
        Light& l = lightNamed(scene, name, "--light-pos");
        if (l.type == LightType::Directional)
            throw InputError("--light-pos", fmt::format("'{}' is a directional light: it has a "
                                                        "direction (--light-dir), no position",
                                                        name));
        l.position = position;
    }
    for (const auto& [name, direction] : e.lightDirections) {
        Light& l = lightNamed(scene, name, "--light-dir");
        if (l.type == LightType::Point)
            throw InputError("--light-dir", fmt::format("'{}' is a point light: it has a "
                                                        "position (--light-pos), no direction",
                                                        name));
        l.direction = unitDirection(direction, "--light-dir");
    }
    if (e.cameraPosition || e.lookAt || e.fovDegrees) {
        if (!e.cameraPosition || !e.lookAt)
            throw InputError(e.cameraPosition ? "--camera-pos"
                             : e.lookAt       ? "--look-at"
                                              : "--fov",
                             "--camera-pos and --look-at go together (--fov needs both)");
        const float fov = e.fovDegrees.value_or(glm::degrees(Camera{}.yfov));
        if (!(fov >= 1.0f && fov <= 170.0f))
            throw InputError("--fov", fmt::format("{} degrees is outside [1, 170]", fov));
        const glm::vec3 forward = unitDirection(*e.lookAt - *e.cameraPosition, "--look-at");
        const glm::vec2 depth = depthRangeFrom(scene, *e.cameraPosition);
        // World up, unless the camera looks straight up or down.
        const glm::vec3 up =
            std::abs(forward.y) > 0.999f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0, 1, 0);
        scene.cameras.insert(scene.cameras.begin(), Camera{.name = "command line",
                                                           .position = *e.cameraPosition,
                                                           .target = *e.lookAt,
                                                           .up = up,
                                                           .yfov = glm::radians(fov),
                                                           .znear = depth.x,
                                                           .zfar = depth.y});
    }
    // Last: whether a ground adds a shadow depends on the camera and the lights chosen above.
    if (!e.ground && !e.noGround && !scene.automaticGround)
        addGroundWhereNothingReceives(scene);
    turnExteriorView(scene); // where the shadow on it shows
    scene.edits = e;
}

} // namespace penumbra
