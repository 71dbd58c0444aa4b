// Lights from the command line: --add-light's sun, spot and point light each cast the shadow the
// ground truth sees, and light sizes that no light of the scene takes are warned about.
#include "core/image_io.h"
#include "gltf_builder.h"
#include "process.h"
#include "scratch_dir.h"
#include "three_light_asset.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <tuple>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// A ground and a box on it, no lights: the loader gives it a default light until one is added.
fs::path unlitAsset(const fs::path& where) {
    GltfBuilder b;
    groundAndBox(b);
    fs::create_directories(where);
    return b.writeGltf(where / "unlit.gltf");
}

const std::vector<std::string> kLights = {"--add-light", "sun:dir=-1,-2,-0.5",
                                          "--add-light", "spot:pos=3,5,2,dir=-0.5,-1,-0.3,cone=40",
                                          "--add-light", "point:pos=-2,3,1,name=bulb"};

std::vector<std::string> command(std::vector<std::string> args) {
    for (const char* a :
         {"--width", "64", "--height", "48", "--camera-pos", "0,9,9", "--look-at", "0,0,0"})
        args.emplace_back(a);
    args.insert(args.end(), kLights.begin(), kLights.end());
    return args;
}

} // namespace

TEST(CliLights, AddedLightsOfEveryKindCastTheShadowsTheTruthSees) {
    const fs::path asset = unlitAsset(outputScratch("added-lights-asset"));
    const fs::path rendered = outputScratch("added-lights-render");
    const fs::path traced = outputScratch("added-lights-truth");
    ProcessResult r =
        runCli(command({"render", asset.string(), "-o", rendered.string(), "--shadow-map-size",
                        "1024", "--frames", "1", "--format", "pfm"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runCli(command({"reference", asset.string(), "-o", traced.string(), "--format", "pfm"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string stats = slurp(rendered / "stats.json");
    for (const char* name : {"directional (--add-light 1)", "spot (--add-light 2)", "bulb"})
        EXPECT_NE(stats.find(name), std::string::npos) << name;
    EXPECT_NE(stats.find("\"default_light\": false"), std::string::npos)
        << "the default light is replaced";
    EXPECT_EQ(stats.find("default sun"), std::string::npos);
    for (const char* file : {"visibility.pfm", "visibility_1.pfm", "visibility_2.pfm"}) {
        const FloatImage v = readPfm(rendered / file), t = readPfm(traced / file);
        ASSERT_EQ(v.pixels.size(), t.pixels.size()) << file;
        size_t seen = 0, shadowed = 0, wrong = 0;
        for (size_t i = 0; i < v.pixels.size(); ++i) {
            if (!std::isfinite(t.pixels[i]))
                continue;
            ++seen;
            shadowed += t.pixels[i] < 0.5f;
            wrong += std::abs(v.pixels[i] - t.pixels[i]) > 0.5f;
        }
        EXPECT_GT(shadowed, seen / 50) << file << ": the box's shadow is in view";
        EXPECT_LT(shadowed, seen - seen / 10) << file << ": the light reaches the ground";
        EXPECT_LE(wrong, seen / 100) << file << ": " << wrong << " of " << seen << " pixels";
    }
}

TEST(CliLights, LightSizesNoLightTakesAreWarnedAbout) {
    const fs::path out = outputScratch("light-size-warnings");
    const std::vector<std::string> base = {
        "render", "builtin:showcase",  "-o", out.string(), "--width", "16", "--height",
        "16",     "--shadow-map-size", "64", "--frames",   "1"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return runCli(args);
    };
    ProcessResult r = with({"--light-radius", "0.3"}); // the showcase has a sun only
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("warning: --light-radius: scene 'showcase' has no spot or point"),
              std::string::npos)
        << r.err;
    r = with({"--light-radius", "0.3", "--add-light", "point:pos=0,3,0"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    r = with({"--light-angle", "2"});
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    r = runCli({"render", "builtin:spot", "-o", out.string(), "--width", "16", "--height", "16",
                "--shadow-map-size", "64", "--frames", "1", "--light-angle", "2"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("warning: --light-angle: scene"), std::string::npos) << r.err;
    // Sizes that are not finite numbers in range: one line each, the range in plain numbers.
    for (const auto& [option, value, words] :
         {std::tuple{"--light-radius", "nan", "is not a finite number >= 0"},
          std::tuple{"--light-radius", "-1", "is not a finite number >= 0"},
          std::tuple{"--light-radius", "1e39", "is not a finite number >= 0"},
          std::tuple{"--light-angle", "nan", "is not a number from 0 to 30"},
          std::tuple{"--light-angle", "30.5", "is not a number from 0 to 30"}}) {
        r = with({option, value});
        EXPECT_NE(r.exitCode, 0) << option << " " << value;
        EXPECT_NE(r.err.find(fmt::format("error: {}: '{}' {}", option, value, words)),
                  std::string::npos)
            << r.err;
    }
    EXPECT_EQ(with({"--light-angle", "30"}).exitCode, 0);
    r = with({"--add-light", "spot:pos=0,3,0"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("error: --add-light: 'spot:pos=0,3,0': it needs dir="), std::string::npos)
        << r.err;
}

TEST(CliLights, ViewGroundDoubleSidedAndOpenGeometryFromTheCommandLine) {
    const fs::path asset = unlitAsset(outputScratch("view-asset"));
    const fs::path out = outputScratch("view-render");
    const auto render = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {
            "render", asset.string(),      "-o", out.string(), "--width", "16",       "--height",
            "16",     "--shadow-map-size", "64", "--frames",   "1",       "--format", "pfm"};
        args.insert(args.end(), extra.begin(), extra.end());
        return runCli(args);
    };
    ProcessResult r = render({"--technique", "second-depth"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // The ground quad is open: 2 of its 14 triangles (the box's 12 are closed).
    EXPECT_NE(r.err.find("2 of 14 triangles lie on surfaces with open edges and 0 on "
                         "mis-wound ones; `second-depth` takes a model's inside"),
              std::string::npos)
        << r.err;
    std::string stats = slurp(out / "stats.json");
    EXPECT_NE(stats.find("\"name\": \"auto (exterior)\""), std::string::npos);
    EXPECT_NE(stats.find("\"exposure\": \"automatic\""), std::string::npos);

    r = render({"--view", "interior", "--ground", "--double-sided"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("open edges"), std::string::npos) << "hard needs no closed surfaces";
    stats = slurp(out / "stats.json");
    EXPECT_NE(stats.find("\"name\": \"auto (interior)\""), std::string::npos);
    EXPECT_NE(stats.find("\"view\": \"interior\""), std::string::npos);
    EXPECT_NE(stats.find("\"ground\": true"), std::string::npos);
    EXPECT_NE(stats.find("\"double_sided\": true"), std::string::npos);
    EXPECT_NE(stats.find("\"triangles\": 16"), std::string::npos) << "the ground's two";

    r = render({"--view", "inside"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("error: --view: 'inside' is not auto, exterior or interior"),
              std::string::npos)
        << r.err;
    r = render({"--view", "exterior", "--camera", "x"});
    EXPECT_NE(r.exitCode, 0) << "--view and --camera exclude each other";
}

// A lone box without lights, camera or ground: one note line, the ground in stats.json and
// reference.json, both commands seeing the same triangles; --no-ground leaves it out; the two
// options together are one error line.
TEST(CliLights, ALoneModelGetsAGroundWithANoteUnlessNoGround) {
    GltfBuilder b;
    twoUnitBox(b, true);
    const fs::path where = outputScratch("lone-asset");
    fs::create_directories(where);
    const fs::path asset = b.writeGltf(where / "lone.gltf");
    const fs::path out = outputScratch("lone-render"), truth = outputScratch("lone-truth");
    const std::vector<std::string> small = {"--width", "32", "--height", "18", "--format", "pfm"};
    const auto run = [&](std::string command, const fs::path& to, std::vector<std::string> extra) {
        std::vector<std::string> args = {command, asset.string(), "-o", to.string()};
        args.insert(args.end(), small.begin(), small.end());
        if (command == "render")
            args.insert(args.end(), {"--frames", "1", "--shadow-map-size", "64"});
        else
            args.insert(args.end(), {"--samples", "1"});
        args.insert(args.end(), extra.begin(), extra.end());
        return runCli(args);
    };
    ProcessResult r = run("render", out, {});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string note = "penumbra: note: added a ground under 'lone'";
    ASSERT_NE(r.err.find(note), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(note, r.err.find(note) + 1), std::string::npos) << "one line";
    std::string stats = slurp(out / "stats.json");
    EXPECT_NE(stats.find("\"automatic_ground\": true"), std::string::npos) << stats;
    EXPECT_NE(stats.find("\"triangles\": 14"), std::string::npos) << "the box's 12 and 2";
    // What the picture shows, measured: a shadow on at least 1% of it, the box on 15%.
    const nlohmann::json view = nlohmann::json::parse(stats)["view"];
    EXPECT_GE(view["cast_shadow"].get<double>(), 0.01) << stats;
    EXPECT_GE(view["subject"].get<double>(), 0.15) << stats;
    r = run("reference", truth, {});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json reference = nlohmann::json::parse(slurp(truth / "reference.json"));
    EXPECT_EQ(reference["automatic_ground"], true);
    EXPECT_EQ(reference["view"], view) << "the same scene, the same view";

    r = run("render", out, {"--no-ground"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("added a ground"), std::string::npos) << r.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(out / "stats.json"))["view"]["cast_shadow"], 0.0)
        << "nothing receives the box's shadow";
    r = run("render", out, {"--no-ground", "--technique", "second-depth"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("open edges"), std::string::npos) << "a closed box: " << r.err;
    stats = slurp(out / "stats.json");
    EXPECT_NE(stats.find("\"automatic_ground\": false"), std::string::npos);
    EXPECT_NE(stats.find("\"no_ground\": true"), std::string::npos);
    EXPECT_NE(stats.find("\"triangles\": 12"), std::string::npos);

    r = run("render", out, {"--ground", "--no-ground"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("error: --ground excludes --no-ground"), std::string::npos) << r.err;
}
