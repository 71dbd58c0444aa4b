// The sweep's library parts without a device: plans and their refusals, task ids and shards,
// the truth cache's keys and files, the truth bootstrap's intervals, merging task records, and
// the cluster jobs' text.
#include "penumbra/error.h"
#include "scratch_dir.h"
#include "sweep/emit.h"
#include "sweep/merge.h"
#include "sweep/plan.h"
#include "sweep/records.h"
#include "sweep/tasks.h"
#include "sweep/truth_bootstrap.h"
#include "sweep/truth_cache.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <thread>

using namespace penumbra;
using namespace penumbra::sweep;
namespace fs = std::filesystem;

namespace {

fs::path writePlan(const std::string& name, const std::string& text) {
    const fs::path p = test::scratchDir("sweep") / name;
    std::ofstream(p) << text;
    return p;
}

const std::string kScenes = "scenes = [\"builtin:showcase\", \"builtin:resting\"]\n";
const std::string kLights = "[[lights]]\nkind = \"sun\"\ndirection = [0.3, -1, 0.4]\n"
                            "sizes = [0, 2]\n[[lights]]\nkind = \"scene\"\n";
const std::string kTechniques = "[[techniques]]\nname = \"hard\"\n[[techniques]]\nname = "
                                "\"pcf\"\npcf.size = [3, 7]\n";

// The InputError message of loading `text`, or "" when it loads.
std::string refusal(const std::string& text) {
    const fs::path p = writePlan("bad.toml", text);
    try {
        loadPlan(p);
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), p.string());
        return std::string(e.what()).substr(p.string().size() + 2);
    }
    return "";
}

} // namespace

TEST(SweepPlan, ExpandsTheGridAndTheLightSizes) {
    const Plan plan = loadPlan(writePlan("good.toml", "width = 64\nheight = 48\nsamples = 8\n" +
                                                          kScenes + kLights + kTechniques));
    EXPECT_EQ(plan.width, 64u);
    EXPECT_EQ(plan.samples, 8u);
    ASSERT_EQ(plan.scenes.size(), 2u);
    ASSERT_EQ(plan.lights.size(), 3u); // sun at 0 and 2 degrees, the scene's own
    EXPECT_EQ(plan.lights[1].size, 2.0f);
    std::vector<std::string> names;
    for (const PlanSetting& s : plan.settings)
        names.push_back(s.name());
    EXPECT_EQ(names, (std::vector<std::string>{"hard", "pcf[pcf.size=3]", "pcf[pcf.size=7]"}));
    EXPECT_EQ(expandTasks(plan).tasks.size(), 2u * 3u * 3u);
}

TEST(SweepPlan, RefusesEachMistakeNamingItsKey) {
    const std::string base = kScenes + kLights;
    const std::pair<std::string, std::string> cases[] = {
        {"colour = 3\n" + base + kTechniques, "colour: unknown key"},
        {"width = 0\n" + base + kTechniques, "width: 0 is outside 1..16384"},
        {"samples = 1.5\n" + base + kTechniques, "samples: expected a whole number"},
        {"scenes = [\"builtin:nothing\"]\n" + kLights + kTechniques, "scenes[0]: no built-in"},
        {"scenes = [\"missing.gltf\"]\n" + kLights + kTechniques, "scenes[0]: no such file"},
        {"scenes = [\"builtin:gen/plates?seed=x\"]\n" + kLights + kTechniques,
         "scenes[0]: builtin:gen/plates?seed=x: seed 'x'"},
        {"scenes = [\"builtin:gen/cave\"]\n" + kLights + kTechniques,
         "scenes[0]: builtin:gen/cave: no such generated family"},
        {base + "[[techniques]]\nname = \"blur\"\n", "techniques[0].name: no technique 'blur'"},
        {base + "[[techniques]]\nname = \"pcf\"\npcf.colour = [1]\n", "techniques[0].pcf.colour:"},
        {base + "[[techniques]]\nname = \"pcf\"\npcf.size = [3, 1000]\n",
         "techniques[0].pcf.size:"},
        {base + "[[techniques]]\nname = \"pcf\"\nvsm.size = [3]\n",
         "techniques[0].vsm: pcf reads no vsm.* parameters"},
        {kScenes + "[[lights]]\nkind = \"sun\"\n" + kTechniques, "lights[0].direction: missing"},
        {kScenes + "[[lights]]\nkind = \"sun\"\ndirection = [0, -1, 0]\nsizes = [45]\n" +
             kTechniques,
         "lights[0].sizes: '45' is not a size in 0..30"},
        {kScenes + "[[lights]]\nkind = \"lamp\"\n" + kTechniques, "lights[0].kind: expected"},
        {kScenes + "[[lights]]\nkind = \"point\"\nposition = [0, 1, 0]\nshape = 1\n" + kTechniques,
         "lights[0].shape: unknown key"},
        {base, "techniques: expected [[techniques]] tables"},
        {"width = \n", "line 1:"}};
    for (const auto& [text, expected] : cases) {
        const std::string why = refusal(text);
        EXPECT_EQ(why.rfind(expected, 0), 0u) << "got '" << why << "' for:\n" << text;
    }
    EXPECT_EQ(refusal(base + kTechniques), "");
    EXPECT_EQ(refusal("scenes = [\"builtin:gen/plates?seed=3\", \"builtin:gen/plates?seed=4\"]\n" +
                      kLights + kTechniques),
              "");
}

