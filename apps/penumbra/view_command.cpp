// `penumbra view SCENE [render's options] [--frames N --screenshot FILE] [--hide-ui]`: the
// interactive viewer (apps/viewer).
#include "commands.h"
#include "compare_timeline.h"
#include "penumbra/error.h"
#include "shadows/technique.h"
#include "viewer.h"

#include <fmt/format.h>
#include <memory>

namespace penumbra::cli {
namespace {

struct ViewArgs {
    SceneOptions sceneOptions;
    std::string scene, technique = std::string(techniqueName(kDefaultTechnique));
    std::vector<std::string> sets;
    bool noVsync = false, play = false;
    std::string show = "scene", compareWith;
    viewer::ViewerOptions options;
};

// --show MODE[:N]: scene, visibility[:LIGHT], shadow-map[:LAYER], cascades, error[:LIGHT],
// blocker-depth[:LIGHT], penumbra[:LIGHT], contact[:LIGHT], pages[:LEVEL], pool.
void parseShow(const std::string& text, viewer::ViewerOptions& options) {
    const size_t colon = text.find(':');
    const std::string mode = text.substr(0, colon);
    using viewer::DisplayMode;
    const std::pair<const char*, DisplayMode> modes[] = {
        {"scene", DisplayMode::Scene},          {"visibility", DisplayMode::Visibility},
        {"shadow-map", DisplayMode::ShadowMap}, {"cascades", DisplayMode::Cascades},
        {"error", DisplayMode::Error},          {"blocker-depth", DisplayMode::BlockerDepth},
        {"penumbra", DisplayMode::Penumbra},    {"contact", DisplayMode::Contact},
        {"pages", DisplayMode::Pages},          {"pool", DisplayMode::Pool}};
    bool found = false;
    for (const auto& [name, value] : modes)
        if (mode == name)
            options.show = value, found = true;
    if (!found)
        throw InputError("--show", "'" + text +
                                       "' is not one of scene, visibility[:LIGHT], "
                                       "shadow-map[:LAYER], cascades, error[:LIGHT], "
                                       "blocker-depth[:LIGHT], penumbra[:LIGHT], "
                                       "contact[:LIGHT], pages[:LEVEL], pool");
    if (options.show == DisplayMode::Pages)
        options.showIndex = -1; // without a level: the finest with pages
    if (colon != std::string::npos) {
        const std::string index = text.substr(colon + 1);
        if (index.empty() || index.size() > 4 ||
            index.find_first_not_of("0123456789") != std::string::npos)
            throw InputError("--show", "'" + index + "' is not a light or layer number");
        options.showIndex = std::stoi(index);
    }
}

int runView(const ViewArgs& args, const GlobalOptions& global) {
    viewer::ViewerOptions options = args.options;
    options.render.frames = 1;
    options.render =
        optionsFor(options.render, {.technique = findTechnique(args.technique).id}, args.sets);
    validate(ReferenceOptions{.samples = options.truthSamples});
    if (!options.screenshot.empty() && options.frames == 0)
        throw InputError("--screenshot", "needs --frames N (the frames drawn before it)");
    parseShow(args.show, options);
    if (!args.compareWith.empty())
        options.compareWith = findTechnique(args.compareWith).id;
    options.vsync = !args.noVsync && options.frames == 0; // scripted runs do not wait for vsync
    options.device = global.device;
    options.validation = global.validation;
    Scene scene = loadSceneReporting(args.scene, global, args.sceneOptions, options.render);
    if (!scene.animation.empty() || lightsOrbit(args.sceneOptions)) {
        // Each pose loaded quietly (this load said the warnings), framed as this one is: its
        // automatic camera, default light and ground hold, as on a compare --timeline.
        SceneOptions posed = args.sceneOptions;
        posed.ground = posed.ground || scene.automaticGround;
        posed.noGround = !posed.ground;
        options.poseAt = [posed, spec = args.scene, &global, render = options.render,
                          first = scene](double time) {
            SceneOptions at = posed;
            at.time = time;
            Scene s = loadSceneReporting(spec, global, at, render, /*quiet=*/true);
            pinToFirstFrame(s, first);
            return s;
        };
        options.time = args.sceneOptions.time.value_or(0.0);
        options.duration = scene.animationDuration;
        options.play = args.play;
        if (!args.sceneOptions.time) // at rest is no time of the animation: start at 0
            scene = options.poseAt(0.0);
    } else if (args.play) {
        throw InputError("--play",
                         fmt::format("'{}' has no animation and no light that orbits", args.scene));
    }
    viewer::runViewer(scene, options);
    return 0;
}

} // namespace

Action addViewCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<ViewArgs>();
    CLI::App* cmd = app.add_subcommand(
        "view", "the interactive viewer: SCENE in a window, every technique and parameter live, "
                "the error against the ground truth (mouse: left drag orbits, right drag looks, "
                "wheel zooms; WASD QE fly; Tab hides the interface; Esc quits)");
    addSceneArgument(*cmd, args->scene);
    cmd->add_option("--technique", args->technique,
                    "the technique at start (`penumbra techniques` lists them)")
        ->type_name("T")
        ->capture_default_str();
    addViewOptions(*cmd, args->options.render, args->sceneOptions);
    cmd->add_option("--shadow-map-size", args->options.render.shadowMapSize,
                    "shadow-map side in texels at start")
        ->type_name("N")
        ->capture_default_str();
    cmd->add_option("--set", args->sets, "a technique parameter at start; repeatable")
        ->type_name("family.name=value");
    cmd->add_option("--frames", args->options.frames,
                    "draw N frames, then exit (0: until the window is closed)")
        ->type_name("N")
        ->capture_default_str();
    cmd->add_option("--screenshot", args->options.screenshot,
                    "with `--frames N`: write the last presented image (the interface included "
                    "unless hidden) to FILE as PNG")
        ->type_name("FILE");
    // The techniques with a blocker search, from the registry.
    const std::string searching = shadows::techniquesWhere(
        [](const shadows::TechniqueModule& m) { return !m.blockerSearchKey.empty(); });
    cmd->add_option("--show", args->show,
                    fmt::format("what the window shows at start: `scene`; `visibility[:LIGHT]` "
                                "(a light's visibility as grey); `shadow-map[:LAYER]` (a layer of "
                                "the depth map: a view, a cascade or a cube face); `cascades` (the "
                                "lit image tinted by cascade: red, green, blue, yellow from near "
                                "to far); `error[:LIGHT]` (the signed-error heat map against the "
                                "ground truth, traced first; with `--frames` the frames wait for "
                                "it and the metrics are printed); `blocker-depth[:LIGHT]` and "
                                "`penumbra[:LIGHT]` ({}: the average blocker's depth, the filter "
                                "radius); `contact[:LIGHT]` (the contact layer's own result); "
                                "`pages[:LEVEL]` and `pool` (virtual maps: a level's page table, "
                                "the physical pool; docs/techniques.md has the legend)",
                                searching))
        ->type_name("MODE")
        ->capture_default_str();
    cmd->add_option("--compare-with", args->compareWith,
                    "A/B: technique T right of the split (a yellow line), `--technique` left of "
                    "it, on the same frame")
        ->type_name("T");
    cmd->add_option("--samples", args->options.truthSamples,
                    "ground-truth rays per pixel and light for the error view (1..65536)")
        ->type_name("N")
        ->capture_default_str();
    cmd->add_flag("--play", args->play,
                  "an animated scene (or one whose added lights orbit) plays from `--time` at "
                  "start, looping at the animation's end (Space plays and pauses; the time "
                  "slider scrubs); with `--frames` each frame moves it on 1/60 s");
    cmd->add_flag("--hide-ui", args->options.hideUi,
                  "draw the scene without the interface (Tab toggles it)");
    cmd->add_flag("--no-vsync", args->noVsync,
                  "present as fast as frames are drawn (scripted runs, with `--frames`, never "
                  "wait for vsync)");
    return [args, &global] { return runView(*args, global); };
}

} // namespace penumbra::cli
