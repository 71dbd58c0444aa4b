// Time in `penumbra view`: an animated scene plays (scripted runs advance a steady 1/60 s a
// frame) and shows the pose `--time` shows at once; lights that orbit play too; a scene that
// nothing moves cannot play. Every run has the validation layer on.
#include "sliding_box.h"
#include "viewer_run.h"

#include <gtest/gtest.h>

#include <fstream>

namespace penumbra::test {

namespace {

// builtin:pendulum in a small window, without the interface, by `technique`.
std::vector<std::string> pendulum(std::vector<std::string> extra,
                                  const std::string& technique = "hard") {
    std::vector<std::string> args{
        "builtin:pendulum", "--technique", technique,           "--width", "320",
        "--height",         "200",         "--shadow-map-size", "512",     "--hide-ui"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

} // namespace

// Played from 0.25 s, 16 frames end on frame 15, at 0.5 s (the bottom of the swing, where the
// ball is fastest): the picture `--time 0.5` shows in one frame, nearer it than the pose a
// frame later or a frame earlier. Without --play the first pose holds.
TEST(ViewerTime, PlayingMovesTheSceneASixtiethOfASecondEachFrame) {
    const Rgb played = viewImage(pendulum({"--time", "0.25", "--play"}), "played", nullptr, "16");
    const Rgb atHalf = viewImage(pendulum({"--time", "0.5"}), "at-half", nullptr, "1");
    const Rgb later = viewImage(pendulum({"--time", "0.516666666667"}), "later", nullptr, "1");
    const Rgb earlier = viewImage(pendulum({"--time", "0.483333333333"}), "earlier", nullptr, "1");
    const Rgb held = viewImage(pendulum({"--time", "0.25"}), "held", nullptr, "16");
    const Rgb start = viewImage(pendulum({"--time", "0.25"}), "start", nullptr, "1");
    ASSERT_EQ(played.width, atHalf.width);
    const double same = meanDifference(played, atHalf);
    EXPECT_LE(same, 0.1); // the same pose: the same picture (a frame off differs by 0.6)
    EXPECT_LT(same, meanDifference(played, later) / 4);
    EXPECT_LT(same, meanDifference(played, earlier) / 4);
    EXPECT_LE(meanDifference(held, start), 0.5);
    EXPECT_GT(meanDifference(held, atHalf), 1.0);
}

// The light sizes the command line set hold through the poses: pcss under a 4-degree sun and a
// spot of radius 0.4 played to 0.5 s draws what it draws at 0.5 s at once.
TEST(ViewerTime, LightSizesHoldAsTheScenePlays) {
    auto with = [&](std::vector<std::string> extra) {
        extra.insert(extra.end(), {"--light-angle", "4", "--light-radius", "0.4"});
        return pendulum(extra, "pcss");
    };
    const Rgb played = viewImage(with({"--time", "0.25", "--play"}), "wide-played", nullptr, "16");
    const Rgb atHalf = viewImage(with({"--time", "0.5"}), "wide-half", nullptr, "1");
    // The same pose draws the same picture; the scene's own sizes differ by 0.09 a channel.
    EXPECT_LE(meanDifference(played, atHalf), 0.01);
}

// An added light that orbits moves with the clock on a still scene: played for 31 frames it
// stands where `--time 0.5` puts it.
TEST(ViewerTime, OrbitingLightsPlayOnAStillScene) {
    const std::vector<std::string> scene{"builtin:resting",
                                         "--technique",
                                         "hard",
                                         "--width",
                                         "320",
                                         "--height",
                                         "200",
                                         "--shadow-map-size",
                                         "512",
                                         "--hide-ui",
                                         "--add-light",
                                         "point:pos=3,3,0,orbit=2,name=bulb"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = scene;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const Rgb played = viewImage(with({"--play"}), "orbit-played", nullptr, "31");
    const Rgb atHalf = viewImage(with({"--time", "0.5"}), "orbit-half", nullptr, "1");
    const Rgb atZero = viewImage(with({"--time", "0"}), "orbit-zero", nullptr, "1");
    EXPECT_LE(meanDifference(played, atHalf), 0.5);
    EXPECT_GT(meanDifference(played, atZero), 1.0);
}

// The clock loops at the animation's end: builtin:town's day (12 s, the sun held at its end
// after it) played from 11.9 s for 13 frames is at 0.1 s, the morning, not the evening held;
// a view put at 12 s without playing shows the evening, as render does.
// A glTF animation without --time starts at 0 s, not at the nodes' rest pose.
TEST(ViewerTime, TheClockLoopsAndStartsAtTheAnimationsStart) {
    const std::vector<std::string> town{"builtin:town", "--technique", "hard", "--width",
                                        "320",          "--height",    "200",  "--shadow-map-size",
                                        "512",          "--hide-ui"};
    auto with = [](std::vector<std::string> args, std::vector<std::string> extra) {
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const Rgb looped = viewImage(with(town, {"--time", "11.9", "--play"}), "looped", nullptr, "13");
    const Rgb morning = viewImage(with(town, {"--time", "0.1"}), "morning", nullptr, "1");
    const Rgb evening = viewImage(with(town, {"--time", "12"}), "evening", nullptr, "1");
    EXPECT_LE(meanDifference(looped, morning), 0.1);
    EXPECT_GT(meanDifference(looped, evening), 1.0);
    // A time put at the end holds there (as render's does) until the scene plays.
    std::vector<std::string> rendered(town.begin(), town.end() - 1); // without --hide-ui
    rendered.insert(rendered.end(), {"--time", "12"});
    EXPECT_LE(meanDifference(evening, renderImage(rendered, "evening-rendered")), 0.5);

    const std::string box = boxAsset(scratch("sliding"), /*animated=*/true).string();
    const std::vector<std::string> view{box,   "--technique", "hard", "--width",
                                        "320", "--height",    "200",  "--hide-ui"};
    const Rgb first = viewImage(view, "box-first", nullptr, "1");
    const Rgb atZero = viewImage(with(view, {"--time", "0"}), "box-zero", nullptr, "1");
    const Rgb atRest =
        renderImage({box, "--technique", "hard", "--width", "320", "--height", "200"}, "box-rest");
    EXPECT_LE(meanDifference(first, atZero), 0.1);
    EXPECT_GT(meanDifference(first, atRest), 0.5) << "at rest the box stands 0.5 to the side";
}

// The file's own camera on an animated node follows it as the scene plays: a camera that slides
// 2 units in a second, played 31 frames from 0, shows what --time 0.5 shows.
TEST(ViewerTime, AFilesAnimatedCameraMovesAsTheScenePlays) {
    const std::filesystem::path dir = scratch("moving-camera");
    nlohmann::json j = nlohmann::json::parse(slurp(boxAsset(dir, /*animated=*/true)));
    j["cameras"] = nlohmann::json::array(
        {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.05}}}}});
    j["nodes"].push_back({{"camera", 0},
                          {"translation", {0.0, 6.0, 9.0}},
                          {"rotation", {-0.2588, 0.0, 0.0, 0.9659}}});
    const size_t eye = j["nodes"].size() - 1;
    j["scenes"][0]["nodes"].push_back(eye);
    nlohmann::json& slide = j["animations"][0];
    const int path = floatAccessor(j, {0.0f, 6.0f, 9.0f, 2.0f, 6.0f, 9.0f}, "VEC3");
    slide["samplers"].push_back({{"input", slide["samplers"][0]["input"]}, {"output", path}});
    slide["channels"].push_back(
        {{"sampler", 1}, {"target", {{"node", eye}, {"path", "translation"}}}});
    const std::string file = (dir / "camera.gltf").string();
    std::ofstream(file) << j.dump();
    const std::vector<std::string> view{file,  "--technique", "hard", "--width",
                                        "320", "--height",    "200",  "--hide-ui"};
    const auto with = [&](std::vector<std::string> args, std::vector<std::string> extra) {
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const Rgb played = viewImage(with(view, {"--play"}), "camera-played", nullptr, "31");
    const Rgb atHalf = viewImage(with(view, {"--time", "0.5"}), "camera-half", nullptr, "1");
    const Rgb atZero = viewImage(with(view, {"--time", "0"}), "camera-zero", nullptr, "1");
    EXPECT_LE(meanDifference(played, atHalf), 0.1);
    EXPECT_GT(meanDifference(played, atZero), 1.0);
}

TEST(ViewerTime, AStillSceneCannotPlay) {
    const ProcessResult r = runViewer({"builtin:resting", "--play", "--frames", "1"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.err, "error: --play: 'builtin:resting' has no animation and no light that "
                     "orbits\n");
}

} // namespace penumbra::test