// `times` makes each scene, light and camera a view at each time: a list, or START:END:STEP as
// compare --timeline reads it (its last frame within a millionth of a step of END).
TEST(SweepPlan, TimesMakeAViewAtEachTime) {
    const std::string body = "scenes = [\"builtin:pendulum\"]\n" + kLights + kTechniques;
    const Plan listed =
        loadPlan(writePlan("times.toml", "times = [0, 0.5, 1.25]\nanimation = \"swing\"\n" + body));
    ASSERT_EQ(listed.times.size(), 3u);
    EXPECT_EQ(listed.times[2], 1.25);
    EXPECT_EQ(listed.animation, "swing");
    const SweepTasks tasks = expandTasks(listed);
    ASSERT_EQ(tasks.views.size(), 3u * 3u); // 3 lights x 3 times
    std::map<double, size_t> perTime;
    for (const SweepView& v : tasks.views) {
        ASSERT_TRUE(v.time.has_value());
        ++perTime[*v.time];
        EXPECT_EQ(v.animation, "swing");
    }
    EXPECT_EQ(perTime, (std::map<double, size_t>{{0.0, 3}, {0.5, 3}, {1.25, 3}}));
    EXPECT_EQ(tasks.tasks.size(), 9u * 3u);

    const Plan ranged = loadPlan(writePlan("range.toml", "times = \"0.5:1.5:0.25\"\n" + body));
    EXPECT_EQ(ranged.times, (std::vector<double>{0.5, 0.75, 1.0, 1.25, 1.5}));
    const Plan tenths = loadPlan(writePlan("tenths.toml", "times = \"0:0.3:0.1\"\n" + body));
    ASSERT_EQ(tenths.times.size(), 4u);
    EXPECT_EQ(tenths.times[3], 0.3); // not 0.30000000000000004
    const Plan one = loadPlan(writePlan("one.toml", "times = [2]\nanimation = 1\n" + body));
    EXPECT_EQ(one.times, std::vector<double>{2.0});
    EXPECT_EQ(one.animation, "1");
    // -0 is 0: the same time, the same view.
    const Plan minusZero = loadPlan(writePlan("minus.toml", "times = [-0.0]\n" + body));
    ASSERT_EQ(minusZero.times.size(), 1u);
    EXPECT_FALSE(std::signbit(minusZero.times[0]));
    EXPECT_EQ(expandTasks(minusZero).views[0].id,
              expandTasks(loadPlan(writePlan("zero.toml", "times = [0]\n" + body))).views[0].id);
    // Without `times` the views are at rest.
    const Plan still = loadPlan(writePlan("still.toml", body));
    EXPECT_TRUE(still.times.empty());
    for (const SweepView& v : expandTasks(still).views)
        EXPECT_FALSE(v.time.has_value());
}

