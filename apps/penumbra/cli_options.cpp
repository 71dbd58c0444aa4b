#include "cli_options.h"

#include "core/exr_io.h"
#include "core/image_io.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "report/stats.h"
#include "scene/first_picture.h"
#include "scene/mesh_closure.h"
#include "shadows/sdf_field.h"
#include "shadows/technique.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

namespace penumbra::cli {
namespace {

// A number from `lo` to `hi`: CLI11's own ranges let NaN through (no comparison fails) and
// print their unbounded end as DBL_MAX's 309 digits.
CLI::Validator finiteBetween(double lo, double hi, const std::string& words) {
    return CLI::Validator(
        [lo, hi, words](std::string& text) -> std::string {
            double v = 0.0;
            if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < lo || v > hi)
                return fmt::format("'{}' is not {}", text, words);
            return {};
        },
        "");
}

// A time in seconds as written in decimal ("1.5", "2e-3"): CLI11 would also read hex ("0x10")
// and take an empty value as none (from_chars refuses both). The range is loadScene's to check,
// with the scene's name.
CLI::Validator decimalSeconds() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            double v = 0.0;
            const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), v,
                                                      std::chars_format::general);
            if (error != std::errc{} || end != text.data() + text.size())
                return fmt::format("'{}' is not a time in seconds (a decimal number)", text);
            return {};
        },
        "");
}

} // namespace

CLI::Validator nonEmptyValue(const std::string& words) {
    return CLI::Validator(
        [words](std::string& text) -> std::string {
            return text.empty() ? fmt::format("'' is not {}", words) : std::string{};
        },
        "");
}

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

void warnOpenGeometry(const Scene& scene, std::span<const Technique> techniques) {
    std::string needing;
    int needed = 0;
    for (const shadows::TechniqueModule* module : shadows::allModules())
        if (module->needsClosedSurfaces &&
            std::find(techniques.begin(), techniques.end(), module->info.id) != techniques.end())
            needing += fmt::format("{}`{}`", needed++ ? " and " : "", module->info.name);
    if (needed == 0)
        return;
    needing += needed == 1 ? " takes" : " take";
    // A few open triangles are a ground quad or a leaf: what the techniques handle as thin
    // shells. Warned: any mis-wound triangle, or open ones past 1% of the scene. Open counts
    // every triangle of a surface that one open edge leaves open, as the `sdf` field takes it
    // (a helmet with a few gaps is a thin shell whole); alpha-tested cards are meant thin.
    const MeshClosure c = meshClosure(scene);
    const uint64_t open = shadows::closedSurfaces(scene).openEdged;
    if (c.misWound == 0 && open * 100 <= c.triangles)
        return;
    std::fprintf(stderr,
                 "penumbra: warning: scene '%s': %llu of %llu triangles lie on surfaces with "
                 "open edges and %llu on mis-wound ones; %s a model's inside from closed, "
                 "consistently wound surfaces and may leak or show acne there\n",
                 scene.name.c_str(), static_cast<unsigned long long>(open),
                 static_cast<unsigned long long>(c.triangles),
                 static_cast<unsigned long long>(c.misWound), needing.c_str());
}

bool lightsOrbit(const SceneOptions& options) {
    return std::any_of(options.addedLights.begin(), options.addedLights.end(),
                       [](const std::string& text) { return parseAddedLight(text).orbitSeconds; });
}

