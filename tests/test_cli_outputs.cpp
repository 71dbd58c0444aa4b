// What the commands write: `--format pfm|exr|both` (the float files of render and reference, for
// every light type, and the file stats.json names) and compare's report images at page size with
// the full-size files beside it.
#include "base64_decode.h"
#include "core/exr_io.h"
#include "core/image_io.h"
#include "float_images.h"
#include "process.h"
#include "scratch_dir.h"
#include "three_light_asset.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <utility>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

std::set<std::string> filesIn(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir))
        names.insert(e.path().filename().string());
    return names;
}

// A small view from above the box, so every light's shadow of it is seen.
const std::vector<std::string> kSmallView = {"--width",      "48",    "--height",  "32",
                                             "--camera-pos", "0,9,9", "--look-at", "0,0,0"};

// A PNG's width and height from its IHDR chunk (big-endian, bytes 16 to 23).
std::pair<uint32_t, uint32_t> pngSize(const std::vector<uint8_t>& png) {
    EXPECT_GE(png.size(), 24u);
    if (png.size() < 24)
        return {0, 0};
    const auto word = [&](size_t at) {
        return uint32_t{png[at]} << 24 | uint32_t{png[at + 1]} << 16 | uint32_t{png[at + 2]} << 8 |
               png[at + 3];
    };
    return {word(16), word(20)};
}

std::vector<std::string> withView(std::vector<std::string> args) {
    args.insert(args.end(), kSmallView.begin(), kSmallView.end());
    return args;
}

} // namespace

