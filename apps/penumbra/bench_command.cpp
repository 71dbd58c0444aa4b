// `penumbra bench SCENE -o FILE.json [--techniques a,b] [--sweep key=v1,v2,...] ...`: every
// technique (and every combination of the values swept among the parameters it reads) timed
// per pass over --frames frames after a warm-up frame; FILE.json and bench.html beside it.
#include "commands.h"
#include "core/output_dir.h"
#include "penumbra/error.h"
#include "report/bench_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace penumbra::cli {
namespace {

struct BenchArgs {
    SceneOptions sceneOptions;
    std::string scene, output, techniques;
    std::vector<std::string> sweeps, sets;
    RenderOptions options;
};

std::vector<Technique> parseTechniques(const std::string& list) {
    std::vector<Technique> out;
    if (list.empty()) {
        for (const TechniqueInfo& t : allTechniques())
            out.push_back(t.id);
        return out;
    }
    for (size_t start = 0; start <= list.size();) {
        const size_t comma = std::min(list.find(',', start), list.size());
        out.push_back(findTechnique(list.substr(start, comma - start)).id);
        start = comma + 1;
    }
    return out;
}

// Every combination of the sweeps whose family the technique reads (one run when none does).
std::vector<BenchRun> runsOf(Technique technique, const RenderOptions& base,
                             const std::vector<Sweep>& sweeps) {
    const TechniqueInfo& info = findTechnique(techniqueName(technique));
    std::vector<BenchRun> runs{{.technique = technique, .parameters = base.parameters}};
    for (const Sweep& s : sweeps) {
        const std::string family = s.key.substr(0, s.key.find('.'));
        if (std::find(info.families.begin(), info.families.end(), family) == info.families.end())
            continue;
        std::vector<BenchRun> next;
        for (const BenchRun& r : runs)
            for (const std::string& value : s.values) {
                BenchRun run = r;
                run.parameters.set(s.key, value);
                run.swept.emplace_back(s.key, value);
                next.push_back(std::move(run));
            }
        runs = std::move(next);
    }
    return runs;
}

int runBench(const BenchArgs& args, const GlobalOptions& global) {
    RenderOptions base = args.options;
    for (const std::string& set : args.sets)
        base.parameters.assign(set);
    validate(base);
    std::vector<Sweep> sweeps;
    BenchData data{.scene = args.scene,
                   .width = base.width,
                   .height = base.height,
                   .shadowMapSize = base.shadowMapSize,
                   .frames = base.frames};
    for (const std::string& text : args.sweeps) {
        sweeps.push_back(parseSweep(text));
        data.sweepKeys.push_back(sweeps.back().key);
    }
    std::vector<BenchRun> runs;
    for (Technique t : parseTechniques(args.techniques))
        for (BenchRun& r : runsOf(t, base, sweeps))
            runs.push_back(std::move(r));
    for (const Sweep& s : sweeps)
        if (std::none_of(runs.begin(), runs.end(), [&](const BenchRun& r) {
                return std::any_of(r.swept.begin(), r.swept.end(),
                                   [&](const auto& kv) { return kv.first == s.key; });
            }))
            std::fprintf(stderr, "penumbra: warning: --sweep %s: no technique benched reads it\n",
                         s.key.c_str());
    const std::filesystem::path path(args.output);
    if (path.filename().empty() || path.filename() == "bench.html")
        throw InputError(args.output,
                         "-o needs a JSON file name (bench.html is written beside it)");
    const Scene scene = loadSceneReporting(args.scene, global, args.sceneOptions);
    StagedOutputDir out(path.has_parent_path() ? path.parent_path() : ".");

    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    auto optionsOf = [&](const BenchRun& r) {
        RenderOptions o = base;
        o.technique = r.technique;
        o.parameters = r.parameters;
        return o;
    };
    for (const BenchRun& r : runs) // every run's options checked before the first one starts
        renderer.check(scene, optionsOf(r));
    data.device = renderer.device();
    std::fprintf(stderr,
                 "penumbra: bench %s on %s (%s), %ux%u, shadow map %u, %zu runs of %u "
                 "frames\n",
                 scene.name.c_str(), data.device.name.c_str(), data.device.driverName.c_str(),
                 base.width, base.height, base.shadowMapSize, runs.size(), base.frames);
    SceneRenderer uploaded(renderer, scene);
    for (size_t i = 0; i < runs.size(); ++i) {
        BenchRun& r = runs[i];
        const std::string label = fmt::format(
            "[{}/{}] {}{}", i + 1, runs.size(), techniqueName(r.technique),
            r.swept.empty() ? "" : " " + [&] {
                std::string s;
                for (const auto& [k, v] : r.swept)
                    s += (s.empty() ? "" : " ") + k + "=" + v;
                return s;
            }());
        std::fprintf(stderr, "penumbra: %s\n", label.c_str());
        const RenderOptions o = optionsOf(r);
        const RenderResult result = uploaded.render(o);
        measureRun(r, result);
        estimateMemory(r, o, result);
        std::printf("%-40s total %8.3f ms [%.3f, %.3f]", label.c_str(), r.total.median, r.total.p10,
                    r.total.p90);
        for (const PassStats& p : r.passes)
            std::printf("  %s %.3f", p.pass.c_str(), p.median);
        std::printf("\n");
    }
    data.runs = std::move(runs);
    if (renderer.validationErrors() > 0)
        throw std::runtime_error(fmt::format("vulkan validation: {} error(s), see messages above; "
                                             "no output written",
                                             renderer.validationErrors()));
    out.write(path.filename().string(), bytesOf(benchJson(data).dump(2) + "\n"));
    out.write("bench.html", bytesOf(benchHtml(data)));
    out.commit();
    std::printf("wrote %s and %s\n", args.output.c_str(),
                (out.path() / "bench.html").string().c_str());
    return 0;
}

} // namespace

// "key=v1,v2,...": a registered key and values in its range (checked now, not mid-run).
Sweep parseSweep(const std::string& text) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw InputError("--sweep", "'" + text + "' is not key=value1,value2,...");
    Sweep sweep{.key = text.substr(0, eq)};
    ParameterValues check;
    for (size_t start = eq + 1; start <= text.size();) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string value = text.substr(start, comma - start);
        try {
            check.set(sweep.key, value);
        } catch (const InputError& e) { // "--set: <what>": the same problem, under its option
            throw InputError("--sweep", std::string(e.what()).substr(e.subject().size() + 2));
        }
        sweep.values.push_back(value);
        start = comma + 1;
    }
    return sweep;
}

Action addBenchCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<BenchArgs>();
    args->options.frames = 20;
    CLI::App* cmd = app.add_subcommand(
        "bench", "GPU time per pass of each technique and swept parameter value: FILE.json and "
                 "bench.html beside it");
    cmd->add_option("scene", args->scene, "builtin:NAME or a glTF file")->required();
    cmd->add_option("-o,--output", args->output, "the JSON file (bench.html is written beside it)")
        ->required();
    cmd->add_option("--techniques", args->techniques,
                    "comma-separated technique names (default: every technique)");
    cmd->add_option("--sweep", args->sweeps,
                    "key=v1,v2,...: run each technique that reads the key once per value "
                    "(repeatable: every combination)");
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addTechniqueOptions(*cmd, args->options, args->sets);
    return [args, &global] { return runBench(*args, global); };
}

} // namespace penumbra::cli