Scene loadSceneReporting(const std::string& spec, const GlobalOptions& global,
                         const SceneOptions& o, const RenderOptions& options, bool quiet) {
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
    for (const std::string& text : o.addedLights)
        edits.addedLights.push_back(parseAddedLight(text));
    if (!o.view.empty())
        edits.view = parseViewChoice(o.view);
    edits.ground = o.ground;
    edits.noGround = o.noGround;
    edits.doubleSided = o.doubleSided;
    std::vector<std::string> warnings;
    Scene scene = loadScene(spec, {.maxFileSize = global.maxFileSize,
                                   .maxTriangles = global.maxTriangles,
                                   .warnings = &warnings,
                                   .time = o.time,
                                   .animation = o.animation,
                                   .lightsMove = lightsOrbit(o)});
    applySceneEdits(scene, edits);
    if (quiet)
        return scene;
    for (const std::string& w : warnings)
        std::fprintf(stderr, "penumbra: warning: %s\n", w.c_str());
    if (scene.automaticGround)
        std::fprintf(stderr, "penumbra: note: %s\n", automaticGroundNote(scene).c_str());
    const auto has = [&](auto kind) {
        return std::any_of(scene.lights.begin(), scene.lights.end(), kind);
    };
    if (options.lightAngleOverride >= 0 &&
        !has([](const Light& l) { return l.type == LightType::Directional; }))
        std::fprintf(stderr,
                     "penumbra: warning: --light-angle: scene '%s' has no directional light; "
                     "the option changes nothing (--add-light sun:dir=X,Y,Z adds one)\n",
                     scene.name.c_str());
    if (options.lightRadiusOverride >= 0 &&
        !has([](const Light& l) { return l.type != LightType::Directional; }))
        std::fprintf(stderr,
                     "penumbra: warning: --light-radius: scene '%s' has no spot or point light; "
                     "the option changes nothing (--add-light point:pos=X,Y,Z adds one)\n",
                     scene.name.c_str());
    return scene;
}

void addViewOptions(CLI::App& cmd, RenderOptions& o, SceneOptions& scene) {
    const auto group = [](CLI::Option* option) { return option->group(kSceneGroup); };
    group(cmd.add_option("--width", o.width,
                         "image width in pixels (1 .. the device's maxImageDimension2D)"))
        ->type_name("W")
        ->capture_default_str();
    group(cmd.add_option("--height", o.height, "image height in pixels (as --width)"))
        ->type_name("H")
        ->capture_default_str();
    CLI::Option* camera = group(
        cmd.add_option("--camera", o.camera,
                       "a named glTF camera (default: the first; a scene without cameras is framed "
                       "automatically)"));
    camera->type_name("NAME");
    group(cmd.add_option("--camera-pos", scene.cameraPosition,
                         "an ad-hoc camera at this world position (named `command line`, world "
                         "up, near and far planes that hold the whole scene; needs --look-at)"))
        ->type_name("X,Y,Z")
        ->excludes(camera);
    group(cmd.add_option("--look-at", scene.lookAt, "the point the ad-hoc camera looks at"))
        ->type_name("X,Y,Z")
        ->excludes(camera);
    group(cmd.add_option("--fov", scene.fovDegrees,
                         "the ad-hoc camera's vertical field of view, 1..170 degrees (default "
                         "45.8)"))
        ->type_name("DEG")
        ->excludes(camera);
    group(cmd.add_option("--view", scene.view,
                         "the automatic camera: `exterior` frames the subject from outside, "
                         "`interior` stands in its most open room, `auto` measures which "
                         "(default: the scene's first camera, else auto)"))
        ->type_name("auto|exterior|interior")
        ->excludes(camera);
    group(cmd.add_option("--time", scene.time,
                         "poses an animated glTF scene this many seconds into its animation "
                         "(nodes, cameras and lights move; before the first keyframe and after "
                         "the last the ends hold; default: the nodes at rest); a decimal number"))
        ->type_name("SECONDS")
        ->check(decimalSeconds());
    group(cmd.add_option("--animation", scene.animation,
                         "the animation --time poses: its name or index, a name matched first "
                         "(default: the first)"))
        ->type_name("NAME|INDEX");
    group(cmd.add_flag("--double-sided", scene.doubleSided,
                       "draws every material's back faces too (a mis-wound or open mesh shows "
                       "holes where single-sided back faces are culled)"));
    CLI::Option* ground = group(
        cmd.add_flag("--ground", scene.ground,
                     "adds a ground quad under the subject, three times its largest extent, to "
                     "catch the shadows of a lone object (without it, added when it "
                     "puts a cast shadow in view)"));
    group(cmd.add_flag("--no-ground", scene.noGround,
                       "never adds the automatic ground (a lone object floats on the sky)"))
        ->excludes(ground);
    group(cmd.add_option("--sun-dir", scene.sunDirection,
                         "a sun whose light travels along X,Y,Z (world space, any length but 0): "
                         "replaces the default light of a scene without lights, else is added "
                         "(named `sun`, or `sun (--sun-dir)` when the scene has a `sun`)"))
        ->type_name("X,Y,Z");
    group(cmd.add_option("--light-pos", scene.lightPositions,
                         "moves the spot or point light NAME (its glTF name; unnamed lights are "
                         "`light<i>`); repeatable"))
        ->type_name("NAME=X,Y,Z");
    group(cmd.add_option("--light-dir", scene.lightDirections,
                         "aims the spot or sun NAME along X,Y,Z; repeatable"))
        ->type_name("NAME=X,Y,Z");
    group(cmd.add_option("--add-light", scene.addedLights,
                         "adds a light: `sun:dir=X,Y,Z[,angle=DEG]`, "
                         "`spot:pos=X,Y,Z,dir=X,Y,Z[,cone=DEG][,radius=R]` or "
                         "`point:pos=X,Y,Z[,radius=R]`, each with optional `intensity=` and "
                         "`name=` (default: as bright at the scene's centre as the default sun; "
                         "named `<kind> (--add-light N)`) and `orbit=SECONDS` (one turn about "
                         "the vertical every SECONDS, placed at --time; spot and point about "
                         "`about=X,Y,Z`, default the scene's centre); it replaces a scene's "
                         "default light; repeatable"))
        ->type_name("LIGHT");
    group(cmd.add_option("--light-radius", o.lightRadiusOverride,
                         "every spot and point light's radius in world units (default: the "
                         "scene's); the size soft techniques and the ground truth use"))
        ->type_name("R")
        ->check(finiteBetween(0.0, std::numeric_limits<float>::max(), "a finite number >= 0"));
    group(cmd.add_option("--light-angle", o.lightAngleOverride,
                         "every directional light's angular diameter, 0..30 degrees (default: "
                         "the scene's)"))
        ->type_name("DEG")
        ->check(finiteBetween(0.0, 30.0, "a number from 0 to 30"));
}

