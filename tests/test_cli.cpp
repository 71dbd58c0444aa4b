// The CLI contract of design.md §1: bad input gives one `error:` line, a non-zero exit code, no
// crash and no output; good input writes exactly the files the contract lists.
#include "core/image_io.h"
#include "process.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("penumbra-test-" + std::to_string(::getpid())) / name;
    fs::remove_all(p);
    fs::create_directories(p.parent_path());
    return p;
}

struct BadInput {
    const char* name;
    std::vector<std::string> args; // "{out}" is replaced by a fresh output path
    const char* expected;          // substring of the error line
};

class CliRefuses : public ::testing::TestWithParam<BadInput> {};

} // namespace

TEST_P(CliRefuses, WithOneErrorLineAndNoOutput) {
    const BadInput& bad = GetParam();
    const fs::path out = scratch(std::string("out-") + bad.name);
    std::vector<std::string> args;
    for (const std::string& a : bad.args)
        args.push_back(a == "{out}" ? out.string() : a);
    const ProcessResult r = runCli(args);
    EXPECT_GT(r.exitCode, 0) << "must fail cleanly (exit code -1 means it crashed)";
    // Exactly one line on stderr, and it is the error.
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "stderr:\n" << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(bad.expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "partial output left at " << out;
}

INSTANTIATE_TEST_SUITE_P(
    BadInputs, CliRefuses,
    ::testing::Values(
        BadInput{"unknown_technique",
                 {"render", "builtin:showcase", "-o", "{out}", "--technique", "blurry"},
                 "--technique: unknown technique 'blurry'"},
        BadInput{"unknown_set_key",
                 {"render", "builtin:showcase", "-o", "{out}", "--set", "pcf.colour=3"},
                 "unknown parameter 'pcf.colour'"},
        BadInput{"set_not_a_number",
                 {"render", "builtin:showcase", "-o", "{out}", "--set", "bias.slope=steep"},
                 "bias.slope=steep: not a finite number"},
        BadInput{"set_out_of_range",
                 {"render", "builtin:showcase", "-o", "{out}", "--set", "bias.normal=-2"},
                 "out of range"},
        BadInput{"set_without_value",
                 {"render", "builtin:showcase", "-o", "{out}", "--set", "bias.slope"},
                 "expected key=value"},
        BadInput{"shadow_map_zero",
                 {"render", "builtin:showcase", "-o", "{out}", "--shadow-map-size", "0"},
                 "--shadow-map-size"},
        BadInput{"shadow_map_past_limit",
                 {"render", "builtin:showcase", "-o", "{out}", "--shadow-map-size", "99999"},
                 "exceeds this device's maxImageDimension2D"},
        BadInput{
            "width_zero", {"render", "builtin:showcase", "-o", "{out}", "--width", "0"}, "--width"},
        BadInput{"height_zero",
                 {"render", "builtin:showcase", "-o", "{out}", "--height", "0"},
                 "--height"},
        BadInput{"width_negative",
                 {"render", "builtin:showcase", "-o", "{out}", "--width", "-4"},
                 "--width"},
        BadInput{"unknown_scene",
                 {"render", "builtin:nowhere", "-o", "{out}"},
                 "builtin:nowhere: no such built-in scene"},
        BadInput{"unknown_camera",
                 {"render", "builtin:showcase", "-o", "{out}", "--camera", "drone"},
                 "--camera"},
        BadInput{"frames_zero",
                 {"render", "builtin:showcase", "-o", "{out}", "--frames", "0"},
                 "--frames"},
        BadInput{"device_out_of_range",
                 {"render", "builtin:showcase", "-o", "{out}", "--device", "57"},
                 "--device: 57 is out of range"},
        BadInput{"output_unwritable",
                 {"render", "builtin:showcase", "-o", "/proc/penumbra-cannot-write"},
                 "/proc/penumbra-cannot-write"},
        BadInput{"output_under_a_file",
                 {"render", "builtin:showcase", "-o", "/etc/hostname/sub"},
                 "/etc/hostname"},
        BadInput{"no_output_option", {"render", "builtin:showcase"}, "--output"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(Cli, RenderWritesTheContractFiles) {
    const fs::path out = scratch("render-ok");
    const ProcessResult r =
        runCli({"render", "builtin:showcase", "-o", out.string(), "--width", "96", "--height", "64",
                "--shadow-map-size", "256", "--frames", "2", "--set", "bias.slope=1.5"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f :
         {"image.png", "visibility.pfm", "position.pfm", "normal.pfm", "stats.json"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(out))
        ++entries;
    EXPECT_EQ(entries, 5u) << "no staging leftovers";

    const PfmImage vis = readPfm(out / "visibility.pfm");
    EXPECT_EQ(vis.width, 96u);
    EXPECT_EQ(vis.height, 64u);
    EXPECT_EQ(vis.channels, 1u);
    // Rows are stored bottom to top; decoded top to bottom the sky (NaN) is first, ground last.
    EXPECT_TRUE(std::isnan(vis.pixels.front()));
    EXPECT_FALSE(std::isnan(vis.pixels.back()));
    const PfmImage pos = readPfm(out / "position.pfm");
    EXPECT_EQ(pos.channels, 3u);
    EXPECT_NEAR(pos.pixels[pos.pixels.size() - 2], 0.0f, 1e-3f); // bottom row lies on y = 0

    const auto stats = nlohmann::json::parse(slurp(out / "stats.json"));
    EXPECT_EQ(stats["technique"], "hard");
    EXPECT_EQ(stats["image"]["width"], 96);
    EXPECT_DOUBLE_EQ(stats["parameters"]["bias.slope"].get<double>(), 1.5);
    for (const char* pass : {"shadow", "gbuffer", "visibility", "composite"}) {
        ASSERT_TRUE(stats["gpu_ms"].contains(pass)) << pass;
        EXPECT_GT(stats["gpu_ms"][pass].get<double>(), 0.0) << pass;
        EXPECT_EQ(stats["gpu_ms_per_frame"][pass].size(), 2u);
    }
    EXPECT_EQ(stats["lights"][0]["visibility_file"], "visibility.pfm");
    EXPECT_NE(r.out.find("GPU ms per pass"), std::string::npos);
}

TEST(Cli, TechniquesListsEveryParameterWithRange) {
    const ProcessResult r = runCli({"techniques", "--json"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_FALSE(j.empty());
    EXPECT_EQ(j[0]["name"], "hard");
    bool sawSlope = false;
    for (const auto& p : j[0]["parameters"])
        if (p["key"] == "bias.slope") {
            sawSlope = true;
            EXPECT_TRUE(p.contains("default") && p.contains("min") && p.contains("max"));
        }
    EXPECT_TRUE(sawSlope);
}

TEST(Cli, InfoNamesTheDevice) {
    const ProcessResult r = runCli({"info"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("maxImageDimension2D"), std::string::npos);
    EXPECT_NE(r.out.find("[default]"), std::string::npos);
}
