#include "penumbra/scene.h"
#include "penumbra/error.h"
#include "scene/builtin_scenes.h"
#include "scene/framing.h"
#include "scene/generated.h"
#include "scene/gltf_loader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

struct BuiltinEntry {
    std::string_view name;
    Scene (*make)();
};
constexpr BuiltinEntry kBuiltins[] = {
    {"showcase", builtin::showcase}, {"grazing", builtin::grazing}, {"spot", builtin::spot},
    {"foliage", builtin::foliage},   {"room", builtin::room},       {"field", builtin::field},
    {"bleeding", builtin::bleeding}, {"dense", builtin::dense},     {"demo", builtin::demo},
    {"figure", builtin::figure},     {"resting", builtin::resting}, {"sheets", builtin::sheets},
    {"glass", builtin::glass},       {"tree", builtin::tree}};

// Built-in scenes that move: made at a time (0 without --time).
struct AnimatedBuiltinEntry {
    std::string_view name;
    Scene (*make)(double time);
};
constexpr AnimatedBuiltinEntry kAnimatedBuiltins[] = {{"pendulum", builtin::pendulum},
                                                      {"town", builtin::town},
                                                      {"fan", builtin::fan},
                                                      {"walker", builtin::walker}};

} // namespace

namespace {
constexpr std::pair<LightType, std::string_view> kLightTypeNames[] = {
    {LightType::Directional, "directional"},
    {LightType::Spot, "spot"},
    {LightType::Point, "point"}};
} // namespace

std::string_view lightTypeName(LightType type) {
    for (const auto& [t, name] : kLightTypeNames)
        if (t == type)
            return name;
    return "unknown";
}

bool lightTypeFromName(std::string_view name, LightType& type) {
    for (const auto& [t, n] : kLightTypeNames)
        if (n == name)
            return type = t, true;
    return false;
}

Bounds Scene::bounds() const {
    // Only vertices that triangles use: dropped triangles may leave non-finite ones behind.
    Bounds b;
    for (uint32_t i : indices)
        if (i < vertices.size())
            b.grow(vertices[i].position);
    return b;
}

Camera Scene::camera(std::string_view cameraName) const {
    if (!cameraName.empty()) {
        for (const Camera& c : cameras)
            if (c.name == cameraName)
                return c;
        std::string names;
        for (const Camera& c : cameras)
            names += (names.empty() ? "" : ", ") + c.name;
        throw InputError("--camera",
                         fmt::format("scene '{}' has no camera named '{}' (cameras: {})", name,
                                     cameraName, names.empty() ? "none" : names));
    }
    if (!cameras.empty())
        return cameras.front();
    // Automatic framing of the subject from outside (scene/framing.h); the glTF loader has
    // already added its measured camera to scenes without one.
    return exteriorCamera(*this, subjectBounds(*this));
}

std::vector<std::string_view> builtinSceneNames() {
    std::vector<std::string_view> names;
    for (const auto& b : kBuiltins)
        names.push_back(b.name);
    for (const auto& b : kAnimatedBuiltins)
        names.push_back(b.name);
    return names;
}

namespace {

Scene loadBuiltin(std::string_view spec, std::string_view name, std::optional<double> time) {
    if (name.starts_with("gen/"))
        return generatedScene(name.substr(4));
    for (const auto& b : kBuiltins)
        if (b.name == name)
            return b.make();
    for (const auto& b : kAnimatedBuiltins)
        if (b.name == name) {
            Scene scene = b.make(time.value_or(0.0));
            scene.time = time;
            return scene;
        }
    std::string names;
    for (std::string_view n : builtinSceneNames())
        names += (names.empty() ? "" : ", ") + std::string(n);
    throw InputError(std::string(spec),
                     "no such built-in scene (built-in: " + names + ", or gen/FAMILY?seed=N)");
}

Scene loadSceneFile(std::string_view spec, const SceneLoadOptions& options) {
    const std::filesystem::path path(spec);
    const std::string ext = path.extension().string();
    if (ext == ".gltf" || ext == ".glb" || ext == ".GLTF" || ext == ".GLB") {
        const uint64_t imageBytes =
            options.maxImageBytes
                ? options.maxImageBytes
                : std::max<uint64_t>(uint64_t{64} << 20, options.maxFileSize > (uint64_t{1} << 60)
                                                             ? options.maxFileSize
                                                             : 4 * options.maxFileSize);
        return loadGltf(path, {.maxFileSize = options.maxFileSize,
                               .maxTriangles = options.maxTriangles,
                               .maxImageBytes = imageBytes,
                               .warnings = options.warnings,
                               .time = options.time,
                               .animation = options.animation});
    }
    throw InputError(std::string(spec),
                     "not a scene: expected builtin:NAME, a .gltf or a .glb file");
}

} // namespace

Scene loadScene(std::string_view spec, const SceneLoadOptions& options) {
    if (options.time && !(std::isfinite(*options.time) && *options.time >= 0.0))
        throw InputError("--time", fmt::format("{} is not a time in seconds from 0 (a finite "
                                               "number, not negative)",
                                               *options.time));
    constexpr std::string_view prefix = "builtin:";
    const bool builtin = spec.starts_with(prefix);
    Scene scene = builtin ? loadBuiltin(spec, spec.substr(prefix.size()), options.time)
                          : loadSceneFile(spec, options);
    // A built-in has one animation at most: its name or index 0 chooses it.
    if (builtin && !options.animation.empty() &&
        (scene.animation.empty() ||
         (options.animation != scene.animation && options.animation != "0")))
        throw InputError("--animation", scene.animation.empty()
                                            ? fmt::format("'{}' has no animations", spec)
                                            : fmt::format("'{}' has one animation, 0 '{}'", spec,
                                                          scene.animation));
    scene.time = options.time; // an orbiting --add-light is placed by it, even on a still scene
    if (scene.time)
        *scene.time += 0.0; // -0 is 0
    // A time for a still scene changes nothing: said, not refused, so one command line serves
    // a set of scenes.
    if (options.time && scene.animation.empty() && !options.lightsMove && options.warnings)
        options.warnings->push_back(fmt::format("{}: --time {}: the scene has no animations; it "
                                                "is drawn at rest",
                                                spec, *options.time));
    return scene;
}

} // namespace penumbra