void addTechniqueOptions(CLI::App& cmd, RenderOptions& o, std::vector<std::string>& sets) {
    cmd.add_option("--shadow-map-size", o.shadowMapSize,
                   "shadow-map side in texels (16 .. the device's maxImageDimension2D)")
        ->group(kTechniqueGroup)
        ->type_name("N")
        ->capture_default_str();
    cmd.add_option("--set", sets,
                   "a technique parameter, e.g. pcf.size=7 (the parameters table below); "
                   "repeatable")
        ->group(kTechniqueGroup)
        ->type_name("family.name=value");
    cmd.add_option("--frames", o.frames,
                   "timed frames after one warm-up frame (two with virtual.enabled: one asks for "
                   "pages, the next renders them); GPU times are their median")
        ->group(kTechniqueGroup)
        ->type_name("N")
        ->capture_default_str();
}

void addReferenceOptions(CLI::App& cmd, ReferenceOptions& options) {
    cmd.add_option("--samples", options.samples,
                   "ground-truth rays per pixel and light for lights with a size (1..65536); a "
                   "light of radius or angle 0 gets one exact ray")
        ->group(kTruthGroup)
        ->type_name("N")
        ->capture_default_str();
    cmd.add_option("--embree-config", options.embreeConfig,
                   "Embree device configuration, e.g. `threads=2`")
        ->group(kTruthGroup)
        ->type_name("STR");
}

void addSceneArgument(CLI::App& cmd, std::string& scene) {
    std::string builtins;
    for (std::string_view name : builtinSceneNames())
        builtins += (builtins.empty() ? "`builtin:" : "`, `builtin:") + std::string(name);
    cmd.add_option("scene", scene,
                   "a built-in scene (" + builtins +
                       "`; `builtin:gen/FAMILY?seed=N` for a generated one; docs/scenes.md) or a "
                       "glTF 2.0 file (.gltf, .glb)")
        ->required();
}

