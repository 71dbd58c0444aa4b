#pragma once
// The sub-commands of the `penumbra` CLI (design.md §1). Each registers its options on the app
// and returns the action to run when it was chosen.
#include <CLI/CLI.hpp>

#include "core/output_dir.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

#include <functional>
#include <optional>
#include <span>
#include <string>
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

// loadScene with the global options, then the scene options applied; loader warnings go to
// stderr as `penumbra: warning:`.
Scene loadSceneReporting(const std::string& spec, const GlobalOptions& global,
                         const SceneOptions& sceneOptions);

using Action = std::function<int()>;

// `--sweep key=v1,v2,...` (bench, tune).
struct Sweep {
    std::string key;
    std::vector<std::string> values;
};
// A registered key and values in its range (checked now, not mid-run); InputError("--sweep").
Sweep parseSweep(const std::string& text);

// Options that fix what is seen: image size, camera, lights and their sizes (every command that
// takes a scene).
void addViewOptions(CLI::App& cmd, RenderOptions& options, SceneOptions& scene);
// --shadow-map-size, --frames and --set (render, compare).
void addTechniqueOptions(CLI::App& cmd, RenderOptions& options, std::vector<std::string>& sets);
// --samples and --embree-config (reference, compare).
void addReferenceOptions(CLI::App& cmd, ReferenceOptions& options);
// visibility.pfm / visibility_<i>.pfm, position.pfm and normal.pfm (design.md §1).
void writeViewFiles(StagedOutputDir& out, const RenderResult& gbuffer,
                    const std::vector<std::vector<float>>& visibility);
// Raw text of a file's bytes for StagedOutputDir::write.
std::span<const uint8_t> bytesOf(const std::string& text);

Action addRenderCommand(CLI::App& app, const GlobalOptions& global);
Action addReferenceCommand(CLI::App& app, const GlobalOptions& global);
Action addCompareCommand(CLI::App& app, const GlobalOptions& global);
Action addBenchCommand(CLI::App& app, const GlobalOptions& global);
Action addViewCommand(CLI::App& app, const GlobalOptions& global);
Action addInfoCommand(CLI::App& app, const GlobalOptions& global);
Action addTechniquesCommand(CLI::App& app);
Action addTuneCommand(CLI::App& app, const GlobalOptions& global);

} // namespace penumbra::cli
