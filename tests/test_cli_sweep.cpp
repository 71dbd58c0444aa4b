// `penumbra sweep` and `penumbra merge` end to end on lavapipe at a tiny size: a run traces each
// view's truth once, a second run skips what is done, a killed run loses only its tasks in
// flight, shards merge to exactly the figures of one run, bad plans are refused before any
// output, a scene that does not load fails its tasks only, and compare and tune read the truth
// a sweep cached.
#include "process.h"
#include "scratch_dir.h"
#include "sliding_box.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <thread>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

const std::string kHead = "width = 64\nheight = 48\nsamples = 8\nshadow_map_size = 256\n"
                          "frames = 1\n";
const std::string kBody = "[[lights]]\nname = \"sun\"\nkind = \"sun\"\n"
                          "direction = [0.35, -1, 0.45]\nsizes = [1]\n"
                          "[[techniques]]\nname = \"hard\"\n"
                          "[[techniques]]\nname = \"pcf\"\npcf.size = [3]\n";

fs::path writePlan(const std::string& name, const std::string& text) {
    const fs::path p = scratchDir("sweep-cli") / name;
    std::ofstream(p) << text;
    return p;
}

fs::path twoScenePlan() {
    return writePlan("two.toml",
                     kHead + "scenes = [\"builtin:showcase\", \"builtin:resting\"]\n" + kBody);
}

size_t records(const fs::path& dir) {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir / "tasks"))
        n += e.path().extension() == ".json" && e.path().filename().string()[0] != '.';
    return n;
}

// merge.json's error figures (everything but the costs, which are timings).
nlohmann::json errorFigures(const fs::path& report) {
    nlohmann::json j = nlohmann::json::parse(slurp(report / "merge.json"));
    for (nlohmann::json& g : j["groups"])
        for (nlohmann::json& s : g["settings"])
            s.erase("cost");
    return j;
}

std::string summaryLine(const ProcessResult& r) {
    std::smatch m;
    return std::regex_search(r.out, m, std::regex("sweep: [^\n]*")) ? m.str() : "";
}

} // namespace