TEST(SweepPlan, RefusesTimesThatAreNotTimes) {
    const std::string body = kScenes + kLights + kTechniques;
    const std::pair<std::string, std::string> cases[] = {
        {"times = []\n", "times: an empty list"},
        {"times = [-1]\n", "times: '-1' is not"},
        {"times = [0, \"a\"]\n", "times: 'a' is not"},
        {"times = [0.5, 0.5]\n", "times: 0.5 is listed twice"},
        {"times = [0, inf]\n", "times: 'inf' is not"},
        {"times = [\"0.5\"]\n", "times: '0.5' is not"},
        {"times = [[0.5]]\n", "times: 'a table or list' is not"},
        {"times = \"1000:1000.000000001:1e-10\"\n", "times: 1000 is listed twice"},
        {"times = [0, 0.25, 0.5, 0.25]\n", "times: 0.25 is listed twice"},
        {"times = true\n", "times: expected"},
        {"times = \"0:1\"\n", "times: '0:1' is not START:END:STEP"},
        {"times = \"1:0:1\"\n", "times: '1:0:1': START must be"},
        {"times = \"0:1:0\"\n", "times: '0:1:0': START must be"},
        {"times = \"0:100000:1\"\n", "times: '0:100000:1' is 100001 frames"},
        {"animation = \"swing\"\n", "animation: needs times"},
        {"times = [0]\nanimation = \"\"\n", "animation: expected"},
        {"times = [0]\nanimation = -1\n", "animation: expected"},
        {"times = [0]\nanimation = 0.5\n", "animation: expected"}};
    for (const auto& [head, expected] : cases) {
        const std::string why = refusal(head + body);
        EXPECT_EQ(why.rfind(expected, 0), 0u) << "got '" << why << "' for:\n" << head;
    }
    EXPECT_EQ(refusal("times = [0]\nanimation = 0\n" + body), "");
    std::string many = "times = [0";
    for (int k = 1; k <= 10000; ++k)
        many += fmt::format(", {}", k);
    EXPECT_EQ(refusal(many + "]\n" + body).rfind("times: 10001 times; at most 10000", 0), 0u);
    many.erase(many.rfind(','));
    EXPECT_EQ(refusal(many + "]\n" + body), "");
}

TEST(SweepTasks, IdsDependOnWhatATaskComputesNotOnThePlansOrder) {
    const std::string head = "width = 64\nheight = 48\n";
    const Plan a = loadPlan(writePlan("a.toml", head + kScenes + kLights + kTechniques));
    const Plan b = loadPlan(
        writePlan("b.toml", head + "scenes = [\"builtin:resting\", \"builtin:showcase\"]\n" +
                                "[[lights]]\nkind = \"scene\"\n[[lights]]\nkind = \"sun\"\n"
                                "direction = [0.3, -1, 0.4]\nsizes = [2, 0]\n"
                                "[[techniques]]\nname = \"pcf\"\npcf.size = [7, 3]\n"
                                "[[techniques]]\nname = \"hard\"\n"));
    const SweepTasks ta = expandTasks(a), tb = expandTasks(b);
    ASSERT_EQ(ta.tasks.size(), tb.tasks.size());
    std::set<std::string> ids;
    for (size_t t = 0; t < ta.tasks.size(); ++t) {
        EXPECT_EQ(ta.tasks[t].id, tb.tasks[t].id);
        ids.insert(ta.tasks[t].id);
    }
    EXPECT_EQ(ids.size(), ta.tasks.size()); // all distinct
    // A different image size is a different task.
    const Plan c = loadPlan(
        writePlan("c.toml", "width = 65\nheight = 48\n" + kScenes + kLights + kTechniques));
    for (const SweepTask& t : expandTasks(c).tasks)
        EXPECT_FALSE(ids.count(t.id));
}

