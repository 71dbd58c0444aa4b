// The CLI contract of docs/cli.md: bad input gives one `error:` line, a non-zero exit code, no
// crash and no output; good input writes exactly the files the contract lists.
#include "cli_refusal.h"
#include "core/exr_io.h"
#include "core/image_io.h"
#include "core/light_space.h"
#include "core/projection.h"
#include "float_images.h"
#include "gltf_builder.h"
#include "penumbra/reference.h"
#include "process.h"
#include "report/heatmap.h"
#include "report/light_mask.h"
#include "report/metrics.h"
#include "scratch_dir.h"
#include "small_comparison.h"
#include "three_light_asset.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <sstream>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    return outputScratch(name);
}

// The file-name prefix compare gives a row: "pcf[box7]" is written "pcf-box7", a layer after it
// ("pcf[box3]+contact") "pcf-box3-contact".
std::string rowFilePrefix(const std::string& row) {
    std::string prefix;
    for (char c : row)
        prefix += c == '[' || c == '+' ? "-" : c == ']' ? "" : std::string(1, c);
    return prefix;
}

class CliRefuses : public ::testing::TestWithParam<BadInput> {};

} // namespace

TEST_P(CliRefuses, WithOneErrorLineAndNoOutput) {
    expectOneErrorLineAndNoOutput(GetParam());
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
        BadInput{"width_not_a_number",
                 {"render", "builtin:showcase", "-o", "{out}", "--width", "abc"},
                 "error: --width: 'abc' is not a value it takes (--help gives its kind)"},
        BadInput{"unknown_command",
                 {"rendr", "builtin:showcase"},
                 "error: 'rendr' is not a command: render, reference, compare"},
        BadInput{"bench_empty_output",
                 {"bench", "builtin:showcase", "-o", ""},
                 "error: -o: an empty file name; -o takes FILE.json"},
        BadInput{"max_triangles_zero",
                 {"--max-triangles", "0", "render", "builtin:showcase", "-o", "{out}"},
                 "error: --max-triangles: '0' is not a number above zero"},
        BadInput{"frames_twice",
                 {"render", "builtin:showcase", "-o", "{out}", "--frames", "2", "--frames", "3"},
                 "error: --frames: given 2 values; it takes one"},
        BadInput{"unexpected_argument",
                 {"render", "builtin:showcase", "-o", "{out}", "--scene"},
                 "error: --scene: not an argument of this command (--help lists them)"},
        BadInput{"height_zero",
                 {"render", "builtin:showcase", "-o", "{out}", "--height", "0"},
                 "--height"},
        BadInput{"width_negative",
                 {"render", "builtin:showcase", "-o", "{out}", "--width", "-4"},
                 "--width"},
        BadInput{"unknown_scene",
                 {"render", "builtin:nowhere", "-o", "{out}"},
                 "builtin:nowhere: no such built-in scene"},
        BadInput{"generated_scene_bad_seed",
                 {"render", "builtin:gen/plates?seed=two", "-o", "{out}"},
                 "builtin:gen/plates?seed=two: seed 'two' is not a whole number"},
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
        BadInput{"no_output_option", {"render", "builtin:showcase"}, "--output"},
        BadInput{"unknown_float_format",
                 {"render", "builtin:showcase", "-o", "{out}", "--format", "tiff"},
                 "error: --format: 'tiff' is not one of both, exr, pfm"},
        BadInput{"reference_zero_samples",
                 {"reference", "builtin:showcase", "-o", "{out}", "--samples", "0"},
                 "--samples"},
        BadInput{"reference_embree_failure",
                 {"reference", "builtin:showcase", "-o", "{out}", "--width", "32", "--height", "32",
                  "--embree-config", "threads=abc"},
                 "embree: cannot create a device"},
        BadInput{"compare_unknown_technique",
                 {"compare", "builtin:showcase", "-o", "{out}", "--techniques", "hard,fuzzy"},
                 "--techniques: unknown technique or variant 'fuzzy'"},
        BadInput{"compare_unknown_layer",
                 {"compare", "builtin:showcase", "-o", "{out}", "--techniques", "pcss+Temporal"},
                 "error: --techniques: unknown layer 'Temporal' in 'pcss+Temporal' (layers: "
                 "contact, temporal, translucent)"},
        BadInput{"render_layer_twice",
                 {"render", "builtin:showcase", "-o", "{out}", "--technique",
                  "pcss+temporal+contact+temporal"},
                 "error: --technique: 'pcss+temporal+contact+temporal' names the layer "
                 "'temporal' twice"},
        BadInput{"sun_dir_two_numbers",
                 {"render", "builtin:showcase", "-o", "{out}", "--sun-dir", "1,2"},
                 "--sun-dir: '1,2' is not three numbers X,Y,Z"},
        BadInput{"sun_dir_zero",
                 {"render", "builtin:showcase", "-o", "{out}", "--sun-dir", "0,0,0"},
                 "--sun-dir: a direction needs a non-zero length"},
        BadInput{"light_pos_unknown_light",
                 {"render", "builtin:spot", "-o", "{out}", "--light-pos", "lamp=0,3,0"},
                 "--light-pos: scene 'spot' has no light named 'lamp' (lights: 'spot')"},
        BadInput{"light_dir_on_a_point_light",
                 {"reference", "builtin:room", "-o", "{out}", "--light-dir", "bulb=0,-1,0"},
                 "--light-dir: 'bulb' is a point light"},
        BadInput{"camera_pos_without_look_at",
                 {"compare", "builtin:showcase", "-o", "{out}", "--camera-pos", "0,5,5"},
                 "--camera-pos and --look-at go together"},
        BadInput{"fov_out_of_range",
                 {"render", "builtin:showcase", "-o", "{out}", "--camera-pos", "0,5,5", "--look-at",
                  "0,0,0", "--fov", "180"},
                 "--fov: 180 degrees is outside [1, 170]"},
        BadInput{"camera_and_camera_pos",
                 {"render", "builtin:showcase", "-o", "{out}", "--camera", "main", "--camera-pos",
                  "0,5,5", "--look-at", "0,0,0"},
                 "excludes"},
        BadInput{"compare_bad_set",
                 {"compare", "builtin:showcase", "-o", "{out}", "--set", "bias.slope=x"},
                 "bias.slope=x"},
        BadInput{"virtual_moments",
                 {"render", "builtin:showcase", "-o", "{out}", "--technique", "vsm", "--set",
                  "virtual.enabled=1"},
                 "virtual maps serve hard, pcf, pcss and smrt"},
        BadInput{"virtual_size_not_a_power_of_two",
                 {"render", "builtin:spot", "-o", "{out}", "--set", "virtual.enabled=1", "--set",
                  "virtual.size=3000"},
                 "virtual.size: 3000 is not a power of two"},
        BadInput{"virtual_pool_not_whole_pages",
                 {"render", "builtin:room", "-o", "{out}", "--set", "virtual.enabled=1", "--set",
                  "virtual.poolSize=1000"},
                 "not a multiple of virtual.pageSize"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(Cli, RenderWritesTheContractFiles) {
    const fs::path out = scratch("render-ok");
    const ProcessResult r = runCli({"render", "builtin:showcase", "-o", out.string(), "--width",
                                    "96", "--height", "64", "--shadow-map-size", "256", "--frames",
                                    "2", "--set", "bias.slope=1.5", "--light-angle", "2.5"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : {"image.png", "visibility.pfm", "position.pfm", "normal.pfm",
                          "visibility.exr", "position.exr", "normal.exr", "stats.json"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(out))
        ++entries;
    EXPECT_EQ(entries, 8u) << "no staging leftovers";
    for (const char* stem : {"visibility", "position", "normal"}) // OpenEXR beside PFM, by default
        expectSameImage(readPfm(out / (std::string(stem) + ".pfm")),
                        readExr(out / (std::string(stem) + ".exr")), stem);

    const FloatImage vis = readPfm(out / "visibility.pfm");
    EXPECT_EQ(vis.width, 96u);
    EXPECT_EQ(vis.height, 64u);
    EXPECT_EQ(vis.channels, 1u);
    // Rows are stored bottom to top; decoded top to bottom the sky (NaN) is first, ground last.
    EXPECT_TRUE(std::isnan(vis.pixels.front()));
    EXPECT_FALSE(std::isnan(vis.pixels.back()));
    const FloatImage pos = readPfm(out / "position.pfm");
    EXPECT_EQ(pos.channels, 3u);
    EXPECT_NEAR(pos.pixels[pos.pixels.size() - 2], 0.0f, 1e-3f); // bottom row lies on y = 0
    const FloatImage normal = readPfm(out / "normal.pfm");
    EXPECT_EQ(normal.channels, 3u);
    EXPECT_NEAR(normal.pixels[normal.pixels.size() - 2], 1.0f, 1e-3f); // the ground faces up
    for (size_t i = 0; i + 2 < normal.pixels.size(); i += 3)
        if (std::isfinite(normal.pixels[i])) {
            const float* n = &normal.pixels[i];
            ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-3f) << "pixel " << i / 3;
        }

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
    EXPECT_DOUBLE_EQ(stats["lights"][0]["angular_diameter_degrees"].get<double>(), 2.5);
    double sum = 0;
    for (const auto& [pass, ms] : stats["gpu_ms"].items())
        if (pass != "total")
            sum += ms.get<double>();
    EXPECT_NEAR(stats["gpu_ms"]["total"].get<double>(), sum, 1e-9 * sum);
    // By the group each pass declares: hard's depth pass, the frame's G-buffer, the rest per pixel.
    const nlohmann::json& transient = stats["transient_memory"];
    EXPECT_GT(transient["separate_bytes"].get<uint64_t>(), 0u) << "the frame's own targets";
    EXPECT_LE(transient["shared_bytes"].get<uint64_t>(),
              transient["separate_bytes"].get<uint64_t>());
    const nlohmann::json& byCost = stats["gpu_ms_by_cost"];
    EXPECT_EQ(byCost["shadow_maps"], stats["gpu_ms"]["shadow"]);
    EXPECT_EQ(byCost["frame"], stats["gpu_ms"]["gbuffer"]);
    EXPECT_NEAR(byCost["per_pixel"].get<double>(),
                stats["gpu_ms"]["visibility"].get<double>() +
                    stats["gpu_ms"]["composite"].get<double>(),
                1e-9 * sum);
    EXPECT_NE(r.out.find("GPU ms per pass"), std::string::npos);
}

// Scene control: render and reference take the same options and so see the same view and
// lights; stats.json records the lights as edited, the camera and the edits as given.
TEST(Cli, SceneControlGivesRenderAndReferenceTheSameViewAndLights) {
    const std::vector<std::string> scene = {"--width",      "64",
                                            "--height",     "48",
                                            "--sun-dir",    "0.2,-1,0.3",
                                            "--light-pos",  "spot=1,5,2",
                                            "--light-dir",  "spot=-1,-5,-2",
                                            "--camera-pos", "0,6,9",
                                            "--look-at",    "0,0.5,0",
                                            "--fov",        "40"};
    const fs::path rendered = scratch("scene-control-render"),
                   traced = scratch("scene-control-reference");
    std::vector<std::string> render = {
        "render", "builtin:spot", "-o", rendered.string(), "--shadow-map-size",
        "256",    "--frames",     "1"};
    std::vector<std::string> reference = {"reference",     "builtin:spot", "-o",
                                          traced.string(), "--samples",    "4"};
    render.insert(render.end(), scene.begin(), scene.end());
    reference.insert(reference.end(), scene.begin(), scene.end());
    const ProcessResult r = runCli(render);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const ProcessResult t = runCli(reference);
    ASSERT_EQ(t.exitCode, 0) << t.err;

    const auto stats = nlohmann::json::parse(slurp(rendered / "stats.json"));
    EXPECT_EQ(stats["camera"]["name"], "command line");
    EXPECT_EQ(stats["camera"]["position"], nlohmann::json::array({0.0, 6.0, 9.0}));
    EXPECT_EQ(stats["camera"]["target"], nlohmann::json::array({0.0, 0.5, 0.0}));
    EXPECT_NEAR(stats["camera"]["yfov_degrees"].get<double>(), 40.0, 1e-4);
    ASSERT_EQ(stats["lights"].size(), 2u) << "the spot and the added sun";
    EXPECT_EQ(stats["lights"][0]["position"], nlohmann::json::array({1.0, 5.0, 2.0}));
    const auto spotDir = stats["lights"][0]["direction"].get<std::vector<double>>();
    EXPECT_NEAR(spotDir[1], -5.0 / std::sqrt(30.0), 1e-6);
    EXPECT_EQ(stats["lights"][1]["type"], "directional");
    EXPECT_NEAR(stats["lights"][1]["direction"][1].get<double>(), -1.0 / std::sqrt(1.13), 1e-6);
    EXPECT_EQ(stats["scene"]["edits"]["light_pos"]["spot"], nlohmann::json::array({1, 5, 2}));
    EXPECT_DOUBLE_EQ(stats["scene"]["edits"]["fov_degrees"].get<double>(), 40.0);
    EXPECT_FALSE(stats["scene"]["default_light"].get<bool>());

    const auto info = nlohmann::json::parse(slurp(traced / "reference.json"));
    EXPECT_EQ(info["camera"], "command line");
    EXPECT_EQ(info["scene_edits"], stats["scene"]["edits"]);
    EXPECT_EQ(slurp(rendered / "position.pfm"), slurp(traced / "position.pfm"))
        << "the same camera sees the same surfaces";
    for (const char* f : {"visibility.pfm", "visibility_1.pfm"}) {
        EXPECT_TRUE(fs::exists(rendered / f)) << f;
        EXPECT_TRUE(fs::exists(traced / f)) << f;
    }
}

// sdf draws no shadow map: no shadow pass, the field's slice and its build in stats.json; a
// malformed --field-slice or a field past its cap is refused with one line and no output. (A
// 48-voxel field is too coarse for the showcase's casters: sdf.refuse=0 keeps the picture.)
TEST(Cli, RenderWithTheDistanceFieldWritesItsSlice) {
    const fs::path out = scratch("render-sdf");
    const ProcessResult r =
        runCli({"render", "builtin:showcase", "-o", out.string(), "--width", "64", "--height", "48",
                "--frames", "1", "--technique", "sdf", "--set", "sdf.resolution=48", "--set",
                "sdf.refuse=0", "--field-slice", "z:0.5"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_TRUE(fs::exists(out / "field_slice.png"));
    const auto stats = nlohmann::json::parse(slurp(out / "stats.json"));
    EXPECT_FALSE(stats["gpu_ms"].contains("shadow"));
    EXPECT_TRUE(stats["gpu_ms"].contains("visibility"));
    const auto& field = stats["distance_field"];
    ASSERT_TRUE(field.is_object());
    EXPECT_EQ(field["voxels"].size(), 3u);
    EXPECT_GT(field["bytes"].get<double>(), 0.0);
    for (const char* pass : {"sdf_seed", "sdf_flood", "sdf_resolve"})
        EXPECT_GT(field["build_passes_ms"][pass].get<double>(), 0.0) << pass;
    // The slice across z: x to the right, y up, each voxel a square of pixels.
    const auto voxels = field["voxels"];
    const std::string png = slurp(out / "field_slice.png");
    ASSERT_GT(png.size(), 24u);
    auto be32 = [&](size_t at) {
        return (uint32_t(uint8_t(png[at])) << 24) | (uint32_t(uint8_t(png[at + 1])) << 16) |
               (uint32_t(uint8_t(png[at + 2])) << 8) | uint32_t(uint8_t(png[at + 3]));
    };
    const uint32_t scale = be32(16) / voxels[0].get<uint32_t>();
    EXPECT_GE(scale, 1u);
    EXPECT_EQ(be32(16), scale * voxels[0].get<uint32_t>());
    EXPECT_EQ(be32(20), scale * voxels[1].get<uint32_t>());
    EXPECT_GE(std::max(be32(16), be32(20)), 512u);
    EXPECT_NE(r.out.find("distance field"), std::string::npos);
    // The progress line names the size built, as stats.json does.
    const std::string built =
        "building the distance field: " + std::to_string(voxels[0].get<uint32_t>()) + "x" +
        std::to_string(voxels[1].get<uint32_t>()) + "x" +
        std::to_string(voxels[2].get<uint32_t>()) + " voxels";
    EXPECT_NE(r.err.find(built), std::string::npos) << r.err;

    for (const std::vector<std::string>& bad :
         {std::vector<std::string>{"--field-slice", "w"},
          std::vector<std::string>{"--field-slice", "y:high"},
          std::vector<std::string>{"--field-slice", "y:1e6"},
          std::vector<std::string>{"--set", "sdf.resolution=1024"},
          std::vector<std::string>{"--set", "sdf.resolution=8"}}) {
        const fs::path refused = scratch("render-sdf-bad");
        std::vector<std::string> args{
            "render", "builtin:showcase", "-o", refused.string(), "--width", "32", "--height",
            "32",     "--frames",         "1",  "--technique",    "sdf"};
        args.insert(args.end(), bad.begin(), bad.end());
        const ProcessResult e = runCli(args);
        EXPECT_NE(e.exitCode, 0) << bad[1];
        EXPECT_EQ(e.err.rfind("error:", 0), 0u) << bad[1] << ": " << e.err;
        EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << e.err;
        EXPECT_FALSE(fs::exists(refused)) << bad[1];
    }
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
    // Whole numbers as they are typed (`--set sdf.steps=128`), fractions as numbers.
    for (const auto& t : j)
        for (const auto& p : t["parameters"]) {
            if (p["type"] == "int") {
                EXPECT_TRUE(p["default"].is_number_integer() && p["min"].is_number_integer() &&
                            p["max"].is_number_integer())
                    << p.dump();
            }
            if (p["key"] == "sdf.steps") {
                EXPECT_EQ(p["default"].dump(), "128");
            }
            if (p["key"] == "bias.slope") {
                EXPECT_TRUE(p["default"].is_number_float());
            }
        }
    const ProcessResult text = runCli({"techniques"});
    EXPECT_NE(text.out.find("--set sdf.steps=128  int [4, 1024]"), std::string::npos) << text.out;
}

TEST(Cli, InfoNamesTheDevice) {
    const ProcessResult r = runCli({"info"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("maxImageDimension2D"), std::string::npos);
    EXPECT_NE(r.out.find("[default]"), std::string::npos);
}

TEST(Cli, CompareWritesMetricsForEveryTechnique) {
    const fs::path& out = smallComparison();
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"));
    ASSERT_TRUE(metrics.contains("reference") && metrics.contains("techniques"));
    EXPECT_EQ(metrics["reference"]["samples"], 4);
    ASSERT_FALSE(metrics["techniques"].empty());
    for (const auto& [name, m] : metrics["techniques"].items()) {
        for (const char* key : {"rmse", "mae", "max", "misclassified",
                                "misclassified_outside_edges", "acne", "leak", "gpu_ms"})
            EXPECT_TRUE(m.contains(key)) << name << " lacks " << key;
        EXPECT_TRUE(m["gpu_ms"].contains("visibility"));
        const std::string prefix = rowFilePrefix(name);
        EXPECT_TRUE(fs::exists(out / (prefix + ".image.png"))) << name;
        EXPECT_TRUE(fs::exists(out / (prefix + ".heatmap.png"))) << name;
        // Every row's stats.json gives the one view's measure.
        const auto view = nlohmann::json::parse(slurp(out / (prefix + ".stats.json")))["view"];
        EXPECT_GT(view["subject"].get<double>(), 0.0) << name;
        EXPECT_GE(view["cast_shadow"].get<double>(), 0.0) << name;
        EXPECT_EQ(view, nlohmann::json::parse(
                            slurp(out / (rowFilePrefix(metrics["techniques"].begin().key()) +
                                         ".stats.json")))["view"])
            << name;
    }
    // One float format by default, OpenEXR: what image tools open, and far smaller than PFM.
    for (const char* f : {"report.html", "visibility.exr", "position.exr", "normal.exr"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    for (const auto& e : fs::directory_iterator(out))
        EXPECT_NE(e.path().extension(), ".pfm") << e.path().filename();
}

TEST(Cli, CompareMetricsHeatMapsAndTruthFollowFromTheFilesItWrote) {
    // Everything compare reports must follow from the images it wrote: the truth from the
    // G-buffer files and the light size asked for, each row's metrics and heat map from the row's
    // visibility and the truth, on the pixels the light can reach.
    const fs::path out = scratch("compare-consistent");
    const ProcessResult r = runCli({"compare",
                                    "builtin:showcase",
                                    "-o",
                                    out.string(),
                                    "--techniques",
                                    "hard,pcf[box7],pcss",
                                    "--width",
                                    "96",
                                    "--height",
                                    "64",
                                    "--shadow-map-size",
                                    "512",
                                    "--frames",
                                    "1",
                                    "--samples",
                                    "16",
                                    "--light-angle",
                                    "6",
                                    "--format",
                                    "both"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const FloatImage truthFile = readPfm(out / "visibility.pfm");
    RenderResult g{.width = truthFile.width, .height = truthFile.height};
    g.position = readPfm(out / "position.pfm").pixels;
    g.normal = readPfm(out / "normal.pfm").pixels;
    Scene scene = loadScene("builtin:showcase");
    applyLightSizeOverrides(scene, -1.0f, 6.0f);
    const ReferenceResult truth = computeReference(scene, g, {.samples = 16});
    ASSERT_EQ(truth.visibility.size(), 1u);
    EXPECT_EQ(0, std::memcmp(truth.visibility[0].data(), truthFile.pixels.data(),
                             truthFile.pixels.size() * sizeof(float)))
        << "visibility.pfm is not the truth for a 6-degree sun";
    const std::vector<uint8_t> mask = lightMask(scene.lights[0], g);
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"))["techniques"];
    ASSERT_EQ(metrics.size(), 4u); // hard, pcf[box7], pcss, pcss[fast]
    for (const auto& [name, reported] : metrics.items()) {
        const std::string prefix = rowFilePrefix(name);
        const FloatImage row = readPfm(out / (prefix + ".visibility.pfm"));
        const MetricLayer layer{row.pixels, truth.visibility[0], mask};
        const ErrorMetrics m = computeMetrics(g.width, g.height, std::span(&layer, 1));
        EXPECT_GT(m.pixels, g.width * g.height / 3) << name;
        const std::pair<const char*, double> expected[] = {
            {"rmse", m.rmse},
            {"mae", m.mae},
            {"max", m.max},
            {"misclassified", m.misclassified},
            {"misclassified_outside_edges", m.misclassifiedOutsideEdges},
            {"acne", m.acne},
            {"leak", m.leak}};
        for (const auto& [key, value] : expected)
            EXPECT_NEAR(reported[key].get<double>(), value, 1e-9) << name << " " << key;
        // The heat map's data: the row minus the truth, NaN where either is.
        const FloatImage difference = readExr(out / (prefix + ".difference.exr"));
        ASSERT_EQ(difference.pixels.size(), row.pixels.size()) << name;
        size_t compared = 0;
        for (size_t i = 0; i < row.pixels.size(); ++i) {
            const float want = row.pixels[i] - truth.visibility[0][i];
            if (std::isnan(want)) {
                ASSERT_TRUE(std::isnan(difference.pixels[i])) << name << " pixel " << i;
                continue;
            }
            ASSERT_EQ(difference.pixels[i], want) << name << " pixel " << i;
            ++compared;
        }
        EXPECT_GT(compared, size_t(m.pixels) / 2) << name;
        expectSameImage(readPfm(out / (prefix + ".difference.pfm")), difference, name);
        EXPECT_EQ(slurp(out / (prefix + ".heatmap.png")),
                  [&] {
                      const std::vector<uint8_t> png = encodePng(signedErrorHeatmap(
                          g.width, g.height, row.pixels, truth.visibility[0], mask));
                      return std::string(png.begin(), png.end());
                  }())
            << name << ": heat map";
    }
}

TEST(Cli, RendersAGltfWithAVisibilityImagePerShadowingLight) {
    const fs::path asset = threeLightAsset(scratch("gltf-assets"));
    const fs::path out = scratch("gltf-render");
    const ProcessResult r = runCli({"render", asset.string(), "-o", out.string(), "--width", "96",
                                    "--height", "64", "--shadow-map-size", "256", "--frames", "1"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "visibility.pfm"));
    EXPECT_TRUE(fs::exists(out / "visibility_1.pfm")) << "the spot light's visibility";
    EXPECT_TRUE(fs::exists(out / "visibility_2.pfm")) << "the point light's visibility";
    EXPECT_FALSE(fs::exists(out / "visibility_3.pfm"));
    const auto stats = nlohmann::json::parse(slurp(out / "stats.json"));
    ASSERT_EQ(stats["lights"].size(), 3u);
    // Every view's projection: the sun's and the spot's one, the bulb's six cube faces, whose
    // layers follow the others' in light order.
    const std::vector<std::string> kinds = {"orthographic", "perspective", "cube"};
    uint32_t layer = 0;
    for (size_t i = 0; i < 3; ++i) {
        const auto& light = stats["lights"][i];
        EXPECT_EQ(light["projection"], kinds[i]);
        const auto& views = light["views"];
        ASSERT_EQ(views.size(), i == 2 ? 6u : i == 0 ? 4u : 1u) << kinds[i]; // csm.cascades 4
        for (const auto& view : views) {
            EXPECT_EQ(view["layer"], layer++);
            EXPECT_EQ(view["world_to_shadow"].size(), 16u);
            EXPECT_LT(view["near"].get<double>(), view["far"].get<double>());
        }
        if (i == 2) {
            EXPECT_EQ(views[0]["face"], "+x");
            EXPECT_EQ(views[5]["face"], "-z");
            // Each face spans 90 degrees plus its guard band on each side.
            const double guard = light["guard_texels"].get<double>();
            const double fov = 2.0 * std::atan(256.0 / (256.0 - 2.0 * guard)) * 180.0 / M_PI;
            EXPECT_GT(guard, 0.0);
            EXPECT_NEAR(views[0]["fov_degrees"].get<double>(), fov, 1e-3);
        }
    }
}

TEST(Cli, RefusesAMalformedGltfWithOneLineAndNoOutput) {
    const fs::path where = scratch("gltf-bad");
    fs::create_directories(where);
    std::ofstream(where / "bad.gltf") << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":7}]})";
    const fs::path out = scratch("gltf-bad-out");
    const ProcessResult r = runCli({"render", (where / "bad.gltf").string(), "-o", out.string()});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "error: " + (where / "bad.gltf").string() +
                         ": nodes[0].mesh: index 7 is out of range (0 meshes)\n");
    EXPECT_FALSE(fs::exists(out));
}

namespace {

// compare's metrics.json for the hard row on builtin:field at 160x120 along a camera path of
// `frames` frames, with `extra` arguments; report.html names the path's shimmer column.
nlohmann::json fieldPathMetrics(const std::string& name, const char* path, int frames,
                                std::vector<std::string> extra) {
    const fs::path out = scratch(name);
    std::vector<std::string> args{"compare",
                                  "builtin:field",
                                  "-o",
                                  out.string(),
                                  "--techniques",
                                  "hard",
                                  "--width",
                                  "160",
                                  "--height",
                                  "120",
                                  "--frames",
                                  "1",
                                  "--samples",
                                  "4",
                                  "--camera-path",
                                  path,
                                  "--path-frames",
                                  std::to_string(frames)};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"));
    EXPECT_EQ(metrics["camera_path"]["path"], path);
    EXPECT_EQ(metrics["camera_path"]["frames"], frames);
    EXPECT_NE(slurp(out / "report.html").find("Shimmer (" + std::string(path)), std::string::npos);
    return metrics;
}

// The shimmer of four cascades, stabilised or not, along a path of 4 frames.
double fieldShimmer(const char* path, bool stabilize) {
    return fieldPathMetrics(std::string("shimmer-") + path + (stabilize ? "-stable" : "-free"),
                            path, 4,
                            {"--shadow-map-size", "1024", "--set", "csm.cascades=4", "--set",
                             std::string("csm.stabilize=") +
                                 (stabilize ? "true" : "false")})["techniques"]["hard"]["shimmer"]
        .get<double>();
}

} // namespace

TEST(Cli, StabilizedCascadesShimmerAtMostHalfAsMuchAsFreeOnes) {
    for (const char* path : {"dolly", "orbit"}) {
        const double stable = fieldShimmer(path, true), free = fieldShimmer(path, false);
        std::printf("%s: shimmer stabilised %.6f, free %.6f\n", path, stable, free);
        EXPECT_GT(free, 1e-4) << path << ": free cascades crawl";
        EXPECT_LE(stable, 0.5 * free) << path;
    }
    // A turning sun: each frame's change against the truth's own (traced per frame).
    const double sun = fieldShimmer("sun", true);
    std::printf("sun: shimmer %.6f\n", sun);
    EXPECT_GE(sun, 0.0);
    EXPECT_LT(sun, 0.05);
}

// Virtual maps along the camera paths: pages fixed in the world do not crawl (shimmer no worse
// than stabilised cascades'), and each frame after the first renders only the few pages its view
// uncovers.
TEST(Cli, VirtualMapsAlongCameraPathsRenderFewPagesAndDoNotCrawl) {
    for (const char* path : {"dolly", "orbit"}) {
        const auto j = fieldPathMetrics(std::string("virtual-path-") + path, path, 5,
                                        {"--set", "virtual.enabled=1"})["techniques"]["hard"];
        const auto rendered = j["path_pages_rendered"].get<std::vector<uint32_t>>();
        const auto resident = j["path_pages_resident"].get<std::vector<uint32_t>>();
        ASSERT_EQ(rendered.size(), 5u) << j.dump();
        ASSERT_EQ(resident.size(), 5u);
        for (size_t t = 1; t < rendered.size(); ++t)
            EXPECT_LE(rendered[t] * 10, resident[t]) << path << " frame " << t;
        const double stable = fieldShimmer(path, true);
        std::printf("%s: virtual shimmer %.6f (stabilised cascades %.6f), pages rendered %u of %u "
                    "resident after the first frame\n",
                    path, j["shimmer"].get<double>(), stable, rendered.back(), resident.back());
        EXPECT_LE(j["shimmer"].get<double>(), stable + 1e-5) << path;
    }
}

TEST(Cli, CompareRefusesAnUnknownCameraPath) {
    const fs::path out = scratch("shimmer-bad");
    const ProcessResult r =
        runCli({"compare", "builtin:field", "-o", out.string(), "--camera-path", "spiral"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "error: --camera-path: 'spiral' is not dolly, orbit or sun\n");
    EXPECT_FALSE(fs::exists(out));
}

// bench: a run per technique and per swept value of a parameter it reads, each pass's median
// inside its 10th and 90th percentiles, the frame's total at least any pass, the maps' memory
// the same for the same maps; bench.html beside the JSON, with a chart of the sweep.
TEST(Cli, BenchTimesEveryTechniqueAndEverySweptValue) {
    const fs::path dir = scratch("bench");
    const ProcessResult r =
        runCli({"bench", "builtin:showcase", "-o", (dir / "times.json").string(), "--techniques",
                "hard,pcf,pcss", "--sweep", "pcf.size=3,7,11", "--width", "96", "--height", "64",
                "--shadow-map-size", "256", "--frames", "3"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(dir / "times.json"));
    EXPECT_EQ(j["device"]["name"].get<std::string>().empty(), false);
    EXPECT_EQ(j["frames"], 3);
    const auto& runs = j["runs"];
    ASSERT_EQ(runs.size(), 5u) << j.dump(1);
    const std::vector<std::string> techniques{"hard", "pcf", "pcf", "pcf", "pcss"};
    const std::vector<std::string> sizes{"", "3", "7", "11", ""};
    for (size_t i = 0; i < runs.size(); ++i) {
        SCOPED_TRACE(i);
        const auto& run = runs[i];
        EXPECT_EQ(run["technique"], techniques[i]);
        if (sizes[i].empty()) {
            EXPECT_TRUE(run["swept"].empty());
        } else {
            EXPECT_EQ(run["swept"]["pcf.size"], sizes[i]);
            EXPECT_DOUBLE_EQ(run["parameters"]["pcf.size"].get<double>(), std::stod(sizes[i]));
        }
        EXPECT_EQ(run["parameters"].contains("pcf.size"), techniques[i] == "pcf");
        double largest = 0;
        for (const char* pass : {"shadow", "gbuffer", "visibility", "composite"}) {
            ASSERT_TRUE(run["gpu_ms"].contains(pass)) << pass;
            const auto& s = run["gpu_ms"][pass];
            EXPECT_GT(s["p10"].get<double>(), 0.0) << pass;
            EXPECT_LE(s["p10"].get<double>(), s["median"].get<double>()) << pass;
            EXPECT_LE(s["median"].get<double>(), s["p90"].get<double>()) << pass;
            largest = std::max(largest, s["median"].get<double>());
        }
        EXPECT_GE(run["gpu_ms_total"]["median"].get<double>(), largest);
        // Four cascades of a 256-texel D32 map, and the same screen targets, for every run here.
        EXPECT_EQ(run["memory"]["shadow_maps"], (techniques[i] == "pcss" || techniques[i] == "pcf"
                                                     ? runs[0]["memory"]["shadow_maps"]
                                                     : nlohmann::json(4u * 256u * 256u * 4u)));
        EXPECT_EQ(run["gpu_memory_bytes"].get<uint64_t>(),
                  run["memory"]["shadow_maps"].get<uint64_t>() +
                      run["memory"]["screen_targets"].get<uint64_t>() +
                      run["memory"]["distance_field"].get<uint64_t>());
    }
    const std::string html = slurp(dir / "bench.html");
    EXPECT_NE(html.find("pcf: cost against pcf.size"), std::string::npos);
    EXPECT_NE(html.find("<svg"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos) << "self-contained";
    EXPECT_NE(r.out.find("[3/5] pcf pcf.size=7"), std::string::npos) << r.out;
}

// bench with virtual maps for every light type: the run that reads them reports its pages (the
// second warm-up renders the view's, the timed frames of a still view none), the pool as its
// shadow-map memory (with a page table and its requests per frame in flight), and bench.html a
// pages column; the run without them reports none.
TEST(Cli, BenchReportsTheVirtualPagesOfEachRun) {
    for (const std::string scene : {"builtin:field", "builtin:spot", "builtin:room"}) {
        SCOPED_TRACE(scene);
        const fs::path dir = scratch("bench-virtual");
        const ProcessResult r =
            runCli({"bench", scene, "-o", (dir / "times.json").string(), "--techniques", "hard",
                    "--sweep", "virtual.enabled=0,1", "--width", "96", "--height", "64", "--frames",
                    "3", "--set", "virtual.poolSize=2048"});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto j = nlohmann::json::parse(slurp(dir / "times.json"));
        ASSERT_EQ(j["runs"].size(), 2u);
        EXPECT_FALSE(j["runs"][0].contains("virtual_maps"));
        const auto& v = j["runs"][1]["virtual_maps"];
        const std::vector<uint32_t> perFrame = v["pages_rendered_per_frame"];
        ASSERT_EQ(perFrame.size(), 5u) << "two warm-ups and three timed frames";
        EXPECT_EQ(perFrame[0], 0u) << "the first frame only asks";
        EXPECT_GT(perFrame[1], 0u);
        EXPECT_EQ(perFrame[1], v["pages_resident"]);
        for (size_t f = 2; f < perFrame.size(); ++f)
            EXPECT_EQ(perFrame[f], 0u) << f;
        EXPECT_EQ(v["pool_pages"], 256u); // (2048 / 128)^2
        EXPECT_DOUBLE_EQ(v["pool_occupancy"].get<double>(),
                         v["pages_resident"].get<double>() / 256.0);
        const uint64_t mapBytes = j["runs"][1]["memory"]["shadow_maps"];
        EXPECT_GT(mapBytes, 2048ull * 2048 * 4) << "the pool and four page tables";
        EXPECT_LT(mapBytes, 2048ull * 2048 * 4 + (64ull << 20));
        const std::string html = slurp(dir / "bench.html");
        EXPECT_NE(html.find("virtual pages</th>"), std::string::npos);
        EXPECT_NE(html.find("<td>0 per frame <small>(most 0)</small>, " +
                            std::to_string(v["pages_resident"].get<uint32_t>()) +
                            " of 256 resident"),
                  std::string::npos)
            << html;
    }
}

TEST(Cli, BenchRefusesBadSweepsAndTechniquesBeforeRunning) {
    const fs::path dir = scratch("bench-bad");
    const std::string out = (dir / "b.json").string();
    for (const auto& [args, subject] :
         std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"--sweep", "pcf.size=3,4"}, "error: --sweep"},
             {{"--sweep", "pcf.nope=3"}, "error: --sweep"},
             {{"--sweep", "pcf.size"}, "error: --sweep"},
             {{"--techniques", "hard,nope"}, "error: --technique"},
             {{"--shadow-map-size", "1000000"}, "error: --shadow-map-size"}}) {
        std::vector<std::string> full{"bench", "builtin:showcase", "-o", out,        "--width",
                                      "32",    "--height",         "32", "--frames", "1"};
        full.insert(full.end(), args.begin(), args.end());
        const ProcessResult r = runCli(full);
        EXPECT_NE(r.exitCode, 0) << args[1];
        EXPECT_EQ(r.err.rfind(subject, 0), 0u) << r.err;
        EXPECT_FALSE(fs::exists(out)) << args[1];
        EXPECT_FALSE(fs::exists(dir / "bench.html"));
    }
    // -o names the JSON: a file of another kind, or a directory that exists, before any run.
    fs::create_directories(dir / "taken.json");
    fs::create_directories(dir / "html" / "bench.html");
    for (const auto& [output, why] : std::vector<std::pair<fs::path, std::string>>{
             {dir / "b.txt", "not a JSON file name; -o takes FILE.json"},
             {dir / "taken.json", "is a directory"},
             {dir / "html" / "b.json", "bench.html: is a directory"}}) {
        const ProcessResult r = runCli({"bench", "builtin:showcase", "-o", output.string(),
                                        "--width", "32", "--height", "32", "--frames", "1"});
        EXPECT_NE(r.exitCode, 0) << output;
        EXPECT_EQ(r.err.rfind("error: " + output.parent_path().string(), 0), 0u) << r.err;
        EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "b.txt"));
        EXPECT_FALSE(fs::exists(dir / "bench.html"));
    }
}
