// `penumbra sweep PLAN -o DIR`: a benchmark plan as resumable tasks (docs/sweep.md). The plan is
// checked in full first; then either the cluster job for it is printed (--emit), or this
// process runs its shard: every task when no shard is named.
#include "commands.h"
#include "penumbra/error.h"
#include "sweep/atomic_file.h"
#include "sweep/emit.h"
#include "sweep/plan.h"
#include "sweep/tasks.h"
#include "sweep_run.h"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>

namespace penumbra::cli {
namespace {

struct SweepArgs {
    std::string plan, output, truthCache, emit;
    std::optional<uint32_t> taskIndex, taskCount;
    sweep::EmitOptions emitOptions;
    bool list = false;
};

// A shard index or count from the option, else from the first of `variables` that is set.
std::optional<uint32_t> fromEnvironment(std::optional<uint32_t> option,
                                        std::initializer_list<const char*> variables) {
    if (option)
        return option;
    for (const char* name : variables)
        if (const char* text = std::getenv(name); text && *text) {
            char* end = nullptr;
            const unsigned long v = std::strtoul(text, &end, 10);
            if (*end || v > UINT32_MAX)
                throw InputError(name, fmt::format("'{}' is not a task index or count", text));
            return uint32_t(v);
        }
    return std::nullopt;
}

// DIR/sweep.json: every task of the plan (what merge counts as missing), the same for every
// shard, so that concurrent shards write the same bytes.
std::string tasksJson(const sweep::Plan& plan, const sweep::SweepTasks& tasks) {
    nlohmann::json j{{"plan", plan.path.filename().string()}, {"tasks", nlohmann::json::array()}};
    for (const sweep::SweepTask& t : tasks.tasks) {
        const sweep::SweepView& v = tasks.views[t.view];
        j["tasks"].push_back({{"id", t.id},
                              {"view", v.id},
                              {"scene", v.scene.label},
                              {"light", v.light.name},
                              {"camera", v.camera},
                              {"setting", t.setting.name()}});
        if (v.time)
            j["tasks"].back()["time"] = *v.time;
    }
    return j.dump(1) + "\n";
}

int runSweep(const SweepArgs& args, const GlobalOptions& global) {
    const sweep::Plan plan = sweep::loadPlan(args.plan);
    const sweep::SweepTasks tasks = sweep::expandTasks(plan);
    const std::optional<uint32_t> count =
        fromEnvironment(args.taskCount, {"SLURM_ARRAY_TASK_COUNT", "PENUMBRA_TASK_COUNT"});
    if (count && *count == 0)
        throw InputError("--task-count", "must be at least 1");
    const std::filesystem::path output = std::filesystem::absolute(args.output);
    if (!args.emit.empty()) {
        sweep::EmitOptions o = args.emitOptions;
        o.shards = count.value_or(
            uint32_t(std::max<size_t>(1, std::min<size_t>(tasks.views.size(), 1000))));
        o.truthCache = args.truthCache;
        if (args.emit == "slurm") {
            o.plan = std::filesystem::absolute(args.plan).string();
            o.output = output.string();
            std::filesystem::create_directories(output); // the array's logs go there
            std::fputs(sweep::slurmScript(o).c_str(), stdout);
        } else {
            // Relative paths are taken inside the volume's mount.
            auto inMount = [&](const std::string& p) {
                return std::filesystem::path(p).is_absolute()
                           ? p
                           : (std::filesystem::path(o.mount) / p).lexically_normal().string();
            };
            o.plan = inMount(args.plan);
            o.output = inMount(args.output);
            std::fputs(sweep::kubernetesManifest(o).c_str(), stdout);
        }
        return 0;
    }
    const std::optional<uint32_t> index =
        fromEnvironment(args.taskIndex, {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"});
    if (index && !count)
        throw InputError("--task-count",
                         "a task index needs a task count (--task-count, SLURM_ARRAY_TASK_COUNT "
                         "or PENUMBRA_TASK_COUNT)");
    if (index && *index >= *count)
        throw InputError("--task-index",
                         fmt::format("{} is not below the task count {}", *index, *count));
    std::vector<size_t> mine;
    if (index) {
        mine = sweep::shardTasks(tasks, *index, *count);
    } else {
        for (size_t t = 0; t < tasks.tasks.size(); ++t)
            mine.push_back(t);
    }
    if (args.list) {
        for (size_t t : mine) {
            const sweep::SweepTask& task = tasks.tasks[t];
            const sweep::SweepView& v = tasks.views[task.view];
            std::printf("%s %s %s %s %s%s\n", task.id.c_str(), v.scene.label.c_str(),
                        v.light.name.c_str(), v.camera.empty() ? "(default)" : v.camera.c_str(),
                        task.setting.name().c_str(),
                        v.time ? fmt::format(" t={}s", *v.time).c_str() : "");
        }
        return 0;
    }
    std::error_code ec;
    std::filesystem::create_directories(output / "tasks", ec);
    if (ec)
        throw InputError(output.string(), "cannot create the output directory");
    sweep::writeFileAtomically(output / "sweep.json",
                               [&](std::ostream& out) { out << tasksJson(plan, tasks); });
    const std::filesystem::path truth =
        args.truthCache.empty() ? output / "truth" : std::filesystem::path(args.truthCache);
    const SweepRunStats stats = runSweepTasks(plan, tasks, mine, output, truth, global);
    std::printf("sweep: %zu task(s) run, %zu skipped (done before), %zu failed; truths: %zu "
                "traced, %zu from the cache\n",
                stats.ran, stats.skipped, stats.failed, stats.truthsComputed, stats.truthsCached);
    return stats.failed > 0 ? 1 : 0;
}

} // namespace

Action addSweepCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<SweepArgs>();
    CLI::App* cmd = app.add_subcommand(
        "sweep", "run a benchmark plan (scenes x lights x cameras x technique settings) as "
                 "resumable tasks, or print the Slurm or Kubernetes job that runs it in shards");
    cmd->add_option("plan", args->plan, "the plan, TOML (docs/sweep.md)")
        ->type_name("PLAN")
        ->required();
    cmd->add_option("-o,--output", args->output,
                    "output directory: tasks/<id>.json per task, sweep.json, truth/")
        ->type_name("DIR")
        ->required();
    cmd->add_option("--truth-cache", args->truthCache,
                    "the truth cache directory, shared by runs and machines (default: DIR/truth)")
        ->type_name("DIR");
    cmd->add_option("--task-index", args->taskIndex,
                    "run only this shard, 0 .. count-1 (default: SLURM_ARRAY_TASK_ID, else "
                    "JOB_COMPLETION_INDEX, else every task)")
        ->type_name("I");
    cmd->add_option("--task-count", args->taskCount,
                    "the number of shards (default: SLURM_ARRAY_TASK_COUNT, else "
                    "PENUMBRA_TASK_COUNT; with --emit: one shard per view)")
        ->type_name("N");
    cmd->add_flag("--list", args->list,
                  "print this shard's tasks (id, scene, light, camera, setting, and "
                  "t=SECONDSs for a view at a time) and exit");
    cmd->add_option("--emit", args->emit,
                    "print the cluster job for the plan instead of running it: an sbatch "
                    "job-array script or a Kubernetes Indexed Job manifest")
        ->type_name("slurm|kubernetes")
        ->check(CLI::IsMember({"slurm", "kubernetes"}));
    sweep::EmitOptions& e = args->emitOptions;
    cmd->add_option("--gpus", e.gpus, "--emit: GPUs per task (0: none requested)")
        ->type_name("N")
        ->capture_default_str();
    cmd->add_option("--penumbra", e.penumbra, "--emit: the penumbra command on the nodes")
        ->type_name("CMD")
        ->capture_default_str();
    cmd->add_option("--job-name", e.jobName, "--emit: the job's name")
        ->type_name("NAME")
        ->capture_default_str();
    cmd->add_option("--image", e.image, "--emit kubernetes: the container image")
        ->type_name("IMAGE")
        ->capture_default_str();
    cmd->add_option("--volume-claim", e.volumeClaim,
                    "--emit kubernetes: the PersistentVolumeClaim holding the plan, its scenes "
                    "and DIR")
        ->type_name("NAME")
        ->capture_default_str();
    cmd->add_option("--mount", e.mount,
                    "--emit kubernetes: where the volume is mounted; relative PLAN and DIR lie "
                    "under it")
        ->type_name("PATH")
        ->capture_default_str();
    return [args, &global] { return runSweep(*args, global); };
}

} // namespace penumbra::cli
