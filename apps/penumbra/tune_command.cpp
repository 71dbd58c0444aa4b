// `penumbra tune SCENE --technique T -o DIR [--sweep key=v1,v2,...] [--set ...]`: the bias
// settings (and mode) swept against the ray-traced truth, traced once per view; DIR/tune.json,
// DIR/tune.html (the acne-against-leak front) and the recommended `--set` line on stdout.
#include "commands.h"
#include "core/output_dir.h"
#include "penumbra/error.h"
#include "report/blur_band.h"
#include "report/light_mask.h"
#include "report/truth_notes.h"
#include "report/tune_report.h"
#include "shadows/technique.h"
#include "truth_cache_option.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <set>

namespace penumbra::cli {
namespace {

struct TuneArgs {
    SceneOptions sceneOptions;
    std::string scene, output, technique, modes = "fixed,adaptive";
    std::vector<std::string> sweeps, sets;
    RenderOptions options;
    ReferenceOptions reference{.progress = true};
    std::string truthCache; // empty: no cache
};

// The sweep of each bias mode when no --sweep is given: the mode's own terms and the normal
// offset, which both modes read, around their defaults (docs/techniques.md, "Adaptive depth
// bias").
std::vector<Sweep> modeGrid(const std::string& mode) {
    if (mode == "fixed")
        return {{"bias.mode", {"fixed"}},
                {"bias.constant", {"0", "0.0002", "0.0005", "0.001", "0.002"}},
                {"bias.slope", {"0", "1", "2", "4"}},
                {"bias.normal", {"0", "0.3", "1"}}};
    return {{"bias.mode", {"adaptive"}},
            {"bias.adaptive", {"0.1", "0.25", "0.5", "1"}},
            {"bias.curvature", {"0", "1", "2"}},
            {"bias.normal", {"0", "0.3", "1"}}};
}

// "fixed: `bias.constant` 0, 0.0002 x ... (60); adaptive: ..." for --modes' help, from the grids.
std::string describeModeGrids() {
    std::string text;
    for (const char* mode : {"fixed", "adaptive"}) {
        std::string axes;
        size_t settings = 1;
        for (const Sweep& sweep : modeGrid(mode)) {
            if (sweep.key == "bias.mode")
                continue;
            std::string values;
            for (const std::string& v : sweep.values)
                values += (values.empty() ? "" : ", ") + v;
            axes += (axes.empty() ? "`" : " x `") + sweep.key + "` " + values;
            settings *= sweep.values.size();
        }
        text += fmt::format("{}{}: {} ({})", text.empty() ? "" : "; ", mode, axes, settings);
    }
    return text;
}

// Every combination of the sweeps' values over `base`.
void addProduct(std::vector<TuneCandidate>& out, std::vector<ParameterValues>& values,
                const ParameterValues& base, const std::vector<Sweep>& sweeps) {
    for (Assignment& sets : sweepProduct(sweeps)) {
        TuneCandidate candidate{.sets = std::move(sets)};
        ParameterValues params = base;
        for (const auto& [key, value] : candidate.sets)
            params.set(key, value);
        for (const auto& [key, value] : candidate.sets)
            if (params.number(key) != base.number(key))
                candidate.setLine +=
                    (candidate.setLine.empty() ? "" : " ") + fmt::format("--set {}={}", key, value);
        if (candidate.setLine.empty())
            continue; // the defaults, already the first candidate
        out.push_back(std::move(candidate));
        values.push_back(std::move(params));
    }
}

// The views tuned over: each of the scene's cameras when it has several (named, distinct) and
// no view was chosen, else the one view the options give.
std::vector<std::string> viewsOf(const Scene& scene, const TuneArgs& args) {
    std::set<std::string> names;
    for (const Camera& c : scene.cameras)
        names.insert(c.name);
    const bool chosen = !args.options.camera.empty() || !args.sceneOptions.cameraPosition.empty();
    if (chosen || scene.cameras.size() < 2 || names.size() != scene.cameras.size() ||
        names.count(""))
        return {args.options.camera};
    std::vector<std::string> views;
    for (const Camera& c : scene.cameras)
        views.push_back(c.name);
    return views;
}

struct ViewTruth {
    RenderOptions options; // the view's camera
    ReferenceResult truth;
    std::vector<std::vector<uint8_t>> masks;
};

int runTune(const TuneArgs& args, const GlobalOptions& global) {
    const TechniqueRow row = rowNamed(args.technique, "--technique");
    RenderOptions base = optionsFor(args.options, row, args.sets);
    validate(args.reference);

    std::vector<TuneCandidate> candidates{TuneCandidate{.isDefault = true}};
    std::vector<ParameterValues> values{base.parameters};
    if (!args.sweeps.empty()) {
        std::vector<Sweep> sweeps;
        for (const std::string& text : args.sweeps)
            sweeps.push_back(parseSweep(text));
        addProduct(candidates, values, base.parameters, sweeps);
    } else {
        for (const std::string& mode : splitList(args.modes, "--modes")) {
            if (mode != "fixed" && mode != "adaptive")
                throw InputError("--modes", fmt::format("'{}' is not fixed or adaptive", mode));
            addProduct(candidates, values, base.parameters, modeGrid(mode));
        }
    }
    // Each candidate's swept keys as the defaults have them: the table's first row.
    for (const TuneCandidate& c : candidates)
        for (const auto& set : c.sets) {
            const std::string& key = set.first; // a lambda may not capture a structured binding
            if (std::none_of(candidates[0].sets.begin(), candidates[0].sets.end(),
                             [&](const auto& kv) { return kv.first == key; }))
                candidates[0].sets.emplace_back(key, base.parameters.text(key));
        }

    Scene scene = loadSceneReporting(args.scene, global, args.sceneOptions, args.options);
    // The row's layers, sized to the scene as compare sizes them (a row runs exactly those).
    applyRow(row, base.parameters, scene.bounds().radius());
    for (ParameterValues& v : values)
        applyRow(row, v, scene.bounds().radius());
    StagedOutputDir out(args.output);
    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    auto optionsOf = [&](size_t i) {
        RenderOptions o = base;
        o.parameters = values[i];
        return o;
    };
    for (size_t i = 0; i < candidates.size(); ++i) // every candidate checked before the first
        renderer.check(scene, optionsOf(i));
    Scene lit = scene; // the light sizes the truth must use
    applyLightSizeOverrides(lit, base.lightRadiusOverride, base.lightAngleOverride);
    const std::vector<std::string> cameras = viewsOf(scene, args);
    const shadows::TechniqueModule& module = shadows::moduleOf(base.technique);
    TuneData data{.scene = args.scene,
                  .technique = row.name,
                  .device = renderer.device().name,
                  .views = cameras,
                  .baseSets = args.sets,
                  .width = base.width,
                  .height = base.height,
                  .shadowMapSize = base.shadowMapSize,
                  .samples = args.reference.samples};
    std::fprintf(stderr, "penumbra: tune %s on %s: %zu settings, %zu view(s), %ux%u on %s\n",
                 row.name.c_str(), args.scene.c_str(), candidates.size(), cameras.size(),
                 base.width, base.height, data.device.c_str());

    warnOpenGeometry(scene, std::span(&row.technique, 1)); // after every check
    SceneRenderer uploaded(renderer, scene);
    std::vector<ViewTruth> views;
    for (const std::string& camera : cameras) {
        ViewTruth v{.options = base};
        v.options.camera = camera;
        const RenderResult gbuffer = uploaded.render(v.options);
        data.lightSized = shadowLightsSized(lit, gbuffer); // the same lights in every view
        std::fprintf(stderr, "penumbra: ground truth for view %s, %s\n",
                     camera.empty() ? "(default)" : camera.c_str(),
                     truthRaysText(args.reference.samples, data.lightSized).c_str());
        v.truth = truthThroughCache(args.truthCache, lit, camera, gbuffer, args.reference);
        data.truthSeconds += v.truth.seconds;
        for (const LightShadow& s : gbuffer.lights)
            if (s.visibilityIndex >= 0)
                v.masks.push_back(lightMask(lit.lights[s.sceneLight], gbuffer));
        views.push_back(std::move(v));
    }

    for (size_t i = 0; i < candidates.size(); ++i) {
        TuneCandidate& c = candidates[i];
        std::fprintf(stderr, "penumbra: [%zu/%zu] %s\n", i + 1, candidates.size(),
                     c.isDefault ? "(defaults)" : c.setLine.c_str());
        const BlurReach blur = shadows::blurRadii(module, values[i]);
        std::vector<RenderResult> results;
        std::vector<TruthView> pooled;
        for (const ViewTruth& v : views) {
            RenderOptions o = optionsOf(i);
            o.camera = v.options.camera;
            results.push_back(uploaded.render(o));
        }
        for (size_t k = 0; k < views.size(); ++k)
            pooled.push_back({.result = &results[k],
                              .truth = views[k].truth.visibility,
                              .masks = views[k].masks});
        c.metrics = metricsAgainstTruth(lit, pooled, blur);
        for (const PassTime& p : results.front().passes)
            c.gpuMs += p.medianMs;
    }
    markFront(candidates);
    data.candidates = std::move(candidates);
    data.recommended = recommend(data.candidates);
    if (renderer.validationErrors() > 0)
        throw std::runtime_error(fmt::format("vulkan validation: {} error(s); no output written",
                                             renderer.validationErrors()));
    out.write("tune.json", bytesOf(tuneJson(data).dump(2) + "\n"));
    out.write("tune.html", bytesOf(tuneHtml(data)));
    out.commit();

    const TuneCandidate& best = data.candidates[data.recommended];
    const TuneCandidate& defaults = data.candidates[data.defaults];
    std::printf("%-60s %9s %9s %9s\n", "settings", "acne>b%", "leak>b%", "RMSE");
    for (const TuneCandidate* c : {&defaults, &best})
        std::printf("%-60s %9.3f %9.3f %9.5f\n", c->isDefault ? "(defaults)" : c->setLine.c_str(),
                    100 * c->metrics.acneBeyondBlur, 100 * c->metrics.leakBeyondBlur,
                    c->metrics.rmse);
    std::printf("recommended: %s\n",
                best.setLine.empty() ? "the defaults (no --set)" : best.setLine.c_str());
    std::printf("report: %s\n", (out.path() / "tune.html").c_str());
    return 0;
}

} // namespace

Action addTuneCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<TuneArgs>();
    args->options.frames = 1;
    args->options.width = 480;
    args->options.height = 270;
    args->reference.samples = 64;
    CLI::App* cmd = app.add_subcommand(
        "tune", "sweep the bias settings against the ground truth; write tune.json and tune.html "
                "and print the recommended --set line");
    addSceneArgument(*cmd, args->scene);
    cmd->add_option("--technique", args->technique,
                    "the technique or compare variant to tune, e.g. `hard`, `pcf[box7]`")
        ->type_name("NAME")
        ->required();
    cmd->add_option("-o,--output", args->output, "output directory, created if missing")
        ->type_name("DIR")
        ->required();
    cmd->add_option("--sweep", args->sweeps,
                    "sweep these (every combination, over `--set`) instead of the default grid; "
                    "repeatable")
        ->type_name("key=v1,v2,...");
    cmd->add_option("--modes", args->modes,
                    "without `--sweep`: the bias modes whose default grid is swept. " +
                        describeModeGrids())
        ->type_name("fixed,adaptive")
        ->default_str("fixed,adaptive");
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addTechniqueOptions(*cmd, args->options, args->sets);
    addReferenceOptions(*cmd, args->reference);
    addTruthCacheOption(*cmd, args->truthCache);
    return [args, &global] { return runTune(*args, global); };
}

} // namespace penumbra::cli