TEST(SweepCli, TracesEachViewOnceResumesAndShardsMergeToTheSameFigures) {
    const fs::path plan = twoScenePlan();
    const fs::path one = outputScratch("sweep-one"), sharded = outputScratch("sweep-sharded");
    ProcessResult r = runCli({"sweep", plan.string(), "-o", one.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(summaryLine(r), "sweep: 4 task(s) run, 0 skipped (done before), 0 failed; truths: "
                              "2 traced, 0 from the cache");
    EXPECT_NE(r.err.find("ETA"), std::string::npos) << r.err;
    EXPECT_EQ(records(one), 4u);
    size_t truths = 0;
    for (const auto& e : fs::directory_iterator(one / "truth"))
        truths += e.path().extension() == ".truth";
    EXPECT_EQ(truths, 2u);

    r = runCli({"sweep", plan.string(), "-o", one.string()});
    EXPECT_EQ(summaryLine(r), "sweep: 0 task(s) run, 4 skipped (done before), 0 failed; truths: "
                              "0 traced, 0 from the cache");
    // A lost record (and a temporary file a killed run left) is redone from the cached truth.
    fs::path lost;
    for (const auto& e : fs::directory_iterator(one / "tasks"))
        lost = e.path();
    const std::string before = slurp(lost);
    fs::remove(lost);
    std::ofstream(one / "tasks" / ".half-written.json.1-2.tmp") << "{";
    r = runCli({"sweep", plan.string(), "-o", one.string()});
    EXPECT_EQ(summaryLine(r), "sweep: 1 task(s) run, 3 skipped (done before), 0 failed; truths: "
                              "0 traced, 1 from the cache");
    nlohmann::json again = nlohmann::json::parse(slurp(lost)),
                   first = nlohmann::json::parse(before);
    EXPECT_EQ(again["metrics"], first["metrics"]);
    EXPECT_EQ(again["replicates"], first["replicates"]);

    // Three shards: two by option, one by Slurm's variables.
    for (int i = 0; i < 2; ++i)
        ASSERT_EQ(runCli({"sweep", plan.string(), "-o", sharded.string(), "--task-index",
                          std::to_string(i), "--task-count", "3"})
                      .exitCode,
                  0);
    ::setenv("SLURM_ARRAY_TASK_ID", "2", 1);
    ::setenv("SLURM_ARRAY_TASK_COUNT", "3", 1);
    r = runCli({"sweep", plan.string(), "-o", sharded.string()});
    ::unsetenv("SLURM_ARRAY_TASK_ID");
    ::unsetenv("SLURM_ARRAY_TASK_COUNT");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(summaryLine(r).find(", 0 skipped"), std::string::npos)
        << "the third shard ran only its own tasks: " << r.out;
    EXPECT_EQ(records(sharded), 4u);

    const fs::path reportOne = outputScratch("merge-one"), reportShards = outputScratch("merge-3");
    r = runCli({"merge", one.string(), "-o", reportOne.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(runCli({"merge", sharded.string(), "-o", reportShards.string()}).exitCode, 0);
    const nlohmann::json figures = errorFigures(reportOne);
    EXPECT_EQ(figures, errorFigures(reportShards));
    EXPECT_EQ(figures["tasks"], 4);
    EXPECT_EQ(figures["missing"], 0);
    ASSERT_EQ(figures["groups"].size(), 3u); // the corpus and the two scenes
    const nlohmann::json& hard = figures["groups"][0]["settings"][0];
    EXPECT_EQ(hard["setting"], "hard");
    EXPECT_EQ(hard["views"], 2);
    const nlohmann::json& rmse = hard["error"]["rmse"];
    EXPECT_GT(rmse["value"].get<double>(), 0.0);
    EXPECT_LT(rmse["ci95"][0].get<double>(), rmse["ci95"][1].get<double>());
    const std::string html = slurp(reportOne / "report.html");
    EXPECT_NE(html.find("class=\"error-vs-cost\""), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos) << "no network references";
}

TEST(SweepCli, AKilledRunLosesOnlyItsTaskInFlight) {
    const fs::path plan =
        writePlan("kill.toml", kHead +
                                   "scenes = [\"builtin:showcase\", \"builtin:resting\", "
                                   "\"builtin:grazing\", \"builtin:spot\"]\n" +
                                   kBody);
    const fs::path out = outputScratch("sweep-killed");
    std::vector<std::string> args{PENUMBRA_CLI_PATH, "sweep", plan.string(), "-o", out.string()};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::freopen("/dev/null", "w", stderr);
        ::freopen("/dev/null", "w", stdout);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    ASSERT_GT(pid, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline &&
           (!fs::exists(out / "tasks") || records(out) < 3))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    const size_t done = records(out);
    ASSERT_GE(done, 3u);
    ASSERT_LT(done, 8u) << "the run finished before it was killed";
    const ProcessResult r = runCli({"sweep", plan.string(), "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(summaryLine(r).find(std::to_string(8 - done) + " task(s) run, " +
                                  std::to_string(done) + " skipped"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(records(out), 8u);
}

TEST(SweepCli, BadPlansAreRefusedWithOneLineAndNoOutput) {
    const fs::path out = outputScratch("sweep-refused");
    const std::pair<std::string, std::string> cases[] = {
        {kHead + "scenes = [\"builtin:showcase\"]\n[[techniques]]\nname = \"blur\"\n",
         "techniques[0].name: no technique 'blur'"},
        {kHead + "scenes = [\"nowhere.glb\"]\n" + kBody, "scenes[0]: no such file"},
        {kHead + "scenes = [\"builtin:showcase\"]\n" + kBody + "pcf.samples = [0]\n",
         "techniques[1].pcf.samples:"},
        {kHead + "scenes = [\"builtin:showcase\"]\nexposure = 2\n" + kBody, "exposure: unknown"}};
    for (const auto& [text, expected] : cases) {
        const fs::path plan = writePlan("bad.toml", text);
        const ProcessResult r = runCli({"sweep", plan.string(), "-o", out.string()});
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_EQ(r.err.rfind("error: " + plan.string() + ": " + expected, 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(out)) << text;
    }
    const ProcessResult r = runCli({"sweep", twoScenePlan().string(), "-o", out.string(),
                                    "--task-index", "3", "--task-count", "3"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "error: --task-index: 3 is not below the task count 3\n");
    EXPECT_FALSE(fs::exists(out));
}

TEST(SweepCli, ASceneThatDoesNotLoadFailsItsTasksOnly) {
    std::ofstream(scratchDir("sweep-cli") / "broken.gltf") << "{ not glTF";
    const fs::path plan = writePlan(
        "broken.toml", kHead + "scenes = [\"broken.gltf\", \"builtin:showcase\"]\n" + kBody);
    const fs::path out = outputScratch("sweep-broken"), report = outputScratch("merge-broken");
    ProcessResult r = runCli({"sweep", plan.string(), "-o", out.string()});
    EXPECT_EQ(r.exitCode, 1) << "failed tasks make the exit status 1";
    EXPECT_EQ(summaryLine(r), "sweep: 4 task(s) run, 0 skipped (done before), 2 failed; truths: "
                              "1 traced, 0 from the cache");
    r = runCli({"merge", out.string(), "-o", report.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json merged = nlohmann::json::parse(slurp(report / "merge.json"));
    ASSERT_EQ(merged["failed"].size(), 2u);
    EXPECT_EQ(merged["failed"][0]["scene"], "broken.gltf");
    EXPECT_NE(merged["failed"][0]["error"].get<std::string>().find("broken.gltf"),
              std::string::npos);
    EXPECT_EQ(merged["groups"][0]["settings"].size(), 2u);
    EXPECT_NE(slurp(report / "report.html").find("Failed tasks"), std::string::npos);
}

TEST(SweepCli, CompareAndTuneReadTheTruthASweepCached) {
    // The scenes' own light at its own size: the view compare sees by default.
    const fs::path plan = writePlan(
        "own.toml", kHead + "scenes = [\"builtin:showcase\"]\n[[techniques]]\nname = \"hard\"\n");
    const fs::path out = outputScratch("sweep-own");
    ASSERT_EQ(runCli({"sweep", plan.string(), "-o", out.string()}).exitCode, 0);
    const std::vector<std::string> view{
        "--width",   "64", "--height",      "48",
        "--samples", "8",  "--truth-cache", (out / "truth").string()};
    std::vector<std::string> compare{"compare",      "builtin:showcase",
                                     "-o",           outputScratch("compare-cached").string(),
                                     "--techniques", "hard"};
    compare.insert(compare.end(), view.begin(), view.end());
    ProcessResult r = runCli(compare);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("ground truth from the cache"), std::string::npos) << r.err;
    std::vector<std::string> tune{"tune",        "builtin:showcase",
                                  "--technique", "hard",
                                  "-o",          outputScratch("tune-cached").string(),
                                  "--sweep",     "bias.constant=0,0.001"};
    tune.insert(tune.end(), view.begin(), view.end());
    r = runCli(tune);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("ground truth from the cache"), std::string::npos) << r.err;
}

namespace {

// A sweep of the sliding box (sliding_box.h) at `times` with hard and pcf into `out`: its task
// records by time (-1: a record without one).
std::map<double, std::vector<nlohmann::json>>
timedSweep(const std::string& name, const std::string& times, ProcessResult& r, fs::path& out) {
    boxAsset(scratchDir("sweep-cli") / "sliding", /*animated=*/true, /*lit=*/false);
    const fs::path plan =
        writePlan(name + ".toml", kHead + "scenes = [\"sliding/unlit.gltf\"]\n" + times +
                                      "[[techniques]]\nname = \"hard\"\n"
                                      "[[techniques]]\nname = \"pcf\"\npcf.size = [3]\n");
    out = outputScratch("sweep-" + name);
    r = runCli({"sweep", plan.string(), "-o", out.string()});
    std::map<double, std::vector<nlohmann::json>> byTime;
    for (const auto& e : fs::directory_iterator(out / "tasks")) {
        if (e.path().extension() != ".json" || e.path().filename().string()[0] == '.')
            continue;
        const nlohmann::json j = nlohmann::json::parse(slurp(e.path()));
        byTime[j.value("time", -1.0)].push_back(j);
    }
    return byTime;
}

// The truth keys of records, and a setting's RMSE among them.
std::set<std::string> truthKeys(const std::vector<nlohmann::json>& records) {
    std::set<std::string> keys;
    for (const nlohmann::json& j : records)
        keys.insert(j["truth"]["key"].get<std::string>());
    return keys;
}

double rmseOf(const std::vector<nlohmann::json>& records, const std::string& setting) {
    for (const nlohmann::json& j : records)
        if (j["setting"] == setting)
            return j["metrics"]["rmse"].get<double>();
    ADD_FAILURE() << "no " << setting;
    return -1.0;
}

} // namespace

// A time is a view of its own: posed at it, traced once, recorded with its time and merged as
// any view. Every time is framed as the plan's first is (its automatic camera, light and
// ground), so a view at a time measures what compare --timeline measures in its frame at that
// time, and the first time's view is compare --time's, whose truth compare reads from the
// sweep's cache. An animation the scene lacks fails its tasks, named with their time.
TEST(SweepCli, TimesAreViewsPosedAtEachTimeAndFramedAtTheFirst) {
    ProcessResult r;
    fs::path out, other;
    const auto both = timedSweep("times", "times = [0, 0.5]\n", r, out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(summaryLine(r), "sweep: 4 task(s) run, 0 skipped (done before), 0 failed; truths: "
                              "2 traced, 0 from the cache");
    EXPECT_NE(r.err.find("on sliding/unlit.gltf, scene, at 0.5 s (elapsed"), std::string::npos)
        << r.err;
    ASSERT_EQ(both.size(), 2u);
    ASSERT_EQ(both.count(0.0) + both.count(0.5), 2u);
    EXPECT_EQ(truthKeys(both.at(0.0)).size(), 1u) << "one truth per view";
    EXPECT_NE(truthKeys(both.at(0.0)), truthKeys(both.at(0.5))) << "the box moved";
    const nlohmann::json planned = nlohmann::json::parse(slurp(out / "sweep.json"));
    for (const nlohmann::json& task : planned["tasks"])
        EXPECT_TRUE(task.contains("time")) << task;
    const std::string list = runCli({"sweep", (scratchDir("sweep-cli") / "times.toml").string(),
                                     "-o", out.string(), "--list"})
                                 .out;
    EXPECT_NE(list.find(" hard t=0.5s\n"), std::string::npos) << list;

    // Compare's timeline, its frames framed by its first, measures the same.
    const fs::path asset = scratchDir("sweep-cli") / "sliding" / "unlit.gltf";
    const std::vector<std::string> view{"--width",      "64",  "--height",          "48",
                                        "--samples",    "8",   "--shadow-map-size", "256",
                                        "--techniques", "hard"};
    const fs::path timelineOut = outputScratch("compare-timeline");
    std::vector<std::string> timeline{"compare",    asset.string(), "-o", timelineOut.string(),
                                      "--timeline", "0:0.5:0.5"};
    timeline.insert(timeline.end(), view.begin(), view.end());
    r = runCli(timeline);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json frames = nlohmann::json::parse(slurp(timelineOut / "timeline.json"));
    EXPECT_DOUBLE_EQ(frames["rows"]["hard"]["rmse"][1].get<double>(), rmseOf(both.at(0.5), "hard"));
    // At 0.5 s alone the box's bounds frame another view.
    const auto alone = timedSweep("time-alone", "times = [0.5]\n", r, other);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(alone.count(0.5), 1u);
    EXPECT_NE(truthKeys(alone.at(0.5)), truthKeys(both.at(0.5)));

    const fs::path report = outputScratch("merge-times");
    ASSERT_EQ(runCli({"merge", out.string(), "-o", report.string()}).exitCode, 0);
    EXPECT_EQ(errorFigures(report)["groups"][0]["settings"][0]["views"], 2);
    std::vector<std::string> compare{"compare",
                                     asset.string(),
                                     "-o",
                                     outputScratch("compare-timed").string(),
                                     "--time",
                                     "0",
                                     "--truth-cache",
                                     (out / "truth").string()};
    compare.insert(compare.end(), view.begin(), view.end());
    r = runCli(compare);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("ground truth from the cache"), std::string::npos) << r.err;

    const auto missing = timedSweep("no-walk", "times = [0.25]\nanimation = \"walk\"\n", r, other);
    EXPECT_EQ(r.exitCode, 1);
    ASSERT_EQ(missing.count(0.25), 1u);
    EXPECT_NE(missing.at(0.25)[0]["error"].get<std::string>().find("'walk'"), std::string::npos)
        << missing.at(0.25)[0];
    const fs::path failures = outputScratch("merge-no-walk");
    ASSERT_EQ(runCli({"merge", other.string(), "-o", failures.string()}).exitCode, 0);
    const nlohmann::json merged = nlohmann::json::parse(slurp(failures / "merge.json"));
    ASSERT_EQ(merged["failed"].size(), 2u);
    EXPECT_EQ(merged["failed"][0]["time"], 0.25);
    EXPECT_NE(slurp(failures / "report.html").find("on sliding/unlit.gltf, scene, at 0.25 s: "),
              std::string::npos);
}

TEST(SweepCli, EmitsTheClusterJobsForThePlan) {
    const fs::path plan = twoScenePlan(), out = outputScratch("sweep-emit");
    ProcessResult r =
        runCli({"sweep", plan.string(), "-o", out.string(), "--emit", "slurm", "--gpus", "0"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("#SBATCH --array=0-1\n"), std::string::npos) << r.out; // two views
    EXPECT_EQ(r.out.find("--gres"), std::string::npos);
    EXPECT_NE(r.out.find(" sweep " + fs::absolute(plan).string() + " -o "), std::string::npos);
    // Relative paths lie inside the volume's mount: run from where plans/p.toml is the plan.
    const fs::path root = scratchDir("sweep-k8s");
    fs::create_directories(root / "plans");
    fs::copy_file(plan, root / "plans" / "p.toml", fs::copy_options::overwrite_existing);
    const fs::path cwd = fs::current_path();
    fs::current_path(root);
    r = runCli({"sweep", "plans/p.toml", "-o", "out", "--emit", "kubernetes", "--task-count", "4",
                "--image", "penumbra:1.0"});
    fs::current_path(cwd);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("  completions: 4\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("image: \"penumbra:1.0\""), std::string::npos);
    EXPECT_NE(r.out.find("nvidia.com/gpu: 1"), std::string::npos);
    // The manifest's shape, read by a YAML parser (Debian's python3-yaml).
    const fs::path manifest = scratchDir("sweep-cli") / "job.yaml";
    std::ofstream(manifest) << r.out;
    const ProcessResult parsed = runProcess(
        {"/usr/bin/python3", "-c",
         "import sys, yaml\n"
         "job = yaml.safe_load(open(sys.argv[1]))\n"
         "assert job['apiVersion'] == 'batch/v1' and job['kind'] == 'Job', job\n"
         "spec = job['spec']\n"
         "assert spec['completionMode'] == 'Indexed' and spec['completions'] == 4\n"
         "assert spec['parallelism'] == 4\n"
         "pod = spec['template']['spec']\n"
         "assert pod['restartPolicy'] == 'Never'\n"
         "[c] = pod['containers']\n"
         "assert c['args'][:4] == ['sweep', '/data/plans/p.toml', '-o', '/data/out'], c\n"
         "assert c['args'][c['args'].index('--task-count') + 1] == '4'\n"
         "assert c['resources']['limits']['nvidia.com/gpu'] == 1\n"
         "[m] = c['volumeMounts']\n"
         "[v] = pod['volumes']\n"
         "assert m['name'] == v['name'] and m['mountPath'] == '/data'\n"
         "assert v['persistentVolumeClaim']['claimName'] == 'penumbra-data'\n",
         manifest.string()});
    EXPECT_EQ(parsed.exitCode, 0) << parsed.err;
}

// The plans the repository ships are valid against today's techniques and parameters, and expand
// to the task counts docs/sweep.md gives.
TEST(SweepCli, TheShippedPlansAreValid) {
    for (const auto& [name, tasks] : {std::pair{"smoke.toml", 12}, std::pair{"standard.toml", 660},
                                      std::pair{"motion.toml", 96}}) {
        const fs::path plan = fs::path(PENUMBRA_SOURCE_DIR) / "bench" / "plans" / name;
        const ProcessResult r =
            runCli({"sweep", plan.string(), "-o", outputScratch("sweep-plans").string(), "--list"});
        ASSERT_EQ(r.exitCode, 0) << name << ": " << r.err;
        size_t lines = 0;
        for (char c : r.out)
            lines += c == '\n';
        EXPECT_EQ(lines, size_t(tasks)) << name << ":\n" << r.out.substr(0, 2000);
    }
}
