#pragma once
// A benchmark plan (`penumbra sweep PLAN`, docs/sweep.md): scenes x lights x cameras x times x
// technique settings, read from TOML and checked in full before any work, so that a typing mistake
// costs nothing and a run never stops half-way on its own plan.
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::sweep {

// One light of a view. `kind` "scene" keeps the scene's own lights (their sizes set to `size`);
// "sun", "spot" and "point" replace them by this one light.
struct PlanLight {
    std::string name; // as given, else "<kind><n>" (n counts the plan's lights from 0)
    std::string kind;
    std::optional<glm::vec3> position, direction; // spot/point position; sun/spot direction
    std::optional<float> coneDegrees;             // spot: outer half-angle
    float size = 0.0f; // sun: angular diameter in degrees; others: radius in world units
};

// A technique with one value for each swept parameter.
struct PlanSetting {
    std::string technique;                                 // CLI name, e.g. "pcf"
    std::vector<std::pair<std::string, std::string>> sets; // sorted by key
    std::string name() const; // "pcf" or "pcf[pcf.samples=16,pcf.size=5]"
};

struct PlanScene {
    std::string label; // as written in the plan: "builtin:showcase", "assets/tree.gltf"
    std::string spec;  // what loadScene takes: builtin names as is, files resolved from the plan
};

struct Plan {
    std::filesystem::path path;
    std::vector<PlanScene> scenes;
    std::vector<PlanLight> lights;    // one per entry and size
    std::vector<std::string> cameras; // "" = the scene's default camera
    uint32_t width = 320, height = 180;
    uint32_t samples = 64; // truth rays per pixel and light with a size
    uint32_t shadowMapSize = 1024;
    uint32_t frames = 3; // timed frames after one warm-up frame
    // `times`: seconds into each scene's animation, a view at each (empty: the views at rest);
    // `animation`: the one they pose, by name or index ("" the first).
    std::vector<double> times;
    std::string animation;
    std::vector<PlanSetting> settings; // every grid point of every technique entry
};

// Reads and checks a plan. Problems throw InputError(PLAN, "<key>: <problem>"): unknown keys,
// techniques and parameters, values out of range, scene files that do not exist.
Plan loadPlan(const std::filesystem::path& path);

} // namespace penumbra::sweep
