#include "cli_options.h"

#include "core/image_io.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "report/stats.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

namespace penumbra::cli {

std::vector<std::string> splitList(std::string_view text, std::string_view option) {
    std::vector<std::string> items;
    for (size_t start = 0; start <= text.size();) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string_view item = text.substr(start, comma - start);
        if (item.empty())
            throw InputError(std::string(option),
                             fmt::format("'{}' has an empty item (a list is a,b,...)", text));
        items.emplace_back(item);
        start = comma + 1;
    }
    return items;
}

// "key=v1,v2,...": a registered key and values in its range (checked now, not mid-run).
Sweep parseSweep(const std::string& text) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw InputError("--sweep", "'" + text + "' is not key=value1,value2,...");
    Sweep sweep{.key = text.substr(0, eq), .values = splitList(text.substr(eq + 1), "--sweep")};
    ParameterValues check;
    for (const std::string& value : sweep.values)
        try {
            check.set(sweep.key, value);
        } catch (const InputError& e) { // "--set: <what>": the same problem, under its option
            throw InputError("--sweep", std::string(e.what()).substr(e.subject().size() + 2));
        }
    return sweep;
}

std::vector<Assignment> sweepProduct(std::span<const Sweep> sweeps) {
    std::vector<Assignment> runs{{}};
    for (const Sweep& s : sweeps) {
        std::vector<Assignment> next;
        for (const Assignment& run : runs)
            for (const std::string& value : s.values) {
                next.push_back(run);
                next.back().emplace_back(s.key, value);
            }
        runs = std::move(next);
    }
    return runs;
}

RenderOptions optionsFor(const RenderOptions& base, const TechniqueRow& row,
                         std::span<const std::string> sets) {
    RenderOptions o = base;
    o.technique = row.technique;
    for (const std::string& set : sets)
        o.parameters.assign(set);
    // The row's own settings last: they are what its name says ("pcf[box3]" is a 3x3 box).
    for (const auto& [key, value] : row.sets)
        o.parameters.set(key, value);
    validate(o);
    return o;
}

TechniqueRow rowNamed(const std::string& name, std::string_view option) {
    std::vector<TechniqueRow> rows;
    try { // the lookups' errors name their own options: the problem, under this one
        if (name.find_first_of("[+") == std::string::npos)
            return {.name = name, .technique = findTechnique(name).id, .sets = {}, .layers = {}};
        rows = comparisonRows(name);
    } catch (const InputError& e) {
        throw InputError(std::string(option), std::string(e.what()).substr(e.subject().size() + 2));
    }
    for (TechniqueRow& row : rows)
        if (row.name == name)
            return row;
    throw InputError(std::string(option), fmt::format("'{}' is not one row (a technique, a "
                                                      "variant such as pcf[box3], +LAYER after "
                                                      "either)",
                                                      name));
}

Scene loadSceneReporting(const std::string& spec, const GlobalOptions& global,
                         const SceneOptions& o) {
    SceneEdits edits{.fovDegrees = o.fovDegrees};
    // Parsed before the scene loads: a typing mistake costs no loading time.
    if (!o.sunDirection.empty())
        edits.sunDirection = parseVector3(o.sunDirection, "--sun-dir");
    if (!o.cameraPosition.empty())
        edits.cameraPosition = parseVector3(o.cameraPosition, "--camera-pos");
    if (!o.lookAt.empty())
        edits.lookAt = parseVector3(o.lookAt, "--look-at");
    for (const std::string& text : o.lightPositions)
        edits.lightPositions.push_back(parseNamedVector3(text, "--light-pos"));
    for (const std::string& text : o.lightDirections)
        edits.lightDirections.push_back(parseNamedVector3(text, "--light-dir"));
    std::vector<std::string> warnings;
    Scene scene = loadScene(spec, {.maxFileSize = global.maxFileSize,
                                   .maxTriangles = global.maxTriangles,
                                   .warnings = &warnings});
    for (const std::string& w : warnings)
        std::fprintf(stderr, "penumbra: warning: %s\n", w.c_str());
    applySceneEdits(scene, edits);
    return scene;
}

void addViewOptions(CLI::App& cmd, RenderOptions& o, SceneOptions& scene) {
    cmd.add_option("--width", o.width, "image width in pixels")->capture_default_str();
    cmd.add_option("--height", o.height, "image height in pixels")->capture_default_str();
    CLI::Option* camera = cmd.add_option("--camera", o.camera,
                                         "glTF camera name (default: the first, else automatic)");
    cmd.add_option("--camera-pos", scene.cameraPosition,
                   "X,Y,Z: an ad-hoc camera at this world position (needs --look-at)")
        ->excludes(camera);
    cmd.add_option("--look-at", scene.lookAt, "X,Y,Z: the point the ad-hoc camera looks at")
        ->excludes(camera);
    cmd.add_option("--fov", scene.fovDegrees,
                   "the ad-hoc camera's vertical field of view in degrees (default 45.8)")
        ->excludes(camera);
    cmd.add_option("--sun-dir", scene.sunDirection,
                   "X,Y,Z: the direction a sun's light travels (world space); replaces the "
                   "default light of a scene without lights, else adds a sun");
    cmd.add_option("--light-pos", scene.lightPositions,
                   "NAME=X,Y,Z: move the spot or point light NAME (repeatable)");
    cmd.add_option("--light-dir", scene.lightDirections,
                   "NAME=X,Y,Z: aim the spot or sun NAME (repeatable)");
    cmd.add_option("--light-radius", o.lightRadiusOverride,
                   "spot/point light radius in world units (overrides the scene)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--light-angle", o.lightAngleOverride,
                   "directional light angular diameter in degrees (overrides the scene)")
        ->check(CLI::Range(0.0, 30.0));
}

void addTechniqueOptions(CLI::App& cmd, RenderOptions& o, std::vector<std::string>& sets) {
    cmd.add_option("--shadow-map-size", o.shadowMapSize, "shadow map side in texels")
        ->capture_default_str();
    cmd.add_option("--set", sets, "technique parameter family.name=value (repeatable)");
    cmd.add_option("--frames", o.frames,
                   "timed frames after one warm-up frame (two with virtual.enabled: one asks for "
                   "pages, the next renders them)")
        ->capture_default_str();
}

void addReferenceOptions(CLI::App& cmd, ReferenceOptions& options) {
    cmd.add_option("--samples", options.samples,
                   "ground-truth rays per pixel and light for lights with a size (1..65536)")
        ->capture_default_str();
    cmd.add_option("--embree-config", options.embreeConfig,
                   "Embree device configuration, e.g. threads=2");
}

void addSceneArgument(CLI::App& cmd, std::string& scene) {
    std::string builtins;
    for (std::string_view name : builtinSceneNames())
        builtins += (builtins.empty() ? "" : ", ") + std::string(name);
    cmd.add_option("scene", scene, "builtin:NAME (" + builtins + ") or a glTF file")->required();
}

void writeViewFiles(StagedOutputDir& out, const RenderResult& g,
                    const std::vector<std::vector<float>>& visibility) {
    for (size_t i = 0; i < visibility.size(); ++i)
        out.write(visibilityFileName(i), encodePfm(g.width, g.height, 1, visibility[i]));
    out.write("position.pfm", encodePfm(g.width, g.height, 3, g.position));
    out.write("normal.pfm", encodePfm(g.width, g.height, 3, g.normal));
}

std::span<const uint8_t> bytesOf(const std::string& text) {
    return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

} // namespace penumbra::cli
