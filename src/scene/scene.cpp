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
    {"figure", builtin::figure},     {"resting", builtin::resting}};

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
    return names;
}

Scene loadScene(std::string_view spec, const SceneLoadOptions& options) {
    constexpr std::string_view prefix = "builtin:";
    if (spec.starts_with(prefix)) {
        const std::string_view name = spec.substr(prefix.size());
        if (name.starts_with("gen/"))
            return generatedScene(name.substr(4));
        for (const auto& b : kBuiltins)
            if (b.name == name)
                return b.make();
        std::string names;
        for (const auto& b : kBuiltins)
            names += (names.empty() ? "" : ", ") + std::string(b.name);
        throw InputError(std::string(spec),
                         "no such built-in scene (built-in: " + names + ", or gen/FAMILY?seed=N)");
    }
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
                               .warnings = options.warnings});
    }
    throw InputError(std::string(spec),
                     "not a scene: expected builtin:NAME, a .gltf or a .glb file");
}

} // namespace penumbra
