// `penumbra merge DIR -o REPORT_DIR`: every task record of a sweep's output (shards and runs
// alike) summed up into merge.json and report.html (docs/sweep.md), written all-or-nothing.
#include "commands.h"
#include "penumbra/error.h"
#include "sweep/merge.h"
#include "sweep/merge_report.h"

#include <cstdio>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

namespace penumbra::cli {
namespace {

struct MergeArgs {
    std::string input, output;
};

// Tasks of sweep.json that have no record yet (a shard still running or never run).
size_t missingTasks(const std::filesystem::path& dir, const std::vector<sweep::TaskRecord>& got) {
    std::ifstream in(dir / "sweep.json");
    if (!in)
        return 0;
    std::stringstream text;
    text << in.rdbuf();
    const nlohmann::json plan = nlohmann::json::parse(text.str(), nullptr, false);
    if (plan.is_discarded() || !plan.contains("tasks"))
        throw InputError((dir / "sweep.json").string(), "not a sweep's task list");
    std::set<std::string> have;
    for (const sweep::TaskRecord& r : got)
        have.insert(r.id);
    size_t missing = 0;
    for (const nlohmann::json& t : plan["tasks"])
        missing += !have.count(t.value("id", ""));
    return missing;
}

int runMerge(const MergeArgs& args) {
    const std::vector<sweep::TaskRecord> records = sweep::readTaskRecords(args.input);
    const size_t missing = missingTasks(args.input, records);
    const sweep::MergeResult merged = sweep::mergeRecords(records);
    nlohmann::json json = sweep::mergeJson(merged);
    json["missing"] = missing;
    StagedOutputDir out(args.output);
    out.write("merge.json", bytesOf(json.dump(2) + "\n"));
    out.write("report.html", bytesOf(sweep::mergeHtml(merged, args.input)));
    out.commit();
    if (missing > 0)
        std::fprintf(stderr,
                     "penumbra: merge: warning: %zu task(s) of the plan have no result "
                     "yet\n",
                     missing);
    std::printf("merge: %zu task(s), %zu failed, %zu missing\nreport: %s\n", merged.tasks,
                merged.failed.size(), missing, (out.path() / "report.html").c_str());
    return 0;
}

} // namespace

Action addMergeCommand(CLI::App& app, const GlobalOptions&) {
    auto args = std::make_shared<MergeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "merge", "sum up a sweep's results: merge.json and report.html with error against cost, "
                 "Pareto fronts, ranks and confidence intervals");
    cmd->add_option("dir", args->input, "a sweep's output directory (sweep -o DIR)")
        ->type_name("DIR")
        ->required();
    cmd->add_option("-o,--output", args->output, "report directory, created if missing")
        ->type_name("REPORT_DIR")
        ->required();
    return [args] { return runMerge(*args); };
}

} // namespace penumbra::cli
