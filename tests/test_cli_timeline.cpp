// `compare --timeline` (issue 59): each frame of an animated asset posed, rendered and traced.
// Each frame's metrics are the ones `compare --time T` measures on the same pose; a still scene
// has no flicker; a moving box takes the pixels its shadow crosses out of flicker's count.
#include "cli_refusal.h"
#include "process.h"
#include "scratch_dir.h"
#include "sliding_box.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

const std::vector<std::string> kView = {"--camera-pos",      "0,9,9",
                                        "--look-at",         "0,0,0",
                                        "--width",           "64",
                                        "--height",          "48",
                                        "--shadow-map-size", "256",
                                        "--samples",         "4",
                                        "--techniques",      "hard,pcf[box3]",
                                        "--format",          "pfm"};

J compareJson(const fs::path& asset, const fs::path& out, std::vector<std::string> extra,
              const char* file) {
    std::vector<std::string> args = {"compare", asset.string(), "-o", out.string()};
    args.insert(args.end(), kView.begin(), kView.end());
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return J::parse(slurp(out / file));
}

} // namespace

TEST(CliTimeline, EachFrameMeasuresAsCompareAtThatTimeAndFlickerAddsUpOverFramePairs) {
    const fs::path dir = outputScratch("timeline");
    const fs::path moving = boxAsset(dir / "moving", true);
    // Frames 0, 1, 2: the box moves between the first two, then holds.
    const J whole = compareJson(moving, dir / "out", {"--timeline", "0:2:1"}, "timeline.json");
    EXPECT_EQ(whole["times"], J({0.0, 1.0, 2.0}));
    ASSERT_EQ(whole["rows"].size(), 2u);
    // The frame at 1 s is what compare --time 1 measures.
    const J atOne = compareJson(moving, dir / "at-one", {"--time", "1"}, "metrics.json");
    const J pose = J::parse(slurp(dir / "at-one" / "hard.stats.json"))["scene"];
    EXPECT_EQ(pose["time"], 1.0);
    EXPECT_EQ(pose["animation"], "slide");
    EXPECT_EQ(pose["animation_duration"], 1.0);
    for (const char* row : {"hard", "pcf[box3]"}) {
        const J& r = whole["rows"][row];
        ASSERT_EQ(r["rmse"].size(), 3u) << row;
        EXPECT_DOUBLE_EQ(r["rmse"][1].get<double>(), atOne["techniques"][row]["rmse"].get<double>())
            << row;
        EXPECT_DOUBLE_EQ(r["leak"][1].get<double>(), atOne["techniques"][row]["leak"].get<double>())
            << row;
        EXPECT_GT(r["gpu_ms"][1].get<double>(), 0.0) << row;
        EXPECT_NE(r["rmse"][0], r["rmse"][1]) << row << ": the box moved";
        EXPECT_EQ(r["rmse"][1], r["rmse"][2]) << row << ": the box held";
        const std::vector<double> rmse = r["rmse"];
        EXPECT_DOUBLE_EQ(r["rmse_over_time"]["mean"].get<double>(),
                         (rmse[0] + rmse[1] + rmse[2]) / 3.0)
            << row;
        EXPECT_EQ(r["rmse_over_time"]["max"].get<double>(), std::max({rmse[0], rmse[1], rmse[2]}))
            << row;
        // Neither keeps anything between frames: in motion each frame is the one at rest, and
        // so is the flicker as played.
        EXPECT_EQ(r["rmse_moving"], r["rmse"]) << row;
        EXPECT_EQ(r["flicker_moving"], r["flicker"]) << row;
        EXPECT_EQ(r["flicker_moving_pixels"], r["flicker_pixels"]) << row;
        EXPECT_EQ(r["pop_in"].get<double>(), 0.0) << row;
        EXPECT_EQ(r["pop_in_ratio"].get<double>(), 1.0) << row;
        EXPECT_EQ(r["lag_frames"].get<size_t>(), 0u) << row;
        ASSERT_EQ(r["gpu_ms_moving"].size(), 3u) << row;
        EXPECT_GT(r["gpu_ms_moving"][2].get<double>(), 0.0) << row;
    }
    // The report plots each row's RMSE over time and says its flicker.
    const std::string report = slurp(dir / "out" / "report.html");
    for (const char* row : {"hard", "pcf[box3]"}) {
        const J& r = whole["rows"][row];
        EXPECT_NE(
            report.find(fmt::format("{} at 1 s: {:.6g}</title>", row, r["rmse"][1].get<double>())),
            std::string::npos)
            << row;
        EXPECT_NE(
            report.find(fmt::format("flicker {:.6f}; as played {:.6f};", r["flicker"].get<double>(),
                                    r["flicker_moving"].get<double>())),
            std::string::npos)
            << row;
    }
    // The usual outputs are the first frame's (the box off its rest place): compare --time 0's.
    const J first = J::parse(slurp(dir / "out" / "metrics.json"));
    const J atZero = compareJson(moving, dir / "at-zero", {"--time", "0"}, "metrics.json");
    EXPECT_DOUBLE_EQ(first["techniques"]["hard"]["rmse"].get<double>(),
                     atZero["techniques"]["hard"]["rmse"].get<double>());
    // One CSV line a frame and row.
    std::istringstream csv(slurp(dir / "out" / "timeline.csv"));
    std::string line;
    size_t lines = 0;
    while (std::getline(csv, line))
        ++lines;
    EXPECT_EQ(lines, 1u + 3u * 2u);

    // Flicker pools its frame pairs: the whole timeline's pixels and changes are those of its
    // halves. The second half stands still: no flicker, every lit pixel counted; the first
    // leaves out the pixels whose truth the moving box changed.
    const J moved = compareJson(moving, dir / "moved", {"--timeline", "0:1:1"}, "timeline.json");
    const J held = compareJson(moving, dir / "held", {"--timeline", "1:2:1"}, "timeline.json");
    for (const char* row : {"hard", "pcf[box3]"}) {
        const auto pixels = [&](const J& t) {
            return t["rows"][row]["flicker_pixels"].get<uint64_t>();
        };
        const auto change = [&](const J& t) {
            return t["rows"][row]["flicker"].get<double>() * double(pixels(t));
        };
        EXPECT_EQ(held["rows"][row]["flicker"].get<double>(), 0.0) << row;
        EXPECT_GT(pixels(held), pixels(moved)) << row;
        EXPECT_GT(pixels(moved), 0u) << row;
        EXPECT_EQ(pixels(whole), pixels(moved) + pixels(held)) << row;
        EXPECT_NEAR(change(whole), change(moved) + change(held), 1e-9 * double(pixels(whole)))
            << row;
    }
}

