// `compare --timeline` (issue 59): each frame of an animated asset posed, rendered and traced.
// Each frame's metrics are the ones `compare --time T` measures on the same pose; a still scene
// has no flicker; a moving box takes the pixels its shadow crosses out of flicker's count.
#include "process.h"
#include "scratch_dir.h"
#include "three_light_asset.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <sstream>

using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

// The ground and box under the three lights; `animated`: the box (nodes[1], at rest at the
// origin) slides from x = 0.5 to 2.5 in the first second, then holds.
fs::path boxAsset(const fs::path& where, bool animated) {
    const fs::path file = threeLightAsset(where);
    if (!animated)
        return file;
    J j = J::parse(slurp(file));
    // A second buffer, base64 in a data URI, holding the keyframes.
    std::vector<uint8_t> bytes;
    for (const float f : {0.0f, 1.0f, 0.5f, 0.0f, 0.0f, 2.5f, 0.0f, 0.0f}) {
        uint8_t b[4];
        std::memcpy(b, &f, 4);
        bytes.insert(bytes.end(), b, b + 4);
    }
    j["buffers"].push_back(
        {{"byteLength", bytes.size()},
         {"uri", "data:application/octet-stream;base64," + GltfBuilder::base64(bytes)}});
    const int buffer = static_cast<int>(j["buffers"].size()) - 1;
    const auto view = [&](int offset, int length) {
        j["bufferViews"].push_back(
            {{"buffer", buffer}, {"byteOffset", offset}, {"byteLength", length}});
        return static_cast<int>(j["bufferViews"].size()) - 1;
    };
    j["accessors"].push_back({{"bufferView", view(0, 8)},
                              {"componentType", 5126},
                              {"count", 2},
                              {"type", "SCALAR"},
                              {"min", {0.0}},
                              {"max", {1.0}}});
    j["accessors"].push_back(
        {{"bufferView", view(8, 24)}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
    const int n = static_cast<int>(j["accessors"].size());
    j["animations"] = {
        {{"name", "slide"},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}},
         {"samplers", {{{"input", n - 2}, {"output", n - 1}}}}}};
    std::ofstream(file) << j.dump();
    return file;
}

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