TEST(SweepTasks, EveryTaskFallsToExactlyOneShardAndViewsStayTogether) {
    const SweepTasks tasks =
        expandTasks(loadPlan(writePlan("s.toml", kScenes + kLights + kTechniques))); // 6 views
    for (uint32_t count = 1; count <= 9; ++count) {
        std::vector<int> seen(tasks.tasks.size(), 0);
        std::map<size_t, std::set<uint32_t>> shardsOfView;
        for (uint32_t i = 0; i < count; ++i)
            for (size_t t : shardTasks(tasks, i, count)) {
                ++seen[t];
                shardsOfView[tasks.tasks[t].view].insert(i);
            }
        EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }))
            << count << " shards";
        if (count <= tasks.views.size()) {
            for (const auto& [view, shards] : shardsOfView)
                EXPECT_EQ(shards.size(), 1u) << "view " << view << " with " << count << " shards";
        }
        if (count == 3) { // 6 views of 3 tasks: two views per shard
            for (uint32_t i = 0; i < count; ++i)
                EXPECT_EQ(shardTasks(tasks, i, count).size(), 6u);
        }
    }
}

namespace {

Scene litScene(float angleDegrees) {
    Scene s = loadScene("builtin:showcase"); // a sun
    applyLightSizeOverrides(s, -1.0f, angleDegrees);
    return s;
}

ReferenceResult fakeTruth(uint32_t w, uint32_t h, float value) {
    ReferenceResult r{.width = w, .height = h, .rays = 7, .seconds = 1.5, .traceSeconds = 1.0};
    r.visibility = {std::vector<float>(size_t(w) * h, value)};
    r.visibility[0][0] = NAN;
    r.occluderDistance = {std::vector<float>(size_t(w) * h, INFINITY)};
    return r;
}

} // namespace

TEST(TruthCache, KeysChangeWithWhatDecidesTheTruthOnly) {
    const Scene lit = litScene(1.0f);
    const std::string key = truthKey(lit, "", 64, 48, 16);
    EXPECT_EQ(key, truthKey(litScene(1.0f), "", 64, 48, 16));
    EXPECT_NE(key, truthKey(lit, "", 64, 48, 32));
    EXPECT_NE(key, truthKey(lit, "", 65, 48, 16));
    EXPECT_NE(key, truthKey(litScene(1.5f), "", 64, 48, 16));
    Scene moved = lit;
    moved.vertices[0].position.x += 0.01f;
    EXPECT_NE(key, truthKey(moved, "", 64, 48, 16));
    EXPECT_NE(sceneContentHash(lit), sceneContentHash(moved));
    Scene renamed = lit; // names and colours do not change the truth
    renamed.name = "other";
    renamed.materials[0].baseColor.x = 0.1f;
    EXPECT_EQ(key, truthKey(renamed, "", 64, 48, 16));
}

TEST(TruthCache, ComputesOnceAndReadsBackWhatItStored) {
    const fs::path dir = test::scratchDir("sweep", "cache", true);
    const TruthCache cache(dir);
    int computations = 0;
    auto compute = [&] {
        ++computations;
        return fakeTruth(8, 4, 0.25f);
    };
    bool computed = false;
    const ReferenceResult first = cachedTruth(&cache, "k1", compute, &computed);
    EXPECT_TRUE(computed);
    const ReferenceResult second = cachedTruth(&cache, "k1", compute, &computed);
    EXPECT_FALSE(computed);
    EXPECT_EQ(computations, 1);
    EXPECT_EQ(second.width, 8u);
    EXPECT_EQ(second.rays, 7u);
    EXPECT_EQ(second.traceSeconds, 1.0);
    ASSERT_EQ(second.visibility.size(), 1u);
    EXPECT_TRUE(std::isnan(second.visibility[0][0]));
    EXPECT_EQ(second.visibility[0][5], 0.25f);
    EXPECT_EQ(second.occluderDistance[0][5], INFINITY);
    // A damaged file is not read: computed again and replaced.
    fs::resize_file(cache.fileOf("k1"), 30);
    cachedTruth(&cache, "k1", compute, &computed);
    EXPECT_TRUE(computed);
    EXPECT_EQ(computations, 2);
    EXPECT_TRUE(cache.load("k1").has_value());
    // Nor is one with bytes past its end.
    std::ofstream(cache.fileOf("k1"), std::ios::binary | std::ios::app) << 'x';
    EXPECT_FALSE(cache.load("k1").has_value()) << "a file longer than its layout";
    cachedTruth(&cache, "k1", compute, &computed);
    EXPECT_TRUE(computed);
    EXPECT_TRUE(cache.load("k1").has_value());
    // A truth without occluder distances keeps them unknown.
    ReferenceResult bare = fakeTruth(4, 4, 1.0f);
    bare.occluderDistance.clear();
    cache.store("bare", bare);
    const std::optional<ReferenceResult> read = cache.load("bare");
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->visibility[0][3], 1.0f);
    EXPECT_TRUE(std::isnan(read->occluderDistance[0][3]));
}