TEST(CliTimeline, TheAutomaticCameraAndLightOfTheFirstFrameHoldForAll) {
    const fs::path dir = outputScratch("timeline-automatic");
    const fs::path unlit = boxAsset(dir, true, /*lit=*/false);
    const auto measure = [&](const std::string& name, std::vector<std::string> extra,
                             const char* file) {
        std::vector<std::string> args = {"compare",      unlit.string(),
                                         "-o",           (dir / name).string(),
                                         "--width",      "64",
                                         "--height",     "48",
                                         "--samples",    "4",
                                         "--techniques", "pcf[box3]",
                                         "--format",     "pfm"};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = runCli(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return J::parse(slurp(dir / name / file));
    };
    // At 0.5 s the box (at x = 1.5) and its shadow are still in frame 0's view.
    const J timeline = measure("timeline", {"--timeline", "0:0.5:0.5"}, "timeline.json");
    const J atZero = measure("at-zero", {"--time", "0"}, "metrics.json");
    const J atHalf = measure("at-half", {"--time", "0.5"}, "metrics.json");
    const auto rmse = [](const J& metrics) {
        return metrics["techniques"]["pcf[box3]"]["rmse"].get<double>();
    };
    EXPECT_DOUBLE_EQ(timeline["rows"]["pcf[box3]"]["rmse"][0].get<double>(), rmse(atZero));
    // At 0.5 s on its own the box's bounds frame another view; in the timeline frame 0's holds.
    const double held = timeline["rows"]["pcf[box3]"]["rmse"][1].get<double>();
    EXPECT_GT(held, 0.0);
    EXPECT_NE(rmse(atZero), rmse(atHalf));
    EXPECT_NE(held, rmse(atHalf));
}

TEST(CliTimeline, AnOrbitingAddedLightMovesWithTheTimeOnAStillScene) {
    const fs::path out = outputScratch("orbit");
    const ProcessResult r =
        runCli({"render", "builtin:resting", "-o", out.string(), "--width", "64", "--height", "48",
                "--frames", "1", "--format", "pfm", "--time", "2", "--add-light",
                "point:pos=3,4,0,orbit=8,about=0,0,0,name=bulb"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("no animations"), std::string::npos) << r.err;
    const J stats = J::parse(slurp(out / "stats.json"));
    EXPECT_EQ(stats["scene"]["time"], 2.0);
    bool found = false;
    for (const J& light : stats["lights"])
        if (light["name"] == "bulb") {
            found = true;
            const std::vector<double> p = light["position"];
            EXPECT_NEAR(p[0], 0.0, 1e-5);
            EXPECT_NEAR(p[1], 4.0, 1e-5);
            EXPECT_NEAR(p[2], -3.0, 1e-5) << "a quarter of the 8-second turn";
        }
    EXPECT_TRUE(found) << stats["lights"].dump();
}

TEST(CliTimeline, TheReferenceRecordsThePose) {
    const fs::path out = outputScratch("reference-pose");
    const ProcessResult r =
        runCli({"reference", "builtin:pendulum", "-o", out.string(), "--width", "32", "--height",
                "24", "--samples", "1", "--format", "pfm", "--time", "0.5"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const J info = J::parse(slurp(out / "reference.json"));
    EXPECT_EQ(info["time"], 0.5);
    EXPECT_EQ(info["animation"], "swing");
    EXPECT_EQ(info["animation_duration"], 2.0);
    // --time -0 is 0 s, written as such.
    const fs::path zero = outputScratch("reference-minus-zero");
    const ProcessResult z =
        runCli({"reference", "builtin:pendulum", "-o", zero.string(), "--width", "16", "--height",
                "12", "--samples", "1", "--format", "pfm", "--time", "-0"});
    ASSERT_EQ(z.exitCode, 0) << z.err;
    const std::string written = slurp(zero / "reference.json");
    EXPECT_EQ(written.find("-0.0"), std::string::npos) << written;
    EXPECT_FALSE(std::signbit(J::parse(written)["time"].get<double>()));
}

TEST(CliTimeline, AStillSceneIsWarnedOnceHasNoFlickerAndItsTimesAreWrittenAsTyped) {
    const fs::path dir = outputScratch("timeline-still");
    const fs::path still = boxAsset(dir, false);
    std::vector<std::string> args = {"compare", still.string(), "-o", (dir / "out").string()};
    args.insert(args.end(), kView.begin(), kView.end());
    args.insert(args.end(), {"--timeline", "0:0.3:0.1"});
    const ProcessResult r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string warning = "the scene has no animations; it is drawn at rest";
    const size_t at = r.err.find(warning);
    EXPECT_NE(at, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(warning, at + 1), std::string::npos) << "warned twice:\n" << r.err;
    const J timeline = J::parse(slurp(dir / "out" / "timeline.json"));
    EXPECT_EQ(timeline["times"], J({0.0, 0.1, 0.2, 0.3}));
    // The CSV: its header, then each frame's rows with the JSON's values in the header's order.
    std::istringstream csv(slurp(dir / "out" / "timeline.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "time,row,rmse,mae,acne,leak,gpu_ms,rmse_moving,gpu_ms_moving");
    std::vector<std::string> lines;
    while (std::getline(csv, line))
        lines.push_back(line);
    ASSERT_EQ(lines.size(), 4u * 2u);
    for (const char* row : {"hard", "pcf[box3]"}) {
        const J& measured = timeline["rows"][row];
        EXPECT_EQ(measured["flicker"].get<double>(), 0.0) << row;
        EXPECT_GT(measured["flicker_pixels"].get<uint64_t>(), 0u) << row;
        const std::string want = fmt::format(
            "0.3,{},{},{},{},{},{},{},{}", row, measured["rmse"][3].get<double>(),
            measured["mae"][3].get<double>(), measured["acne"][3].get<double>(),
            measured["leak"][3].get<double>(), measured["gpu_ms"][3].get<double>(),
            measured["rmse_moving"][3].get<double>(), measured["gpu_ms_moving"][3].get<double>());
        EXPECT_NE(std::find(lines.begin(), lines.end(), want), lines.end()) << want;
    }
}

TEST(CliTimeline, AFrameRefusedAfterTheFirstNamesItselfAndLeavesNoOutput) {
    const fs::path dir = outputScratch("timeline-refused");
    J j = J::parse(slurp(boxAsset(dir, true)));
    // The spot (nodes[3]) shrinks to nothing over the first second: frame 3 of 0:1:0.5.
    const int shrink = floatAccessor(j, {1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f}, "VEC3");
    J& slide = j["animations"][0];
    slide["samplers"].push_back({{"input", slide["samplers"][0]["input"]}, {"output", shrink}});
    slide["channels"].push_back({{"sampler", 1}, {"target", {{"node", 3}, {"path", "scale"}}}});
    const fs::path file = dir / "shrinking.gltf";
    std::ofstream(file) << j.dump();
    const fs::path out = dir / "out";
    std::vector<std::string> args = {"compare", file.string(), "-o", out.string()};
    args.insert(args.end(), kView.begin(), kView.end());
    args.insert(args.end(), {"--timeline", "0:1:0.5"});
    const ProcessResult r = runCli(args);
    EXPECT_GT(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("error: " + file.string() +
                         ": nodes[3]: KHR_lights_punctual.lights[1] has no direction: its node's "
                         "transform is scaled to zero at time 1 s (--timeline frame 3 of 3, at "
                         "1 s)\n"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out));
    // render --fps names the frame the same way.
    const fs::path played = dir / "played";
    const ProcessResult p = runCli({"render", file.string(), "-o", played.string(), "--width", "32",
                                    "--height", "24", "--fps", "2", "--frames", "3"});
    EXPECT_GT(p.exitCode, 0) << p.err;
    EXPECT_NE(p.err.find("at time 1 s (--fps frame 3 of 3, at 1 s)\n"), std::string::npos) << p.err;
    EXPECT_FALSE(fs::exists(played));
}

namespace {

class CliTimeRefuses : public ::testing::TestWithParam<BadInput> {};

} // namespace

TEST_P(CliTimeRefuses, WithOneErrorLineAndNoOutput) {
    expectOneErrorLineAndNoOutput(GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    TimeInputs, CliTimeRefuses,
    ::testing::Values(
        BadInput{"time_negative",
                 {"render", "builtin:showcase", "-o", "{out}", "--time", "-2"},
                 "error: --time: -2 is not a time in seconds from 0 (a finite number, not "
                 "negative)"},
        BadInput{"time_not_a_number",
                 {"compare", "builtin:showcase", "-o", "{out}", "--time", "soon"},
                 "error: --time: 'soon' is not a time in seconds (a decimal number)"},
        BadInput{"time_in_hex",
                 {"render", "builtin:pendulum", "-o", "{out}", "--time", "0x10"},
                 "error: --time: '0x10' is not a time in seconds (a decimal number)"},
        BadInput{"time_empty",
                 {"render", "builtin:pendulum", "-o", "{out}", "--time", ""},
                 "error: --time: '' is not a time in seconds (a decimal number)"},
        BadInput{
            "animation_index_with_a_tail",
            {"render", "builtin:pendulum", "-o", "{out}", "--time", "1", "--animation", "0abc"},
            "error: --animation: 'builtin:pendulum' has one animation, 0 'swing'"},
        BadInput{"animation_index_past_the_last",
                 {"render", "builtin:pendulum", "-o", "{out}", "--animation", "1"},
                 "error: --animation: 'builtin:pendulum' has one animation, 0 'swing'"},
        BadInput{"animation_of_a_still_scene",
                 {"reference", "builtin:showcase", "-o", "{out}", "--animation", "walk"},
                 "error: --animation: 'builtin:showcase' has no animations"},
        BadInput{"timeline_empty",
                 {"compare", "builtin:pendulum", "-o", "{out}", "--timeline", ""},
                 "error: --timeline: '' is not a timeline START:END:STEP"},
        BadInput{"fps_empty",
                 {"render", "builtin:pendulum", "-o", "{out}", "--fps", ""},
                 "error: --fps: '' is not a rate in frames a second"},
        BadInput{"timeline_of_two_numbers",
                 {"compare", "builtin:showcase", "-o", "{out}", "--timeline", "0:1"},
                 "error: --timeline: '0:1' is not START:END:STEP in seconds"},
        BadInput{"timeline_backwards",
                 {"compare", "builtin:showcase", "-o", "{out}", "--timeline", "2:1:0.5"},
                 "error: --timeline: '2:1:0.5': START must be 0 or more, END at least START and "
                 "STEP above 0"},
        BadInput{"timeline_without_a_step",
                 {"compare", "builtin:showcase", "-o", "{out}", "--timeline", "0:1:0"},
                 "STEP above 0"},
        BadInput{"timeline_not_numbers",
                 {"compare", "builtin:showcase", "-o", "{out}", "--timeline", "0:one:0.5"},
                 "error: --timeline: '0:one:0.5' is not START:END:STEP in seconds ('one' is not a "
                 "finite number)"},
        BadInput{"timeline_starting_before_zero",
                 {"compare", "builtin:pendulum", "-o", "{out}", "--timeline=-1:1:0.5"},
                 "error: --timeline: '-1:1:0.5': START must be 0 or more"},
        BadInput{"timeline_too_long",
                 {"compare", "builtin:showcase", "-o", "{out}", "--timeline", "0:100:0.001"},
                 "error: --timeline: '0:100:0.001' is 100001 frames; at most 10000"},
        BadInput{
            "timeline_with_time",
            {"compare", "builtin:showcase", "-o", "{out}", "--timeline", "0:1:0.5", "--time", "1"},
            "--timeline"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

// In motion each frame continues the last one. Virtual pages are asked for by the frame before,
// so under a light that orbits a frame reads pages placed for the light's last position (coarser
// ones where those are missing): the frames in motion lag behind the ones at rest. The same row
// without virtual maps keeps nothing between frames and draws both alike.
TEST(CliTimeline, VirtualPagesLagBehindAnOrbitingLightAndPlainMapsDoNot) {
    const fs::path dir = outputScratch("timeline-lag");
    const auto timeline = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args = {
            "compare",      "builtin:resting",
            "-o",           (dir / name).string(),
            "--width",      "128",
            "--height",     "96",
            "--samples",    "4",
            "--format",     "pfm",
            "--techniques", "pcf[box3]",
            "--timeline",   "0:1:0.25",
            "--add-light",  "point:pos=2,3,0,orbit=4,about=0,0,0,name=bulb"};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = runCli(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return J::parse(slurp(dir / name / "timeline.json"))["rows"]["pcf[box3]"];
    };
    const J plain = timeline("plain", {});
    EXPECT_EQ(plain["rmse_moving"], plain["rmse"]);
    EXPECT_EQ(plain["flicker_moving"], plain["flicker"]);
    EXPECT_EQ(plain["lag_frames"], 0);
    EXPECT_EQ(plain["pop_in"], 0.0);
    EXPECT_FALSE(plain.contains("pages_moving")) << "no virtual map, no pages";
    const J paged = timeline("paged", {"--set", "virtual.enabled=1"});
    // Pages per frame in motion: the first frame starts at rest, its pages all cached; each
    // later one renders again the moved bulb's pages the frame before asked for, and no more.
    const J pages = paged["pages_moving"];
    for (const char* field : {"requested", "rendered", "resident"})
        ASSERT_EQ(pages[field].size(), 5u) << pages.dump();
    EXPECT_EQ(pages["rendered"][0].get<int>(), 0) << pages.dump();
    EXPECT_EQ(pages["requested"][0], pages["resident"][0]) << "a fresh pool holds what was asked";
    for (size_t k = 0; k < 5; ++k) {
        const int rendered = pages["rendered"][k].get<int>();
        EXPECT_TRUE(k == 0 || rendered > 0) << pages.dump();
        EXPECT_LE(rendered, pages["requested"][k].get<int>()) << pages.dump();
        EXPECT_LT(rendered, pages["resident"][k].get<int>()) << "the sun's pages stay";
    }
    const std::vector<double> rest = paged["rmse"], moving = paged["rmse_moving"];
    ASSERT_EQ(moving.size(), 5u);
    EXPECT_EQ(moving[0], rest[0]) << "the motion starts at rest";
    // Played, each frame reads the pages the frame before placed: its changes are not the
    // poses' at rest (over the same pixels: the truth and the masks are the same).
    EXPECT_NE(paged["flicker_moving"].get<double>(), paged["flicker"].get<double>());
    EXPECT_EQ(paged["flicker_moving_pixels"], paged["flicker_pixels"]);
    EXPECT_GT(paged["flicker_moving"].get<double>(), 0.0);
    EXPECT_NE(slurp(dir / "paged" / "report.html")
                  .find(fmt::format("as played {:.6f};", paged["flicker_moving"].get<double>())),
              std::string::npos);
    double most = 0.0;
    for (size_t k = 1; k < 5; ++k)
        most = std::max(most, moving[k] - rest[k]);
    std::printf("virtual pcf[box3]: pop-in %.5f (ratio %.3f), lag %d frames\n",
                paged["pop_in"].get<double>(), paged["pop_in_ratio"].get<double>(),
                paged["lag_frames"].get<int>());
    EXPECT_GT(most, 0.0);
    EXPECT_DOUBLE_EQ(paged["pop_in"].get<double>(), most);
    EXPECT_GE(paged["lag_frames"].get<int>(), 1);
    EXPECT_GE(paged["lagging_frames"].get<int>(), paged["lag_frames"].get<int>());
    EXPECT_GT(paged["pop_in_ratio"].get<double>(), 1.1);
    EXPECT_EQ(paged["rmse_moving_over_time"]["max"].get<double>(),
              *std::max_element(moving.begin(), moving.end()));
    // The CSV's frame at 0.25 s: its rest and motion columns where the header says.
    std::istringstream csv(slurp(dir / "paged" / "timeline.csv"));
    std::string line;
    std::vector<std::string> header, atQuarter;
    const auto split = [](const std::string& s) {
        std::vector<std::string> fields;
        std::istringstream in(s);
        for (std::string f; std::getline(in, f, ',');)
            fields.push_back(f);
        return fields;
    };
    std::getline(csv, line);
    header = split(line);
    while (std::getline(csv, line))
        if (line.rfind("0.25,", 0) == 0)
            atQuarter = split(line);
    ASSERT_EQ(atQuarter.size(), header.size()) << line;
    const auto column = [&](const char* name) {
        return std::stod(
            atQuarter[size_t(std::find(header.begin(), header.end(), name) - header.begin())]);
    };
    EXPECT_EQ(column("rmse"), rest[1]);
    EXPECT_EQ(column("rmse_moving"), moving[1]);
    EXPECT_EQ(column("gpu_ms_moving"), paged["gpu_ms_moving"][1].get<double>());
}

// Every command that renders many frames quietly says a pool too small for them once, after
// them (per row where it has rows): compare --timeline and --camera-path, and bench per run.
TEST(CliTimeline, APoolTooSmallIsSaidOnceByEveryCommandOfManyFrames) {
    const fs::path dir = outputScratch("small-pool-commands");
    const std::vector<std::string> small = {"--set",    "virtual.enabled=1",
                                            "--set",    "virtual.pageSize=32",
                                            "--set",    "virtual.poolSize=256",
                                            "--width",  "64",
                                            "--height", "48"};
    const auto run = [&](std::vector<std::string> args) {
        args.insert(args.end(), small.begin(), small.end());
        const ProcessResult r = runCli(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return r.err;
    };
    const auto times = [](const std::string& text, const std::string& what) {
        size_t n = 0;
        for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
            ++n;
        return n;
    };
    const std::string pool = "the virtual pool holds 64 pages; ";
    const std::string timeline =
        run({"compare", "builtin:walker", "-o", (dir / "timeline").string(), "--samples", "1",
             "--format", "pfm", "--techniques", "hard,pcf[box3]", "--timeline", "0:0.1:0.05"});
    EXPECT_EQ(times(timeline, "warning: hard: " + pool), 1u) << timeline;
    EXPECT_EQ(times(timeline, "warning: pcf[box3]: " + pool), 1u) << timeline;
    // Every frame a row rendered counts: each of the three still ones (a fresh render: its
    // second warm-up and its frame at least) and the three in motion.
    const size_t said = timeline.find("warning: hard: " + pool);
    unsigned frames = 0, rendered = 0;
    ASSERT_NE(said, std::string::npos);
    ASSERT_EQ(std::sscanf(timeline.c_str() + said + ("warning: hard: " + pool).size(),
                          "%u of %u frames (warm-ups included) asked for more", &frames, &rendered),
              2)
        << timeline;
    EXPECT_GE(frames, 2u * 3u + 3u) << timeline;
    EXPECT_LE(frames, rendered) << timeline;
    // Said for the row once: not also for the view the timeline starts from.
    EXPECT_EQ(times(timeline, pool), 2u) << timeline;
    const std::string path = run({"compare", "builtin:field", "-o", (dir / "path").string(),
                                  "--samples", "1", "--format", "pfm", "--techniques", "hard",
                                  "--camera-path", "dolly", "--path-frames", "3"});
    EXPECT_EQ(times(path, "warning: hard: " + pool), 1u) << path;
    EXPECT_EQ(times(path, pool), 1u) << path;
    const std::string bench = run({"bench", "builtin:field", "-o", (dir / "bench.json").string(),
                                   "--techniques", "hard,pcf", "--frames", "2"});
    EXPECT_EQ(times(bench, "warning: " + pool), 2u) << bench;
    // A roomy pool says nothing.
    const ProcessResult roomy =
        runCli({"compare", "builtin:walker", "-o", (dir / "roomy").string(), "--samples", "1",
                "--format", "pfm", "--techniques", "hard", "--timeline", "0:0.1:0.05", "--width",
                "64", "--height", "48", "--set", "virtual.enabled=1"});
    EXPECT_EQ(roomy.exitCode, 0) << roomy.err;
    EXPECT_EQ(roomy.err.find("virtual pool"), std::string::npos) << roomy.err;
}

// Only a camera Penumbra framed is held at the first frame's: the file's own camera moves with
// its node in a timeline as at --time, whatever its name ("autocam" is not "auto").
TEST(CliTimeline, AFilesOwnCameraMovesWithItsNodeWhateverItsName) {
    const fs::path dir = outputScratch("timeline-autocam");
    J j = J::parse(slurp(boxAsset(dir / "asset", true)));
    j["cameras"] = J::array({{{"name", "autocam"},
                              {"type", "perspective"},
                              {"perspective", {{"yfov", 0.8}, {"znear", 0.05}}}}});
    j["nodes"].push_back({{"name", "eye"},
                          {"camera", 0},
                          {"translation", {0.0, 6.0, 9.0}},
                          {"rotation", {-0.2588, 0.0, 0.0, 0.9659}}});
    const size_t eye = j["nodes"].size() - 1;
    j["scenes"][0]["nodes"].push_back(eye);
    J& slide = j["animations"][0];
    const int path = floatAccessor(j, {0.0f, 6.0f, 9.0f, 2.0f, 6.0f, 9.0f}, "VEC3");
    slide["samplers"].push_back({{"input", slide["samplers"][0]["input"]}, {"output", path}});
    slide["channels"].push_back(
        {{"sampler", 1}, {"target", {{"node", eye}, {"path", "translation"}}}});
    const fs::path file = dir / "autocam.gltf";
    std::ofstream(file) << j.dump();
    const auto measure = [&](const std::string& name, const std::string& option,
                             const std::string& value, const char* json) {
        const ProcessResult r =
            runCli({"compare", file.string(), "-o", (dir / name).string(), "--width", "64",
                    "--height", "48", "--samples", "4", "--techniques", "pcf[box3]", "--format",
                    "pfm", option, value});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return J::parse(slurp(dir / name / json));
    };
    const J timeline = measure("timeline", "--timeline", "0:1:1", "timeline.json");
    const J atOne = measure("at-one", "--time", "1", "metrics.json");
    const J atZero = measure("at-zero", "--time", "0", "metrics.json");
    const auto rmse = [](const J& m) { return m["techniques"]["pcf[box3]"]["rmse"].get<double>(); };
    EXPECT_NE(rmse(atZero), rmse(atOne));
    EXPECT_DOUBLE_EQ(timeline["rows"]["pcf[box3]"]["rmse"][1].get<double>(), rmse(atOne));
}

// Rows whose renderers together pass the device's local memory (moment maps of 2048 for a
// sun's cascades and a bulb's six faces, the row's and the frame's own renderer): each keeps
// between frames only what its next frame reads, says so, and measures as before in motion;
// its time in motion is split by pass.
TEST(CliTimeline, RowsThatPassTheDevicesMemoryKeepOnlyWhatTheirNextFrameReads) {
    const fs::path dir = outputScratch("timeline-trimmed");
    const ProcessResult r =
        runCli({"compare", "builtin:walker", "-o", dir.string(), "--width", "64", "--height", "48",
                "--samples", "1", "--format", "pfm", "--techniques", "evsm", "--frames", "1",
                "--timeline", "0:0.25:0.25"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("each keeps between frames only what its next frame reads"),
              std::string::npos)
        << r.err;
    const J rows = J::parse(slurp(dir / "timeline.json"))["rows"];
    for (const std::string name : {"evsm"}) {
        EXPECT_EQ(rows[name]["rmse_moving"], rows[name]["rmse"]) << name;
        // In motion by pass: the skin pass only after the pose (the first frame placed it in
        // its warm-up), and the passes sum to each frame's time in motion.
        const J& byPass = rows[name]["gpu_ms_moving_by_pass"];
        ASSERT_TRUE(byPass.contains("skin")) << name;
        EXPECT_EQ(byPass["skin"][0].get<double>(), 0.0) << name;
        for (size_t k = 0; k < 2; ++k) {
            double sum = 0.0;
            for (const auto& [pass, times] : byPass.items()) {
                ASSERT_EQ(times.size(), 2u) << name << " " << pass;
                sum += times[k].get<double>();
            }
            EXPECT_NEAR(sum, rows[name]["gpu_ms_moving"][k].get<double>(), 1e-9) << name;
        }
    }
}