TEST(CliOutputs, ExrOnlyWritesNoPfmAndStatsNameTheExrFiles) {
    const fs::path asset = threeLightAsset(outputScratch("formats-asset"));
    const fs::path out = outputScratch("formats-exr");
    const ProcessResult r =
        runCli(withView({"render", asset.string(), "-o", out.string(), "--shadow-map-size", "128",
                         "--frames", "1", "--format", "exr"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(filesIn(out), (std::set<std::string>{"image.png", "visibility.exr",
                                                   "visibility_1.exr", "visibility_2.exr",
                                                   "position.exr", "normal.exr", "stats.json"}));
    const auto stats = nlohmann::json::parse(slurp(out / "stats.json"));
    ASSERT_EQ(stats["lights"].size(), 3u);
    for (size_t l = 0; l < 3; ++l) { // the sun's, the spot's and the bulb's
        const std::string name = stats["lights"][l]["visibility_file"];
        EXPECT_EQ(name, l == 0 ? "visibility.exr" : "visibility_" + std::to_string(l) + ".exr");
        const FloatImage v = readExr(out / name);
        EXPECT_EQ(v.width, 48u);
        EXPECT_EQ(v.height, 32u);
        EXPECT_EQ(v.channels, 1u);
        size_t lit = 0, shadowed = 0;
        for (float x : v.pixels)
            if (std::isfinite(x))
                (x > 0.5f ? lit : shadowed) += 1;
        EXPECT_GT(lit, 0u) << name;
        EXPECT_GT(shadowed, 0u) << name << ": the box's shadow";
    }
    EXPECT_EQ(readExr(out / "position.exr").channels, 3u);
}

TEST(CliOutputs, PfmOnlyAndTheReferencesExrMatchItsPfm) {
    const fs::path asset = threeLightAsset(outputScratch("formats-asset-2"));
    const fs::path pfm = outputScratch("formats-pfm");
    ProcessResult r = runCli(withView(
        {"reference", asset.string(), "-o", pfm.string(), "--samples", "4", "--format", "pfm"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(filesIn(pfm),
              (std::set<std::string>{"visibility.pfm", "visibility_1.pfm", "visibility_2.pfm",
                                     "position.pfm", "normal.pfm", "reference.json"}));
    // The default writes both; the truth is deterministic, so the OpenEXR files of a second run
    // hold the first run's PFM pixels bit for bit.
    const fs::path both = outputScratch("formats-both");
    r = runCli(withView({"reference", asset.string(), "-o", both.string(), "--samples", "4"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* stem : {"visibility", "visibility_1", "visibility_2", "position", "normal"}) {
        const std::string s = stem;
        expectSameImage(readPfm(pfm / (s + ".pfm")), readExr(both / (s + ".exr")), s);
        expectSameImage(readPfm(both / (s + ".pfm")), readExr(both / (s + ".exr")), s);
    }
}

// Translucent casters make the truth's visibility R, G, B (design.md), in both formats; an opaque
// scene's stays one channel.
TEST(CliOutputs, TheTruthThroughTranslucentCastersIsRgb) {
    for (const bool translucent : {true, false}) {
        const fs::path out = outputScratch(translucent ? "rgb-truth" : "grey-truth");
        const ProcessResult r =
            runCli({"reference", translucent ? "builtin:sheets" : "builtin:bleeding", "-o",
                    out.string(), "--width", "48", "--height", "32", "--samples", "4"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const FloatImage pfm = readPfm(out / "visibility.pfm");
        EXPECT_EQ(pfm.channels, translucent ? 3u : 1u);
        expectSameImage(pfm, readExr(out / "visibility.exr"), "visibility");
        size_t coloured = 0; // red and blue apart: light through a filter
        for (size_t i = 0; translucent && i + 2 < pfm.pixels.size(); i += 3)
            coloured += std::abs(pfm.pixels[i] - pfm.pixels[i + 2]) > 0.2f;
        EXPECT_EQ(coloured > 20, translucent) << coloured;
    }
}

// The translucent layer's render writes its light per channel as the truth does (R, G, B, red
// and blue apart where a filter tints), its luminance the visibility a grey row writes; without
// the layer, one channel. So do compare's rows.
TEST(CliOutputs, TheTranslucentLayerWritesRgb) {
    for (const char* method : {"moments", "off"}) {
        const bool on = std::string(method) != "off";
        const fs::path out = outputScratch(std::string("rgb-render-") + method);
        const ProcessResult r =
            runCli({"render", "builtin:sheets", "-o", out.string(), "--width", "48", "--height",
                    "32", "--shadow-map-size", "256", "--frames", "1", "--set",
                    std::string("translucent.method=") + method, "--technique", "hard"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const FloatImage pfm = readPfm(out / "visibility.pfm");
        EXPECT_EQ(pfm.channels, on ? 3u : 1u) << method;
        expectSameImage(pfm, readExr(out / "visibility.exr"), "visibility");
        size_t coloured = 0;
        for (size_t i = 0; on && i + 2 < pfm.pixels.size(); i += 3)
            coloured += std::abs(pfm.pixels[i] - pfm.pixels[i + 2]) > 0.2f;
        EXPECT_EQ(coloured > 20, on) << coloured;
    }
    const fs::path out = outputScratch("rgb-compare");
    const ProcessResult r =
        runCli({"compare", "builtin:sheets", "-o", out.string(), "--techniques",
                "hard,hard+translucent", "--width", "48", "--height", "32", "--shadow-map-size",
                "256", "--frames", "1", "--samples", "1", "--format", "pfm"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readPfm(out / "hard.visibility.pfm").channels, 1u);
    EXPECT_EQ(readPfm(out / "hard-translucent.visibility.pfm").channels, 3u);
    // Each row's error per channel against the coloured truth: the layer's below the grey row's.
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"))["techniques"];
    const auto grey = metrics["hard"]["rmse_per_channel"];
    const auto tinted = metrics["hard+translucent"]["rmse_per_channel"];
    ASSERT_EQ(grey.size(), 3u);
    ASSERT_EQ(tinted.size(), 3u);
    for (size_t c = 0; c < 3; ++c)
        EXPECT_LT(tinted[c].get<double>(), 0.5 * grey[c].get<double>()) << "channel " << c;
}

TEST(CliOutputs, WideComparisonsShowReducedImagesAndLinkTheFullSizeFiles) {
    // 1000 pixels across is past the page's 960: every image is shown at half size, and the
    // lit image and heat map link their full-size files, which compare writes beside the page.
    const fs::path out = outputScratch("wide-compare");
    const ProcessResult r =
        runCli({"compare", "builtin:showcase", "-o", out.string(), "--techniques", "hard",
                "--width", "1000", "--height", "24", "--shadow-map-size", "256", "--frames", "1",
                "--samples", "1", "--format", "pfm"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string fullSize = slurp(out / "hard.image.png");
    EXPECT_EQ(pngSize({fullSize.begin(), fullSize.end()}), std::make_pair(1000u, 24u));
    EXPECT_FALSE(fs::exists(out / "visibility.exr")) << "--format pfm";
    const std::string html = slurp(out / "report.html");
    EXPECT_NE(html.find("<main data-page-scale=\"2\">"), std::string::npos);
    for (const char* file : {"hard.image.png", "hard.heatmap.png"}) {
        EXPECT_NE(html.find(std::string("href=\"") + file + "\""), std::string::npos) << file;
        EXPECT_TRUE(fs::exists(out / file)) << file;
    }
    const std::string prefix = "src=\"data:image/png;base64,";
    size_t images = 0;
    for (size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at)) {
        at += prefix.size();
        const auto [width, height] =
            pngSize(decodeBase64(html.substr(at, html.find('"', at) - at)));
        EXPECT_EQ(width, 500u) << "image " << images;
        EXPECT_GE(height, 12u) << "image " << images; // heat maps add their legend below
        ++images;
    }
    EXPECT_EQ(images, 4u) << "the truth, and the row's lit image, visibility and heat map";
}

TEST(CliOutputs, RowsTheDeviceCannotHoldAreSkippedAndMarked) {
    // A device of 512 MiB (PENUMBRA_DEVICE_MEMORY: what the checks assume) and one 8192^2 map:
    // hard's 256 MiB of depth fits; vsm's two-moment map and its blur's do not.
    setenv("PENUMBRA_DEVICE_MEMORY", std::to_string(512u << 20).c_str(), 1);
    const fs::path out = outputScratch("skipped-rows");
    const std::vector<std::string> view = {
        "--width", "32",    "--height",      "24", "--frames", "1", "--shadow-map-size",
        "8192",    "--set", "csm.cascades=1"};
    std::vector<std::string> args = {"compare",      "builtin:showcase", "-o",        out.string(),
                                     "--techniques", "hard,vsm",         "--samples", "1"};
    args.insert(args.end(), view.begin(), view.end());
    ProcessResult r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("warning: vsm skipped: --shadow-map-size: vsm needs "), std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("vsm                    skipped: --shadow-map-size: vsm needs"),
              std::string::npos)
        << r.out;
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"))["techniques"];
    ASSERT_TRUE(metrics.contains("hard"));
    EXPECT_TRUE(metrics["hard"].contains("rmse"));
    ASSERT_TRUE(metrics.contains("vsm"));
    EXPECT_NE(metrics["vsm"]["skipped"].get<std::string>().find("a render may use 0.40 GiB"),
              std::string::npos)
        << metrics["vsm"];
    EXPECT_FALSE(fs::exists(out / "vsm.image.png"));
    const std::string html = slurp(out / "report.html");
    EXPECT_NE(html.find("<h2>Skipped rows</h2>"), std::string::npos);
    EXPECT_NE(html.find("<li><strong>vsm</strong>: --shadow-map-size: vsm needs"),
              std::string::npos);
    EXPECT_EQ(html.find("data-technique=\"vsm\""), std::string::npos) << "no table row, no image";

    // bench the same: the run that fits is timed, the other marked.
    args = {"bench",        "builtin:showcase", "-o", (out / "bench.json").string(),
            "--techniques", "hard,vsm"};
    args.insert(args.end(), view.begin(), view.end());
    r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const size_t vsmLine = r.out.find("[2/2] vsm");
    ASSERT_NE(vsmLine, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("[2/2] vsm", vsmLine + 1), std::string::npos)
        << r.out << "one line for the skipped run, no timing";
    const auto runs = nlohmann::json::parse(slurp(out / "bench.json"))["runs"];
    ASSERT_EQ(runs.size(), 2u);
    EXPECT_TRUE(runs[0].contains("gpu_ms_total")) << runs[0];
    EXPECT_NE(runs[1]["skipped"].get<std::string>().find("vsm needs"), std::string::npos);
    EXPECT_NE(slurp(out / "bench.html").find("skipped: --shadow-map-size: vsm needs"),
              std::string::npos);

    // When no row fits, it is the error it always was.
    args = {"compare", "builtin:showcase", "-o", (out / "none").string(), "--techniques", "vsm"};
    args.insert(args.end(), view.begin(), view.end());
    r = runCli(args);
    unsetenv("PENUMBRA_DEVICE_MEMORY");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("error: --shadow-map-size: vsm needs"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out / "none"));
}

// Skipped rows first, in the middle and last: every row that is kept renders with its own
// options (its technique and parameters in its stats.json, its own image), in the order asked.
TEST(CliOutputs, RowsSkippedAnywhereLeaveTheOthersTheirOwnOptions) {
    setenv("PENUMBRA_DEVICE_MEMORY", std::to_string(512u << 20).c_str(), 1);
    const fs::path out = outputScratch("skipped-anywhere");
    // vsm, evsm and msm need moment maps of 8192^2 the 512 MiB device cannot hold; hard and pcf
    // read the depth map alone.
    const ProcessResult r = runCli({"compare",
                                    "builtin:showcase",
                                    "-o",
                                    out.string(),
                                    "--techniques",
                                    "vsm,hard,evsm,pcf[box7],msm",
                                    "--samples",
                                    "1",
                                    "--width",
                                    "32",
                                    "--height",
                                    "24",
                                    "--frames",
                                    "1",
                                    "--shadow-map-size",
                                    "8192",
                                    "--set",
                                    "csm.cascades=1",
                                    "--set",
                                    "bias.constant=0.003"});
    unsetenv("PENUMBRA_DEVICE_MEMORY");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* skipped : {"vsm", "evsm", "msm"}) {
        EXPECT_NE(r.err.find(std::string("warning: ") + skipped + " skipped: "), std::string::npos)
            << skipped << "\n"
            << r.err;
        EXPECT_FALSE(fs::exists(out / (std::string(skipped) + ".image.png"))) << skipped;
    }
    for (const auto& [file, technique] : {std::pair{"hard", "hard"}, {"pcf-box7", "pcf"}}) {
        const auto stats = nlohmann::json::parse(slurp(out / (std::string(file) + ".stats.json")));
        EXPECT_EQ(stats["technique"], technique);
        EXPECT_EQ(stats["shadow_map_size"], 8192);
        EXPECT_FLOAT_EQ(stats["parameters"]["bias.constant"].get<float>(), 0.003f);
        EXPECT_TRUE(fs::exists(out / (std::string(file) + ".image.png"))) << file;
    }
    const auto pcf = nlohmann::json::parse(slurp(out / "pcf-box7.stats.json"))["parameters"];
    EXPECT_EQ(pcf["pcf.filter"], "box");
    EXPECT_EQ(pcf["pcf.size"], 7.0);
    // The table keeps the order asked: rows, then the skipped ones.
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"))["techniques"];
    for (const char* row : {"vsm", "hard", "evsm", "pcf[box7]", "msm"})
        EXPECT_TRUE(metrics.contains(row)) << row;
    const size_t hard = r.out.find("\nhard "), box = r.out.find("\npcf[box7] ");
    ASSERT_NE(hard, std::string::npos) << r.out;
    ASSERT_NE(box, std::string::npos) << r.out;
    EXPECT_LT(hard, box) << r.out;
    EXPECT_NE(r.err.find("rendering hard (1/2)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("rendering pcf[box7] (2/2)"), std::string::npos) << r.err;
    const size_t vsm = r.out.find("\nvsm "), evsm = r.out.find("\nevsm "),
                 msm = r.out.find("\nmsm ");
    EXPECT_LT(box, vsm) << r.out;
    EXPECT_LT(vsm, evsm) << r.out << "the skipped rows in the order asked";
    EXPECT_LT(evsm, msm) << r.out;
    EXPECT_LT(r.err.find("warning: vsm skipped"), r.err.find("warning: evsm skipped")) << r.err;

    // When none fits, the error is the first row's.
    setenv("PENUMBRA_DEVICE_MEMORY", std::to_string(512u << 20).c_str(), 1);
    const ProcessResult none =
        runCli({"compare", "builtin:showcase", "-o", (out / "none").string(), "--techniques",
                "evsm,vsm", "--samples", "1", "--width", "32", "--height", "24", "--frames", "1",
                "--shadow-map-size", "8192", "--set", "csm.cascades=1"});
    unsetenv("PENUMBRA_DEVICE_MEMORY");
    EXPECT_EQ(none.exitCode, 2);
    EXPECT_NE(none.err.find("error: --shadow-map-size: evsm needs"), std::string::npos) << none.err;
}

// The truth traces one exact ray towards a light without a size, and every output says so:
// metrics.json's rays per light, the report's words, the progress line, reference.json. A soft
// row (pcss) ranked against that hard truth gets a note naming the light; a hard row (pcf) none.
TEST(CliOutputs, ALightWithoutASizeGetsOneExactRayAndSoftRowsANote) {
    const fs::path asset = threeLightAsset(outputScratch("hard-truth-asset"));
    const fs::path out = outputScratch("hard-truth");
    const std::vector<std::string> sizes = {"--light-radius", "0.2", "--light-angle", "0"};
    std::vector<std::string> args =
        withView({"compare", asset.string(), "-o", out.string(), "--techniques", "pcf,pcss",
                  "--samples", "8", "--frames", "1", "--shadow-map-size", "256"});
    args.insert(args.end(), sizes.begin(), sizes.end());
    ProcessResult r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string words = "8 rays per pixel towards the 2 lights with a size, 1 exact ray "
                              "towards the 1 light without";
    EXPECT_NE(r.err.find("ground truth, " + words), std::string::npos) << r.err;
    const nlohmann::json metrics = nlohmann::json::parse(slurp(out / "metrics.json"));
    EXPECT_EQ(metrics["reference"]["rays_per_pixel"], (nlohmann::json{1, 8, 8}))
        << "the sun (angle 0), the spot and the bulb (radius 0.2)";
    ASSERT_GE(metrics["notes"].size(), 1u);
    const std::string note = metrics["notes"][0];
    EXPECT_NE(note.find("towards light0 "), std::string::npos) << note;
    EXPECT_NE(note.find("penumbrae of pcss"), std::string::npos) << note; // its rows
    EXPECT_EQ(note.find("pcf"), std::string::npos) << "pcf models no light size: " << note;
    const std::string html = slurp(out / "report.html");
    EXPECT_NE(html.find(words), std::string::npos);
    EXPECT_NE(html.find("note hard-truth"), std::string::npos);

    const fs::path hardRows = outputScratch("hard-truth-pcf");
    args = withView({"compare", asset.string(), "-o", hardRows.string(), "--techniques", "pcf",
                     "--samples", "8", "--frames", "1", "--shadow-map-size", "256"});
    args.insert(args.end(), sizes.begin(), sizes.end());
    r = runCli(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(slurp(hardRows / "metrics.json").find("The truth is hard"), std::string::npos);

    const fs::path traced = outputScratch("hard-truth-reference");
    r = runCli(withView({"reference", asset.string(), "-o", traced.string(), "--samples", "8",
                         "--light-radius", "0", "--light-angle", "0", "--format", "pfm"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("1 exact ray per pixel and light (no light has a size"), std::string::npos)
        << r.err;
    const nlohmann::json ref = nlohmann::json::parse(slurp(traced / "reference.json"));
    EXPECT_EQ(ref["rays_per_pixel"], (nlohmann::json{1, 1, 1}));
    EXPECT_EQ(ref["samples"], 8) << "what was asked for stays";
}