TEST(TruthCache, ConcurrentWritersLeaveOneWholeFile) {
    const fs::path dir = test::scratchDir("sweep", "race", true);
    const TruthCache cache(dir);
    const ReferenceResult truth = fakeTruth(256, 256, 0.5f);
    std::vector<std::thread> writers;
    for (int i = 0; i < 4; ++i)
        writers.emplace_back([&] {
            for (int k = 0; k < 5; ++k) {
                cache.store("same", truth);
                const std::optional<ReferenceResult> read = cache.load("same");
                EXPECT_TRUE(read && read->visibility[0][100] == 0.5f);
            }
        });
    for (std::thread& t : writers)
        t.join();
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir))
        files += entry.is_regular_file();
    EXPECT_EQ(files, 1u); // no temporary file left
}

TEST(TruthBootstrap, IntervalsNarrowAsTheSquareRootOfTheSamplesAndUndoTheTruthsNoise) {
    // A technique that says 0 everywhere against a truth of 0.5 from n rays per pixel: the
    // measured RMSE is sqrt(mean t^2). With t = 1/2 + e, Var e = 1/(4n), the mean of t^2 over P
    // pixels has variance (1/(4n) + 1/(8 n^2)) / P, and RMSE (~1/2) moves by as much as that
    // mean: the 95% width is 3.92 of its square root. Redrawn truths are noisier than the
    // measured one by the same amount the measured one is noisier than the exact truth, so the
    // replicates' RMSE sits sqrt(1/4 + 1/(4n)) - 1/2 high and the interval as far below 1/2.
    const uint32_t w = 64, h = 64;
    const double pixels = double(w * h - 1); // one background pixel
    auto interval = [&](uint32_t n) {
        const ReferenceResult truth = fakeTruth(w, h, 0.5f);
        const std::vector<uint32_t> perLayer{n};
        std::vector<double> rmse;
        for (const ReferenceResult& r : bootstrapTruths(truth, perLayer, 200, 7)) {
            double sum = 0;
            for (float t : r.visibility[0])
                if (std::isfinite(t))
                    sum += double(t) * t;
            rmse.push_back(std::sqrt(sum / pixels));
        }
        return basicInterval(0.5, rmse);
    };
    for (const double n : {16.0, 256.0}) {
        const Interval ci = interval(uint32_t(n));
        const double width = 3.92 * std::sqrt((1 / (4 * n) + 1 / (8 * n * n)) / pixels);
        const double bias = std::sqrt(0.25 + 1 / (4 * n)) - 0.5;
        EXPECT_NEAR(ci.hi - ci.lo, width, 0.3 * width) << n << " rays";
        EXPECT_NEAR(0.5 * (ci.lo + ci.hi), 0.5 - bias, 0.3 * width) << n << " rays";
    }
}

