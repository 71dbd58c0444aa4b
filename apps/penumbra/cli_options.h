#pragma once
// The options every command shares, in one place: list splitting, `--sweep` and its products,
// `--set` assembly onto a base and a row, the view, technique and reference option groups, and
// scene loading with the scene edits. A command file holds only what is its own.
#include <CLI/CLI.hpp>

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
    std::vector<std::string> lightPositions, lightDirections;
    std::optional<float> fovDegrees;
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

// loadScene with the global options, then the scene options applied; loader warnings go to
// stderr as `penumbra: warning:`.
Scene loadSceneReporting(const std::string& spec, const GlobalOptions& global,
                         const SceneOptions& sceneOptions);

// Options that fix what is seen: image size, camera, lights and their sizes (every command that
// takes a scene).
void addViewOptions(CLI::App& cmd, RenderOptions& options, SceneOptions& scene);
// --shadow-map-size, --frames and --set (render, compare, bench, tune, view).
void addTechniqueOptions(CLI::App& cmd, RenderOptions& options, std::vector<std::string>& sets);
// --samples and --embree-config (reference, compare, tune).
void addReferenceOptions(CLI::App& cmd, ReferenceOptions& options);
// The scene argument, with the built-in scenes' names in its help.
void addSceneArgument(CLI::App& cmd, std::string& scene);

// visibility.pfm / visibility_<i>.pfm, position.pfm and normal.pfm (design.md §1).
void writeViewFiles(StagedOutputDir& out, const RenderResult& gbuffer,
                    const std::vector<std::vector<float>>& visibility);
// Raw text of a file's bytes for StagedOutputDir::write.
std::span<const uint8_t> bytesOf(const std::string& text);

} // namespace penumbra::cli
