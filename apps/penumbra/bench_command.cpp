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
#include <exception>
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
    for (const std::string& name : splitList(list, "--techniques"))
        out.push_back(findTechnique(name).id);
    return out;
}

// Every combination of the sweeps whose family the technique reads (one run when none does).
std::vector<BenchRun> runsOf(Technique technique, const RenderOptions& base,
                             const std::vector<Sweep>& sweeps) {
    const TechniqueInfo& info = findTechnique(techniqueName(technique));
    std::vector<Sweep> read;
    for (const Sweep& s : sweeps)
        if (std::find(info.families.begin(), info.families.end(),
                      s.key.substr(0, s.key.find('.'))) != info.families.end())
            read.push_back(s);
    std::vector<BenchRun> runs;
    for (Assignment& swept : sweepProduct(read)) {
        BenchRun run{.technique = technique, .parameters = base.parameters};
        for (const auto& [key, value] : swept)
            run.parameters.set(key, value);
        run.swept = std::move(swept);
        runs.push_back(std::move(run));
    }
    return runs;
}

int runBench(const BenchArgs& args, const GlobalOptions& global) {
    const RenderOptions base = optionsFor(args.options, {}, args.sets);
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
    if (path.filename().empty() || path.filename() == "bench.html" || path.extension() != ".json")
        throw InputError(
            args.output.empty() ? "-o" : args.output,
            fmt::format("{}; -o takes FILE.json (bench.html is written beside it)",
                        args.output.empty() ? "an empty file name" : "not a JSON file name"));
    const std::filesystem::path html = path.parent_path() / "bench.html";
    for (const std::filesystem::path& file : {path, html}) // found now, not after the runs
        if (std::filesystem::is_directory(file))
            throw InputError(file.string(), "is a directory; bench writes FILE.json and "
                                            "bench.html beside it");
    const Scene scene = loadSceneReporting(args.scene, global, args.sceneOptions, args.options);
    StagedOutputDir out(path.has_parent_path() ? path.parent_path() : ".");

    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    auto optionsOf = [&](const BenchRun& r) {
        RenderOptions o = base;
        o.technique = r.technique;
        o.parameters = r.parameters;
        return o;
    };
    // Every run's options checked before the first one starts; a run the device cannot hold is
    // skipped and marked (only when none fits is it an error).
    auto describe = [](const BenchRun& r) {
        std::string text(techniqueName(r.technique));
        for (const auto& [k, v] : r.swept)
            text += " " + k + "=" + v;
        return text;
    };
    std::exception_ptr firstRefusal;
    size_t skipped = 0;
    for (BenchRun& r : runs)
        try {
            renderer.check(scene, optionsOf(r));
        } catch (const InputError& e) {
            if (!firstRefusal)
                firstRefusal = std::current_exception();
            r.skipped = e.what();
            ++skipped;
        }
    if (skipped == runs.size())
        std::rethrow_exception(firstRefusal); // the error it always was, without warnings
    for (const BenchRun& r : runs)
        if (!r.skipped.empty())
            std::fprintf(stderr, "penumbra: warning: %s skipped: %s\n", describe(r).c_str(),
                         r.skipped.c_str());
    data.device = renderer.device();
    std::fprintf(stderr,
                 "penumbra: bench %s on %s (%s), %ux%u, shadow map %u, %zu runs of %u "
                 "frames\n",
                 scene.name.c_str(), data.device.name.c_str(), data.device.driverName.c_str(),
                 base.width, base.height, base.shadowMapSize, runs.size(), base.frames);
    std::vector<Technique> techniques;
    for (const BenchRun& r : runs)
        techniques.push_back(r.technique);
    warnOpenGeometry(scene, techniques); // after every check
    SceneRenderer uploaded(renderer, scene);
    for (size_t i = 0; i < runs.size(); ++i) {
        BenchRun& r = runs[i];
        const std::string label = fmt::format("[{}/{}] {}", i + 1, runs.size(), describe(r));
        if (!r.skipped.empty()) {
            std::printf("%-40s skipped: %s\n", label.c_str(), r.skipped.c_str());
            continue;
        }
        std::fprintf(stderr, "penumbra: %s\n", label.c_str());
        const RenderOptions o = optionsOf(r);
        // Quiet but for its warnings (a virtual pool too small for the view).
        const RenderResult result = uploaded.render(o, [&](const std::string& said) {
            if (said.starts_with("warning: "))
                std::fprintf(stderr, "penumbra: %s: %s\n", label.c_str(), said.c_str());
        });
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

Action addBenchCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<BenchArgs>();
    args->options.frames = 20;
    CLI::App* cmd = app.add_subcommand(
        "bench", "GPU time per pass of each technique and swept parameter value: FILE.json and "
                 "bench.html beside it");
    addSceneArgument(*cmd, args->scene);
    cmd->add_option("-o,--output", args->output,
                    "the JSON; `bench.html` is written beside it (both all-or-nothing)")
        ->type_name("FILE.json")
        ->required();
    cmd->add_option("--techniques", args->techniques, "technique names (default: every technique)")
        ->type_name("a,b,...");
    cmd->add_option("--sweep", args->sweeps,
                    "run each technique that reads the key once per value, each checked "
                    "against its range first; repeatable (every combination)")
        ->type_name("key=v1,v2,...");
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addTechniqueOptions(*cmd, args->options, args->sets);
    return [args, &global] { return runBench(*args, global); };
}

} // namespace penumbra::cli