TEST(TruthBootstrap, ExactTruthsAreNeverRedrawn) {
    const ReferenceResult truth = fakeTruth(16, 16, 0.5f);
    const std::vector<uint32_t> exact{1};
    for (const ReferenceResult& r : bootstrapTruths(truth, exact, 8, 1))
        EXPECT_EQ(r.visibility[0][3], 0.5f);
    const std::vector<uint32_t> sampled{64};
    const std::vector<ReferenceResult> a = bootstrapTruths(truth, sampled, 4, 9);
    const std::vector<ReferenceResult> b = bootstrapTruths(truth, sampled, 4, 9);
    auto drawn = [](const ReferenceResult& r) { // past the background pixel (NaN != NaN)
        return std::vector<float>(r.visibility[0].begin() + 1, r.visibility[0].end());
    };
    EXPECT_EQ(drawn(a[3]), drawn(b[3])); // the same seed, the same draws
    EXPECT_NE(drawn(a[3]), drawn(a[2]));
    EXPECT_TRUE(std::isnan(a[3].visibility[0][0]));
    // Replicate 3 alone is the fourth of four.
    EXPECT_EQ(drawn(bootstrapTruth(truth, sampled, 9, 3)), drawn(a[3]));
    // On the machine's cores, each replicate's metric at its index.
    const std::vector<ErrorMetrics> metrics =
        bootstrapMetrics(truth, sampled, 4, 9, [](const ReferenceResult& r) {
            ErrorMetrics m;
            m.rmse = r.visibility[0][7];
            return m;
        });
    for (size_t i = 0; i < 4; ++i)
        EXPECT_EQ(metrics[i].rmse, a[i].visibility[0][7]);
}

TEST(TruthBootstrap, BasicIntervalReflectsTheReplicatesAboutTheEstimate) {
    std::vector<double> replicates;
    for (int i = 0; i <= 100; ++i)
        replicates.push_back(0.30 + 0.001 * i); // 2.5th (2 of 0..100): 0.302, 97.5th: 0.398
    std::reverse(replicates.begin(), replicates.end());
    const Interval ci = basicInterval(0.32, replicates);
    EXPECT_NEAR(ci.lo, 2 * 0.32 - 0.398, 1e-12);
    EXPECT_NEAR(ci.hi, 2 * 0.32 - 0.302, 1e-12);
    EXPECT_TRUE(std::isnan(basicInterval(0.3, {}).lo));
    EXPECT_EQ(basicInterval(0.001, {0.0, 0.5}).lo, 0.0); // clamped
}

namespace {

TaskRecord record(const std::string& id, const std::string& scene, const std::string& setting,
                  double rmse, double shadowMs) {
    TaskRecord r{.id = id, .scene = scene, .setting = setting, .technique = "pcf"};
    r.device = "dev";
    for (const MetricField& f : kMetricFields) {
        r.metrics[std::string(f.name)] = f.name == "rmse" ? rmse : 0.0;
        r.replicates[std::string(f.name)] = {r.metrics[std::string(f.name)],
                                             r.metrics[std::string(f.name)] + 0.01};
    }
    r.shadowMs = shadowMs;
    r.visibilityMs = shadowMs / 2;
    return r;
}

} // namespace

TEST(SweepMerge, MeansRanksFrontsAndFailures) {
    std::vector<TaskRecord> records{
        record("a", "s1", "cheap", 0.30, 1.0), record("b", "s1", "good", 0.10, 3.0),
        record("c", "s1", "bad", 0.35, 4.0),   record("d", "s2", "cheap", 0.20, 1.0),
        record("e", "s2", "good", 0.10, 5.0),  record("f", "s2", "bad", 0.40, 2.0)};
    TaskRecord failed{.id = "g", .scene = "s2", .setting = "good", .failed = true, .error = "x"};
    records.push_back(failed);
    const MergeResult m = mergeRecords(records);
    EXPECT_EQ(m.tasks, 7u);
    ASSERT_EQ(m.failed.size(), 1u);
    ASSERT_EQ(m.groups.size(), 3u);
    const GroupSummary& corpus = m.groups[0];
    EXPECT_EQ(corpus.name, "corpus");
    ASSERT_EQ(corpus.settings.size(), 3u);
    const SettingSummary& bad = corpus.settings[0]; // sorted: bad, cheap, good
    const SettingSummary& cheap = corpus.settings[1];
    const SettingSummary& good = corpus.settings[2];
    EXPECT_EQ(good.setting, "good");
    EXPECT_NEAR(cheap.metrics.at("rmse").value, 0.25, 1e-12);
    EXPECT_NEAR(cheap.shadowMs, 1.0, 1e-12);
    EXPECT_NEAR(bad.shadowMs, 3.0, 1e-12);
    EXPECT_EQ(good.metrics.at("rmse").rank, 1);
    EXPECT_EQ(cheap.metrics.at("rmse").rank, 2);
    EXPECT_EQ(bad.metrics.at("rmse").rank, 3);
    EXPECT_EQ(bad.metrics.at("acne").rank, 1); // all tie
    EXPECT_TRUE(good.onFront);
    EXPECT_TRUE(cheap.onFront);
    EXPECT_FALSE(bad.onFront); // cheap beats it on both
    // Replicate-wise means (0.25, 0.26): the interval reflected about 0.25.
    EXPECT_NEAR(cheap.metrics.at("rmse").lo, 2 * 0.25 - 0.26, 1e-12);
    EXPECT_NEAR(cheap.metrics.at("rmse").hi, 0.25, 1e-12);
    EXPECT_EQ(m.groups[1].name, "s1");
    // The order records come in does not change a figure.
    std::reverse(records.begin(), records.end());
    EXPECT_EQ(mergeJson(mergeRecords(records)).dump(), mergeJson(m).dump());
}