void addFormatOption(CLI::App& cmd, FloatFormat& format) {
    const std::map<std::string, FloatFormat> names{
        {"pfm", FloatFormat::Pfm}, {"exr", FloatFormat::Exr}, {"both", FloatFormat::Both}};
    std::string shown = "both"; // the command's own default, as `format` holds it
    for (const auto& [name, f] : names)
        if (f == format)
            shown = name;
    cmd.add_option("--format", format,
                   "the float images (visibility, position, normal; compare's differences and "
                   "occluder distances) as `pfm`, `exr` (OpenEXR: 32-bit float, lossless ZIP, "
                   "what tev, Blender, Nuke and OpenImageIO open) or `both`")
        ->transform(CLI::CheckedTransformer(names))
        ->type_name("FORMAT")
        ->default_str(shown);
}

std::string_view namingExtension(FloatFormat format) {
    return format == FloatFormat::Exr ? "exr" : "pfm";
}

void writeFloatImage(StagedOutputDir& out, const std::string& stem, FloatFormat format,
                     uint32_t width, uint32_t height, uint32_t channels,
                     std::span<const float> pixels) {
    if (format != FloatFormat::Exr)
        out.write(stem + ".pfm", encodePfm(width, height, channels, pixels));
    if (format != FloatFormat::Pfm)
        out.write(stem + ".exr", encodeExr(width, height, channels, pixels));
}

std::vector<bool> shadowLightsSized(const Scene& lit, const RenderResult& gbuffer) {
    std::vector<bool> sized;
    for (const LightShadow& s : gbuffer.lights)
        if (s.visibilityIndex >= 0)
            sized.push_back(lit.lights.at(s.sceneLight).hasSize());
    return sized;
}

void writeViewFiles(StagedOutputDir& out, const RenderResult& g,
                    const std::vector<std::vector<float>>& visibility, FloatFormat format,
                    const std::vector<std::vector<float>>& coloured) {
    for (size_t i = 0; i < visibility.size(); ++i)
        if (i < coloured.size() && !coloured[i].empty())
            writeFloatImage(out, visibilityFileStem(i), format, g.width, g.height, 3, coloured[i]);
        else
            writeFloatImage(out, visibilityFileStem(i), format, g.width, g.height, 1,
                            visibility[i]);
    writeFloatImage(out, "position", format, g.width, g.height, 3, g.position);
    writeFloatImage(out, "normal", format, g.width, g.height, 3, g.normal);
}

std::span<const uint8_t> bytesOf(const std::string& text) {
    return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

namespace {

const char* parameterTypeName(ParameterType type) {
    switch (type) {
    case ParameterType::Float:
        return "float";
    case ParameterType::Int:
        return "int";
    case ParameterType::Bool:
        return "bool";
    case ParameterType::Choice:
        return "choice";
    }
    return "?";
}

nlohmann::json describeParameter(const ParameterInfo& p) {
    nlohmann::json j = {{"key", p.key},
                        {"type", parameterTypeName(p.type)},
                        {"description", p.description},
                        {"unit", p.unit}};
    if (p.type == ParameterType::Choice) {
        j["choices"] = p.choices;
        j["default"] = p.choices[static_cast<size_t>(p.defaultValue)];
    } else if (p.type == ParameterType::Bool) {
        j["default"] = p.defaultValue != 0.0;
    } else if (p.type == ParameterType::Int) { // whole numbers, as they are typed
        j["default"] = static_cast<int64_t>(p.defaultValue);
        j["min"] = static_cast<int64_t>(p.min);
        j["max"] = static_cast<int64_t>(p.max);
    } else {
        j["default"] = p.defaultValue;
        j["min"] = p.min;
        j["max"] = p.max;
    }
    return j;
}

} // namespace

nlohmann::json techniquesJson() {
    nlohmann::json out = nlohmann::json::array();
    for (const TechniqueInfo& t : allTechniques()) {
        nlohmann::json params = nlohmann::json::array();
        for (const ParameterInfo& p : allParameters())
            for (std::string_view family : t.families)
                if (p.key.substr(0, p.key.find('.')) == family)
                    params.push_back(describeParameter(p));
        out.push_back({{"name", t.name},
                       {"summary", t.summary},
                       {"reference", t.reference},
                       {"parameters", params}});
    }
    return out;
}

} // namespace penumbra::cli
