// `render --fps` and `render --motion` (issues 59 and 61): a scene played frame by frame, each
// pose the next frame of one renderer. Its poses are `render --time`'s, its passes timed in every
// pose, its virtual pages drawn as the frame before asked, and its motion vectors the last
// frame's.
#include "core/image_io.h"
#include "process.h"
#include "scratch_dir.h"
#include "sliding_box.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

// render builtin:pendulum with hard at a small size, and `extra`; its output folder.
fs::path renderPendulum(const std::string& name, std::vector<std::string> extra) {
    const fs::path out = outputScratch(name);
    std::vector<std::string> args{
        "render", "builtin:pendulum",  "-o",  out.string(),  "--width", "96",       "--height",
        "64",     "--shadow-map-size", "256", "--technique", "hard",    "--format", "pfm"};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return out;
}

} // namespace

// A skinned figure played: the skin pass runs in every pose after the first (which is placed in
// its warm-up), and has a time in each pose all the same, 0 in the first, as every pass has.
TEST(CliPlay, RenderFpsListsEveryPassForEveryPose) {
    const fs::path out = outputScratch("fps-walker");
    const ProcessResult r = runCli({"render", "builtin:walker", "-o", out.string(), "--width", "96",
                                    "--height", "64", "--shadow-map-size", "256", "--technique",
                                    "hard", "--format", "pfm", "--fps", "30", "--frames", "3"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const J stats = J::parse(slurp(out / "stats.json"));
    ASSERT_TRUE(stats["gpu_ms_per_frame"].contains("skin"));
    EXPECT_EQ(stats["gpu_ms_per_frame"]["skin"][0].get<double>(), 0.0) << "warmed";
    for (const auto& [pass, times] : stats["gpu_ms_per_frame"].items())
        EXPECT_EQ(times.size(), 3u) << pass;
}

// render --fps plays its timed frames: 16 at 60 a second from 0.25 s end at 0.5 s (the bottom
// of the swing, where the ball is fastest), on render --time 0.5's picture and not on the pose
// a frame later; stats.json holds each pass's time in each of the 16 poses and the rate.
TEST(CliPlay, RenderFpsPlaysItsTimedFrames) {
    const fs::path played =
        renderPendulum("fps-played", {"--time", "0.25", "--fps", "60", "--frames", "16"});
    const fs::path at = renderPendulum("fps-at", {"--time", "0.5", "--frames", "1"});
    const fs::path later =
        renderPendulum("fps-later", {"--time", "0.516666666667", "--frames", "1"});
    EXPECT_EQ(slurp(played / "visibility.pfm"), slurp(at / "visibility.pfm"));
    EXPECT_NE(slurp(played / "visibility.pfm"), slurp(later / "visibility.pfm"));
    const J stats = J::parse(slurp(played / "stats.json"));
    EXPECT_EQ(stats["scene"]["time"], 0.5);
    EXPECT_EQ(stats["frames"]["timed"], 16);
    EXPECT_EQ(stats["frames"]["fps"], 60.0);
    ASSERT_TRUE(stats["gpu_ms_per_frame"].contains("shadow"));
    EXPECT_EQ(stats["gpu_ms_per_frame"]["shadow"].size(), 16u);
    for (const auto& [pass, times] : stats["gpu_ms_per_frame"].items()) { // each the median
        std::vector<double> sorted = times.get<std::vector<double>>();
        ASSERT_EQ(sorted.size(), 16u) << pass;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_DOUBLE_EQ(stats["gpu_ms"][pass].get<double>(), 0.5 * (sorted[7] + sorted[8]))
            << pass;
    }
    EXPECT_FALSE(J::parse(slurp(at / "stats.json"))["frames"].contains("fps"));
    // Without --time it plays from 0 s, the animation's start, not the nodes' rest pose: the
    // sliding box stands at x = 0.5 at 0 s and at 0 at rest.
    const fs::path box = boxAsset(scratchDir("fps") / "box", /*animated=*/true);
    const auto renderBox = [&](const std::string& name, std::vector<std::string> extra) {
        const fs::path out = outputScratch(name);
        std::vector<std::string> args{"render",   box.string(), "-o",       out.string(),
                                      "--width",  "64",         "--height", "48",
                                      "--format", "pfm",        "--frames", "1"};
        args.insert(args.end(), extra.begin(), extra.end());
        EXPECT_EQ(runCli(args).exitCode, 0);
        return slurp(out / "visibility.pfm");
    };
    const std::string fromStart = renderBox("fps-box", {"--fps", "30"});
    EXPECT_EQ(fromStart, renderBox("box-zero", {"--time", "0"}));
    EXPECT_NE(fromStart, renderBox("box-rest", {}));
}

// Each played frame is framed as the first: the box alone under its automatic camera, light and
// ground, played at 2 frames a second, draws its frame at 0.5 s from the camera and under the
// light of 0 s, with the ground (its pixels the same within the box's own move), not with the
// camera and light 0.5 s frames alone.
TEST(CliPlay, RenderFpsFramesEachPoseAsTheFirst) {
    const fs::path unlit = boxAsset(scratchDir("fps") / "unlit", /*animated=*/true, /*lit=*/false);
    struct Frame {
        J stats;
        penumbra::FloatImage visibility;
    };
    const auto render = [&](const std::string& name, std::vector<std::string> extra) {
        const fs::path out = outputScratch(name);
        std::vector<std::string> args{"render", unlit.string(), "-o", out.string(), "--width",
                                      "64",     "--height",     "48", "--format",   "pfm"};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = runCli(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return Frame{J::parse(slurp(out / "stats.json")),
                     penumbra::readPfm(out / "visibility.pfm")};
    };
    const Frame played = render("fps-framed", {"--fps", "2", "--frames", "2"});
    const Frame start = render("fps-start", {"--time", "0", "--frames", "1"});
    const Frame alone = render("fps-alone", {"--time", "0.5", "--frames", "1"});
    ASSERT_EQ(played.stats["scene"]["time"], 0.5);
    EXPECT_EQ(played.stats["camera"], start.stats["camera"]);
    EXPECT_NE(played.stats["camera"], alone.stats["camera"]);
    EXPECT_EQ(played.stats["lights"][0]["direction"], start.stats["lights"][0]["direction"]);
    const auto surface = [](const penumbra::FloatImage& image) {
        return std::count_if(image.pixels.begin(), image.pixels.end(),
                             [](float v) { return std::isfinite(v); });
    };
    EXPECT_NEAR(double(surface(played.visibility)), double(surface(start.visibility)),
                0.1 * double(surface(start.visibility)))
        << "the ground of the first frame holds";
}

TEST(CliPlay, RenderFpsRefusesAStillSceneAndRatesOutOfRange) {
    const fs::path out = outputScratch("fps-refused");
    ProcessResult r = runCli({"render", "builtin:resting", "-o", out.string(), "--fps", "60"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "error: --fps: 'builtin:resting' has no animation and no light that orbits: "
                     "nothing would move\n");
    // A rate so slow that the second frame's time overflows is refused before the first frame.
    r = runCli(
        {"render", "builtin:pendulum", "-o", out.string(), "--fps", "1e-320", "--frames", "2"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err.rfind("error: --fps: at 1e-320 a second frame 2 would be at inf s", 0), 0u)
        << r.err;
    for (const char* rate : {"0", "-30", "20000", "nan"}) {
        r = runCli({"render", "builtin:pendulum", "-o", out.string(), "--fps", rate});
        EXPECT_EQ(r.exitCode, 2) << rate;
        EXPECT_EQ(r.err.rfind("error: --fps: ", 0), 0u) << r.err;
    }
    EXPECT_FALSE(fs::exists(out));
}

// render --fps draws each later pose as the next frame, with no warm-up: a virtual map's frame
// renders the pages the frame before asked for (its cost while the light moves), once; the
// bulb's pages each pose, the still sun's once.
TEST(CliPlay, RenderFpsDrawsEachPoseAsOneFrameAfterTheLast) {
    const fs::path out = outputScratch("fps-virtual");
    const ProcessResult r =
        runCli({"render", "builtin:resting", "-o", out.string(), "--width", "96", "--height", "72",
                "--format", "pfm", "--fps", "30", "--frames", "3", "--set", "virtual.enabled=1",
                "--add-light", "point:pos=2,3,0,orbit=4,about=0,0,0,name=bulb"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const J pages = J::parse(slurp(out / "stats.json"))["virtual_maps"];
    // Every pose's frames: the first's two warm-ups and its frame, then one frame a pose, each
    // rendering pages again (the light moved).
    ASSERT_EQ(pages["pages_rendered_per_frame"].size(), 5u) << pages.dump();
    EXPECT_GT(pages["pages_rendered_per_frame"][3].get<int>(), 0) << pages.dump();
    EXPECT_GT(pages["pages_rendered_per_frame"][4].get<int>(), 0) << pages.dump();
    // The scene's sun: nothing moved under it, its pages stay.
    EXPECT_GT(pages["pages_cached"].get<int>(), 0) << pages.dump();
    EXPECT_LT(pages["pages_cached"].get<int>(), pages["pages_resident"].get<int>());
    EXPECT_EQ(pages["frames_short_of_pool"].get<int>(), 0) << pages.dump();
    EXPECT_EQ(r.err.find("warning: the virtual pool"), std::string::npos) << r.err;
}

// Under still lights a walking figure's frames render again only the pages under where it was
// and where it is: the rest of the floor's pages stay cached from pose to pose.
TEST(CliPlay, AWalkingFigureRendersOnlyThePagesItCrosses) {
    const fs::path out = outputScratch("fps-walker-virtual");
    const ProcessResult r =
        runCli({"render", "builtin:walker", "-o", out.string(), "--width", "96", "--height", "72",
                "--format", "pfm", "--fps", "30", "--frames", "3", "--set", "virtual.enabled=1"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const J pages = J::parse(slurp(out / "stats.json"))["virtual_maps"];
    ASSERT_EQ(pages["pages_rendered_per_frame"].size(), 5u) << pages.dump();
    for (size_t frame : {3, 4}) {
        const int rendered = pages["pages_rendered_per_frame"][frame].get<int>();
        EXPECT_GT(rendered, 0) << pages.dump();
        EXPECT_LT(rendered * 2, pages["pages_resident"].get<int>()) << pages.dump();
    }
    EXPECT_GT(pages["pages_cached"].get<int>(), 0) << pages.dump();
}

// A pool too small for the poses: one warning after the last pose (not one a pose, not none),
// and stats.json counts every frame short of pages: the first pose's second warm-up (the first
// only asks) and each pose's frame.
TEST(CliPlay, APoolTooSmallWhilePlayingIsSaidOnce) {
    const fs::path out = outputScratch("fps-walker-small-pool");
    const ProcessResult r = runCli({"render",   "builtin:walker",
                                    "-o",       out.string(),
                                    "--width",  "96",
                                    "--height", "72",
                                    "--format", "pfm",
                                    "--fps",    "30",
                                    "--frames", "3",
                                    "--set",    "virtual.enabled=1",
                                    "--set",    "virtual.pageSize=32",
                                    "--set",    "virtual.poolSize=256"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string said = "warning: the virtual pool holds 64 pages; ";
    const size_t at = r.err.find(said);
    ASSERT_NE(at, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(said, at + 1), std::string::npos) << "said once: " << r.err;
    EXPECT_NE(r.err.find("raise virtual.poolSize", at), std::string::npos) << r.err;
    const J pages = J::parse(slurp(out / "stats.json"))["virtual_maps"];
    EXPECT_EQ(pages["frames_short_of_pool"].get<int>(), 4) << pages.dump();
    EXPECT_GT(pages["pages_dropped"].get<int>(), 0) << pages.dump();
    const std::string counts = "; 4 of 5 frames (warm-ups included) asked for more (at most ";
    const size_t most = r.err.find(counts, at);
    ASSERT_EQ(most, at + said.size() - 2) << r.err;
    // The most any frame asked for and dropped: the last frame's at least.
    unsigned asked = 0, dropped = 0;
    ASSERT_EQ(
        std::sscanf(r.err.c_str() + most + counts.size(), "%u pages, %u of them", &asked, &dropped),
        2)
        << r.err;
    EXPECT_GE(asked, pages["pages_requested"].get<unsigned>()) << r.err;
    EXPECT_GE(dropped, pages["pages_dropped"].get<unsigned>()) << r.err;
    EXPECT_LT(dropped, asked) << r.err;
}

// render --motion writes the G-buffer's motion vectors: the sliding box's pixels moved in the
// last played frame and the still ground's did not; background is NaN; a frame not played has
// none; without the flag there is no file.
TEST(CliPlay, RenderMotionWritesTheLastFramesMotionVectors) {
    const fs::path box = boxAsset(scratchDir("motion") / "box", /*animated=*/true);
    const auto render = [&](const std::string& name, std::vector<std::string> extra) {
        const fs::path out = outputScratch(name);
        std::vector<std::string> args{"render",   box.string(), "-o",       out.string(),
                                      "--width",  "64",         "--height", "48",
                                      "--format", "pfm",        "--frames", "2"};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = runCli(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return out;
    };
    const fs::path played = render("motion-played", {"--fps", "10", "--motion"});
    const penumbra::FloatImage motion = penumbra::readPfm(played / "motion.pfm");
    const penumbra::FloatImage position = penumbra::readPfm(played / "position.pfm");
    const penumbra::FloatImage normal = penumbra::readPfm(played / "normal.pfm");
    ASSERT_EQ(motion.channels, 3u);
    ASSERT_EQ(motion.pixels.size(), position.pixels.size());
    float ground = std::numeric_limits<float>::infinity(); // the lowest surface seen
    for (size_t i = 0; i < position.pixels.size() / 3; ++i)
        if (std::isfinite(position.pixels[3 * i + 1]))
            ground = std::min(ground, position.pixels[3 * i + 1]);
    // The box (x from -1 to 1 about its place, 0.5 then 0.7 in the last two frames; z from -1
    // to 1) stands on the ground: its lowest pixels lie on the ground's plane too.
    const auto outsideTheBox = [&](size_t i) {
        const float x = position.pixels[3 * i], z = position.pixels[3 * i + 2];
        return x < -0.55f || x > 1.75f || std::abs(z) > 1.05f;
    };
    size_t moving = 0, still = 0, background = 0, wrong = 0;
    for (size_t i = 0; i < motion.pixels.size() / 3; ++i) {
        const float m = std::hypot(motion.pixels[3 * i], motion.pixels[3 * i + 1]);
        if (!std::isfinite(position.pixels[3 * i])) {
            background += 1;
            wrong += !std::isnan(motion.pixels[3 * i]);
        } else if (std::abs(position.pixels[3 * i + 1] - ground) < 1e-4f &&
                   normal.pixels[3 * i + 1] > 0.999f && outsideTheBox(i)) { // the ground
            still += m == 0.0f;
            wrong += m != 0.0f;
        } else {
            moving += m > 0.1f;
        }
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(moving, 20u);
    EXPECT_GT(still, 100u);
    const penumbra::FloatImage rest =
        penumbra::readPfm(render("motion-rest", {"--motion"}) / "motion.pfm");
    size_t restMoving = 0;
    for (size_t i = 0; i < rest.pixels.size() / 3; ++i)
        restMoving += std::isfinite(rest.pixels[3 * i]) &&
                      (rest.pixels[3 * i] != 0.0f || rest.pixels[3 * i + 1] != 0.0f);
    EXPECT_EQ(restMoving, 0u) << "a frame not played";
    EXPECT_FALSE(fs::exists(render("motion-none", {"--fps", "10"}) / "motion.pfm"));
}