// By the group each pass declares, never by its name: smrt's "filter" is per-pixel work, a pass
// of any name in the frame's group is left out.
TEST(SweepMerge, CostsAreThePerPixelPassesAndEveryPassButTheFrames) {
    TaskRecord r;
    const auto pass = [](std::string name, CostGroup cost, double ms) {
        return PassTime{.pass = std::move(name), .cost = cost, .medianMs = ms};
    };
    setCosts(r, {pass("shadow", CostGroup::ShadowMaps, 1.0), pass("gbuffer", CostGroup::Frame, 2.0),
                 pass("vsm_blur", CostGroup::ShadowMaps, 0.25),
                 pass("visibility", CostGroup::PerPixel, 0.5),
                 pass("filter", CostGroup::PerPixel, 16.0), pass("tonemap", CostGroup::Frame, 32.0),
                 pass("composite", CostGroup::PerPixel, 4.0)});
    EXPECT_EQ(r.visibilityMs, 20.5); // visibility, filter, composite
    EXPECT_EQ(r.shadowMs, 21.75);    // everything but the frame's
    ASSERT_EQ(r.passes.size(), 7u);
    EXPECT_EQ(r.passes[4], (std::pair<std::string, double>{"filter", 16.0})) << "frame order";
    // Costed again (a task run twice): the new passes replace the old.
    setCosts(r, {pass("visibility", CostGroup::PerPixel, 0.5)});
    EXPECT_EQ(r.passes.size(), 1u);
    EXPECT_EQ(r.visibilityMs, 0.5);
    EXPECT_EQ(r.shadowMs, 0.5);
}

TEST(SweepEmit, SlurmArrayAndKubernetesIndexedJob) {
    const EmitOptions o{.plan = "/p/plan.toml", .output = "/p/out dir", .shards = 3, .gpus = 2};
    const std::string slurm = slurmScript(o);
    EXPECT_EQ(slurm.rfind("#!/bin/bash\n", 0), 0u);
    EXPECT_NE(slurm.find("#SBATCH --array=0-2\n"), std::string::npos);
    EXPECT_NE(slurm.find("#SBATCH --gres=gpu:2\n"), std::string::npos);
    EXPECT_NE(slurm.find("penumbra sweep /p/plan.toml -o '/p/out dir' --task-count 3\n"),
              std::string::npos);
    const std::string k8s = kubernetesManifest(o);
    for (const char* line :
         {"apiVersion: batch/v1\n", "kind: Job\n", "  completionMode: Indexed\n",
          "  completions: 3\n", "  parallelism: 3\n", "      restartPolicy: Never\n",
          "              nvidia.com/gpu: 2\n", "            claimName: \"penumbra-data\"\n"})
        EXPECT_NE(k8s.find(line), std::string::npos) << line;
    EXPECT_NE(k8s.find("\"--task-count\", \"3\""), std::string::npos);
    EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
}
