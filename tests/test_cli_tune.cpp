// `penumbra tune`: the sweep against the truth, its files, its recommendation (which, applied
// through `compare`, reproduces its numbers and is never worse than the defaults), and its
// refusals.
#include "process.h"
#include "scratch_dir.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    return outputScratch(name);
}

double objective(const nlohmann::json& c) {
    return c["acne_beyond_blur"].get<double>() + c["leak_beyond_blur"].get<double>();
}

const std::vector<std::string> kView{"--width",   "120", "--height",          "68",
                                     "--samples", "4",   "--shadow-map-size", "512"};

// Without bias the grazing box's ground shows acne: a sweep of bias.constant and the mode has a
// best setting to find.
TEST(CliTune, RecommendsTheLeastAcneAndLeakAndCompareReproducesIt) {
    const fs::path dir = scratch("tune");
    std::vector<std::string> args{"tune",        "builtin:grazing",
                                  "--technique", "pcf[box3]",
                                  "-o",          dir.string(),
                                  "--set",       "bias.mode=fixed",
                                  "--set",       "bias.receiver=off",
                                  "--set",       "bias.constant=0",
                                  "--set",       "bias.slope=0",
                                  "--set",       "bias.normal=0",
                                  "--sweep",     "bias.constant=0,0.0001,0.001,0.01",
                                  "--sweep",     "bias.mode=fixed,adaptive"};
    args.insert(args.end(), kView.begin(), kView.end());
    const ProcessResult r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("[8/8]"), std::string::npos) << r.err; // progress, one line a setting
    const auto j = nlohmann::json::parse(slurp(dir / "tune.json"));
    EXPECT_EQ(j["technique"], "pcf[box3]");
    EXPECT_EQ(j["scene"], "builtin:grazing");
    EXPECT_EQ(j["samples"], 4);
    const auto& c = j["candidates"];
    // The defaults (bias.constant=0 fixed, given by --set), then every other combination.
    ASSERT_EQ(c.size(), 8u) << j.dump(1);
    EXPECT_TRUE(c[0]["defaults"].get<bool>());
    EXPECT_EQ(c[0]["set"].get<std::string>(), "");
    EXPECT_EQ(j["defaults"], 0);
    size_t best = 0, front = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        if (objective(c[i]) < objective(c[best]))
            best = i;
        front += c[i]["front"].get<bool>();
        // Nobody on the front is beaten on both counts by anybody.
        if (c[i]["front"].get<bool>()) {
            for (const auto& o : c)
                EXPECT_FALSE(o["acne_beyond_blur"] < c[i]["acne_beyond_blur"] &&
                             o["leak_beyond_blur"] < c[i]["leak_beyond_blur"]);
        }
    }
    EXPECT_GE(front, 1u);
    // Within a hundredth of a percent of the least acne + leak, never above the defaults', and
    // the lowest RMSE of those.
    const auto& rec = j["recommended"]["metrics"];
    EXPECT_LE(objective(rec), objective(c[best]) + 1e-4);
    EXPECT_LE(objective(rec), objective(c[0]));
    for (const auto& o : c) {
        if (objective(o) <= std::min(objective(c[best]) + 1e-4, objective(c[0]))) {
            EXPECT_LE(rec["rmse"].get<double>(), o["rmse"].get<double>());
        }
    }
    EXPECT_GT(objective(c[0]), 0.0) << "no acne to remove: the test sees nothing";
    const std::string set = j["recommended"]["set"];
    EXPECT_NE(r.out.find("recommended: " + (set.empty() ? "the defaults" : set)), std::string::npos)
        << r.out;
    const std::string html = slurp(dir / "tune.html");
    EXPECT_NE(html.find("<svg"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos); // self-contained
    EXPECT_EQ(std::count(html.begin(), html.end(), '\n') > 0, true);

    // Applied through compare, the recommendation reads the same acne and leak beyond blur.
    const fs::path check = scratch("tune-check");
    std::vector<std::string> compare{
        "compare",      "builtin:grazing",   "-o",    check.string(),
        "--techniques", "pcf[box3]",         "--set", "bias.mode=fixed",
        "--set",        "bias.receiver=off", "--set", "bias.constant=0",
        "--set",        "bias.slope=0",      "--set", "bias.normal=0"};
    compare.insert(compare.end(), kView.begin(), kView.end());
    std::istringstream words(set);
    for (std::string w; words >> w;)
        compare.push_back(w);
    const ProcessResult cr = runCli(compare);
    ASSERT_EQ(cr.exitCode, 0) << cr.err;
    const auto m = nlohmann::json::parse(slurp(check / "metrics.json"))["techniques"]["pcf[box3]"];
    EXPECT_DOUBLE_EQ(objective(m), objective(j["recommended"]["metrics"]));
}

TEST(CliTune, RefusesBadOptionsBeforeRunning) {
    const fs::path dir = scratch("tune-bad");
    for (const auto& [extra, subject] :
         std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"--technique", "nope"}, "error: --technique"},
             {{"--technique", "pcf[nope]"}, "error: --technique"},
             {{"--technique", "hard", "--sweep", "bias.constant=1"}, "error: --sweep"},
             {{"--technique", "hard", "--sweep", "bias.nope=1"}, "error: --sweep"},
             {{"--technique", "hard", "--modes", "fixed,sometimes"}, "error: --modes"},
             {{"--technique", "hard", "--set", "bias.mode=never"}, "error: --set"},
             {{"--technique", "hard", "--samples", "0"}, "error: --samples"}}) {
        std::vector<std::string> args{"tune", "builtin:showcase", "-o", dir.string()};
        args.insert(args.end(), extra.begin(), extra.end());
        args.insert(args.end(), {"--width", "120", "--height", "68"});
        const ProcessResult r = runCli(args);
        EXPECT_NE(r.exitCode, 0) << extra.back();
        EXPECT_EQ(r.err.rfind(subject, 0), 0u) << r.err;
        EXPECT_FALSE(fs::exists(dir)) << extra.back();
    }
    // --technique is required.
    const ProcessResult r = runCli({"tune", "builtin:showcase", "-o", dir.string()});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
}

} // namespace
