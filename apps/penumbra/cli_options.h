#pragma once
// The options every command shares, in one place: list splitting, `--sweep` and its products,
// `--set` assembly onto a base and a row, the view, technique and reference option groups, and
// scene loading with the scene edits. A command file holds only what is its own.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/output_dir.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra::cli {

struct GlobalOptions {
    int device = -1;
    bool validation = false; // also PENUMBRA_VALIDATION=1
    uint64_t maxFileSize = uint64_t{1} << 30;
    uint64_t maxTriangles = 100'000'000;
};

// Scene control (--sun-dir, --light-pos, --light-dir, --camera-pos, --look-at, --fov) as typed;
// parsed and applied by loadSceneReporting, where a mistake is an `error:` line.
struct SceneOptions {
    std::string sunDirection, cameraPosition, lookAt;
    std::vector<std::string> lightPositions, lightDirections, addedLights;
    std::optional<float> fovDegrees;
    std::string view;           // --view
    std::optional<double> time; // --time: seconds into the animation (none: at rest)
    std::string animation;      // --animation: a name or an index ("" the first)
    bool ground = false, noGround = false, doubleSided = false;
};

// "a,b,c" -> {"a", "b", "c"}; an empty list or an empty item is an InputError(option).
std::vector<std::string> splitList(std::string_view text, std::string_view option);

// `--sweep key=v1,v2,...` (bench, tune).
struct Sweep {
    std::string key;
    std::vector<std::string> values;
};
// A registered key and values in its range (checked now, not mid-run); InputError("--sweep").
Sweep parseSweep(const std::string& text);

// One run's settings: (key, value) in the order of the sweeps that set them.
using Assignment = std::vector<std::pair<std::string, std::string>>;
// Every combination of the sweeps' values, the first sweep varying slowest; one empty
// assignment when there are no sweeps.
std::vector<Assignment> sweepProduct(std::span<const Sweep> sweeps);

// The options a run renders with: `base`, the row's technique and settings, then the user's
// `--set` lines (which win), checked (validate; InputError).
RenderOptions optionsFor(const RenderOptions& base, const TechniqueRow& row,
                         std::span<const std::string> sets);

// The row a single `--technique` names: a technique at its defaults, a variant ("pcf[box7]") or
// either with layers ("pcf[box3]+contact"); InputError(option) otherwise.
TechniqueRow rowNamed(const std::string& name, std::string_view option);

// One warning when a technique that takes a model's inside from its winding (sdf, second-depth)
// meets mis-wound surfaces, or open ones past 1% of the triangles (scene/mesh_closure.h), with
// the triangles counted. Called after every check, so that no warning precedes an error line.
void warnOpenGeometry(const Scene& scene, std::span<const Technique> techniques);

// Whether an --add-light orbits: the scene then moves with the time though nothing in it is
// animated.
bool lightsOrbit(const SceneOptions& options);

// loadScene with the global options, then the scene options applied; loader warnings go to
// stderr as `penumbra: warning:`, and so do light sizes that no light of the scene takes
// (--light-angle without a sun, --light-radius without a spot or point light). `quiet`: none of
// them (a timeline's later frames, whose first said them).
Scene loadSceneReporting(const std::string& spec, const GlobalOptions& global,
                         const SceneOptions& sceneOptions, const RenderOptions& options,
                         bool quiet = false);

// The option groups several commands share, under these headings in `--help` and docs/cli.md.
inline constexpr const char* kSceneGroup = "Scene and view";
inline constexpr const char* kTechniqueGroup = "Technique";
inline constexpr const char* kTruthGroup = "Ground truth";

// Options that fix what is seen: image size, camera, lights and their sizes (every command that
// takes a scene).
// Refuses an empty value ("'' is not `words`"): CLI11 takes `--opt ""` as the option not given.
CLI::Validator nonEmptyValue(const std::string& words);

void addViewOptions(CLI::App& cmd, RenderOptions& options, SceneOptions& scene);
// --shadow-map-size, --frames and --set (render, compare, bench, tune, view).
void addTechniqueOptions(CLI::App& cmd, RenderOptions& options, std::vector<std::string>& sets);
// --samples and --embree-config (reference, compare, tune).
void addReferenceOptions(CLI::App& cmd, ReferenceOptions& options);
// The scene argument, with the built-in scenes' names in its help.
void addSceneArgument(CLI::App& cmd, std::string& scene);

// Which files a float image becomes (`--format`): PFM, OpenEXR or both (the default: PFM is the
// contract tools depend on, OpenEXR what image tools open).
enum class FloatFormat { Pfm, Exr, Both };
// --format pfm|exr|both (render, reference, compare); the default is what `format` holds.
void addFormatOption(CLI::App& cmd, FloatFormat& format);
// The extension stats.json names a float image by: pfm unless only OpenEXR is written.
std::string_view namingExtension(FloatFormat format);
// Stages STEM.pfm and/or STEM.exr (rows top to bottom, 1 or 3 channels).
void writeFloatImage(StagedOutputDir& out, const std::string& stem, FloatFormat format,
                     uint32_t width, uint32_t height, uint32_t channels,
                     std::span<const float> pixels);
// Per shadow-casting light of the view, in visibility order: whether it has a size in `lit` (the
// scene with the light-size overrides applied): what the truth traced towards it.
std::vector<bool> shadowLightsSized(const Scene& lit, const RenderResult& gbuffer);
// visibility / visibility_<i>, position and normal as float images (docs/cli.md); a light's
// visibility in R, G, B where `coloured` has it (the truth through translucent casters).
void writeViewFiles(StagedOutputDir& out, const RenderResult& gbuffer,
                    const std::vector<std::vector<float>>& visibility, FloatFormat format,
                    const std::vector<std::vector<float>>& coloured = {});
// Every technique with its summary, paper and parameters (defaults, ranges, units): `penumbra
// techniques --json` and the Python module's techniques().
nlohmann::json techniquesJson();
// Raw text of a file's bytes for StagedOutputDir::write.
std::span<const uint8_t> bytesOf(const std::string& text);

} // namespace penumbra::cli
