// `penumbra view` under a virtual X server (xvfb-run, which `make deps` installs): its screenshot
// against `render`'s image of the same options for every light type, the interface shown or
// hidden, the display modes (visibility, A/B split, error against the truth) against the files
// `render` and `compare` write, and its errors. Every run has the validation layer on.
#include "viewer_run.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>

namespace penumbra::test {

namespace fs = std::filesystem;

// What the issue checks: the viewer without its interface draws render's picture, for a sun
// (showcase, pcss), a spot light (pcf) and a point light (room: its cube faces).
TEST(ViewerTest, HiddenInterfaceScreenshotIsRendersImage) {
    const std::vector<std::vector<std::string>> cases{
        {"builtin:showcase", "--technique", "pcss", "--width", "640", "--height", "360"},
        {"builtin:spot", "--technique", "pcf", "--width", "320", "--height", "200", "--set",
         "pcf.size=5", "--light-radius", "0.3"},
        {"builtin:room", "--technique", "hard", "--width", "320", "--height", "240",
         "--shadow-map-size", "512"}};
    for (const auto& options : cases) {
        SCOPED_TRACE(options[0]);
        const Rgb rendered = renderImage(options, "render");
        std::vector<std::string> viewOptions = options;
        viewOptions.push_back("--hide-ui");
        const Rgb viewed = viewImage(viewOptions, "view");
        ASSERT_EQ(viewed.width, rendered.width);
        ASSERT_EQ(viewed.height, rendered.height);
        EXPECT_LE(meanDifference(viewed, rendered), 0.5);
    }
}

// Virtual shadow maps in the viewer: its frames (two in flight) ask for pages, render them and
// then reuse them; after a few frames it draws render's picture, for a sun and a point light,
// with the pages decided on the host and on the device (each frame in flight with its own slot
// of the device's inputs).
TEST(ViewerTest, VirtualMapsDrawRendersImage) {
    std::vector<std::vector<std::string>> cases;
    for (const char* decides : {"virtual.deviceDecides=0", "virtual.deviceDecides=1"}) {
        cases.push_back({"builtin:showcase", "--technique", "pcf", "--width", "320", "--height",
                         "200", "--set", "virtual.enabled=1", "--set", decides});
        cases.push_back({"builtin:room", "--technique", "hard", "--width", "320", "--height", "240",
                         "--set", "virtual.enabled=1", "--set", decides});
    }
    for (const auto& options : cases) {
        SCOPED_TRACE(options[0] + " " + options.back());
        const Rgb rendered = renderImage(options, "render-virtual");
        std::vector<std::string> viewOptions = options;
        viewOptions.push_back("--hide-ui");
        const Rgb viewed = viewImage(viewOptions, "view-virtual");
        ASSERT_EQ(viewed.width, rendered.width);
        EXPECT_LE(meanDifference(viewed, rendered), 0.5);
    }
}

// The virtual-map views against the page counts the viewer prints for the same frame: the page
// table of the finest level with pages (one cell per page, red rendered this frame, green cached)
// and the pool (one cell per physical page, bright when rendered this frame), for a sun and a
// point light. Frame 3 renders the pages frame 1 asked for (two frames in flight), frame 4
// renders none.
TEST(ViewerTest, VirtualPageViewsShowTheFramesPages) {
    struct Line {
        uint32_t resident = 0, pool = 0, rendered = 0, cached = 0, levelPages = 0;
        std::string level;
        uint32_t firstX = 0, lastX = 0, firstY = 0, lastY = 0;
    };
    auto lastLine = [](const std::string& out) {
        const std::regex re(R"(virtual pages: requested \d+, resident (\d+) of (\d+), rendered )"
                            R"((\d+), cached (\d+), dropped 0; shown: (.*?)(?: \((\d+) pages\), )"
                            R"(pages (\d+)\.\.(\d+), (\d+)\.\.(\d+))?\n)");
        Line line;
        bool found = false;
        for (auto it = std::sregex_iterator(out.begin(), out.end(), re);
             it != std::sregex_iterator(); ++it) {
            const std::smatch& m = *it;
            auto n = [&](int i) { return static_cast<uint32_t>(std::stoul(m[i].str())); };
            line = {n(1), n(2), n(3), n(4), 0, m[5].str()};
            if (m[6].matched)
                line.levelPages = n(6), line.firstX = n(7), line.lastX = n(8), line.firstY = n(9),
                line.lastY = n(10);
            found = true;
        }
        EXPECT_TRUE(found) << out;
        return line;
    };
    // The colour at the centre of each of the n x n cells of the square grid in the window.
    auto cells = [](const Rgb& shot, uint32_t n) {
        std::vector<std::array<int, 3>> colors;
        const int side = std::min(shot.width, shot.height);
        const int x0 = (shot.width - side) / 2, y0 = (shot.height - side) / 2;
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                const uint8_t* p =
                    shot.at(x0 + int((x + 0.5) * side / n), y0 + int((y + 0.5) * side / n));
                colors.push_back({p[0], p[1], p[2]});
            }
        return colors;
    };
    const std::array<int, 3> kRed{235, 70, 50}, kGreen{60, 175, 85}, kFree{20, 20, 20};
    const std::vector<std::vector<std::string>> scenes{{"builtin:field", "--technique", "pcf"},
                                                       {"builtin:room", "--technique", "hard"}};
    for (const auto& scene : scenes) {
        SCOPED_TRACE(scene[0]);
        for (const std::string frames : {"3", "4"}) {
            SCOPED_TRACE("frames " + frames);
            std::vector<std::string> args = scene;
            args.insert(args.end(), {"--width", "320", "--height", "256", "--set",
                                     "virtual.enabled=1", "--hide-ui", "--show", "pages"});
            ProcessResult r;
            Rgb shot = viewImage(args, "pages", &r, frames);
            Line line = lastLine(r.out);
            if (scene[0] == "builtin:room") {
                EXPECT_TRUE(std::regex_search(line.level, std::regex("light 0 [+-][xyz] level")))
                    << line.level;
            } else { // a sun's levels have no cube faces
                EXPECT_TRUE(std::regex_match(line.level, std::regex(R"(light \d+ level \d+)")))
                    << line.level;
            }
            const uint32_t side = line.lastX + 1 - line.firstX;
            ASSERT_EQ(line.lastY + 1 - line.firstY, side);
            ASSERT_GT(line.levelPages, 0u);
            int red = 0, green = 0, other = 0;
            for (const auto& c : cells(shot, side)) {
                if (c == kRed)
                    ++red;
                else if (c == kGreen)
                    ++green;
                else if (c != kFree)
                    ++other;
            }
            EXPECT_EQ(other, 0) << "kept or dropped pages on a still frame";
            EXPECT_EQ(uint32_t(red + green), line.levelPages);
            if (frames == "3")
                EXPECT_EQ(green, 0) << "every page is new on the first frame that renders";
            else
                EXPECT_EQ(red, 0) << "nothing rendered once the pages are resident";

            args.back() = "pool";
            shot = viewImage(args, "pool", &r, frames);
            line = lastLine(r.out);
            ASSERT_EQ(line.pool, 4096u); // the default pool: 64 x 64 pages
            uint32_t held = 0, bright = 0;
            for (const auto& c : cells(shot, 64)) {
                held += c != kFree;
                bright += *std::max_element(c.begin(), c.end()) >= 200;
            }
            EXPECT_EQ(held, line.resident);
            EXPECT_EQ(bright, line.rendered);
            EXPECT_EQ(line.rendered + line.cached, line.resident); // nothing kept from before
            EXPECT_EQ(line.rendered, frames == "3" ? line.resident : 0u);
        }
    }
}

TEST(ViewerTest, InterfaceIsDrawnOverTheTopLeftUnlessHidden) {
    const std::vector<std::string> options{"builtin:showcase", "--width", "800", "--height", "500"};
    const Rgb hidden = viewImage(
        {options[0], options[1], options[2], options[3], options[4], "--hide-ui"}, "hidden");
    const Rgb shown = viewImage(options, "shown");
    ASSERT_EQ(shown.width, 800);
    auto changed = [&](int x0, int y0, int x1, int y1) {
        size_t n = 0, total = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x, ++total) {
                int d = 0;
                for (int c = 0; c < 3; ++c)
                    d += std::abs(int(shown.at(x, y)[c]) - int(hidden.at(x, y)[c]));
                n += d > 30;
            }
        return double(n) / double(total);
    };
    EXPECT_GT(changed(10, 10, 300, 300), 0.5) << "the panel covers the top left";
    EXPECT_EQ(changed(600, 350, 800, 500), 0.0) << "and nothing else";
}

// --show visibility draws visibility.pfm as grey; the A/B split shows A left of the split column
// and B from it on (render's images of each), with a marker line on the column itself.
TEST(ViewerTest, DisplayModesShowTheFrameTheyName) {
    const std::vector<std::string> scene{"builtin:spot", "--width",     "256", "--height",
                                         "160",          "--technique", "pcf"};
    const fs::path out = scratch("render-vis");
    std::vector<std::string> args{"render", "-o", out.string(), "--frames", "1"};
    args.insert(args.end(), scene.begin(), scene.end());
    ASSERT_EQ(runCli(args).exitCode, 0);
    const FloatImage visibility = readPfm(out / "visibility.pfm");
    std::vector<std::string> show = scene;
    show.insert(show.end(), {"--hide-ui", "--show", "visibility"});
    const Rgb grey = viewImage(show, "show-vis");
    ASSERT_EQ(grey.width * grey.height, static_cast<int>(visibility.pixels.size()));
    size_t finite = 0;
    for (int i = 0; i < grey.width * grey.height; ++i) {
        const float v = visibility.pixels[i];
        const uint8_t* p = &grey.pixels[3 * size_t(i)];
        if (!std::isfinite(v))
            continue;
        ++finite;
        const double expected = 255.0 * std::clamp(v, 0.0f, 1.0f);
        ASSERT_NEAR(p[0], expected, 1.01) << "pixel " << i;
        ASSERT_EQ(p[0], p[1]);
        ASSERT_EQ(p[1], p[2]);
    }
    EXPECT_GT(finite, visibility.pixels.size() / 2);

    // A wide light, so that B's penumbrae differ from A's hard edges.
    std::vector<std::string> a = scene, b = scene;
    a.insert(a.end(), {"--light-radius", "0.8"});
    b.insert(b.end(), {"--light-radius", "0.8"});
    a[6] = "hard";
    b[6] = "pcss";
    const Rgb left = renderImage(a, "render-a"), right = renderImage(b, "render-b");
    std::vector<std::string> split = a;
    split.insert(split.end(), {"--hide-ui", "--compare-with", "pcss"});
    const Rgb both = viewImage(split, "split");
    const int column = 128; // the default split, half the width
    EXPECT_LE(meanDifference(both, left, 0, column), 0.5);
    EXPECT_LE(meanDifference(both, right, column + 1, 256), 0.5);
    EXPECT_GT(meanDifference(left, right, column + 1, 256), 0.5) << "B differs from A there";
}

// --show contact draws the contact layer's own result: where it is black the layer put the pixel
// in shadow, so render's visibility with the layer is the visibility without it times that. On
// the resting objects at a bias that detaches their shadows, it finds pixels the map left lit.
TEST(ViewerTest, ContactViewShowsWhatTheLayerMultipliesIn) {
    const std::vector<std::string> scene{
        "builtin:resting",   "--width", "256",   "--height",        "160",
        "--technique",       "hard",    "--set", "bias.mode=fixed", "--set",
        "bias.constant=0.02"};
    auto visibilityOf = [&](const std::string& length, const std::string& name) {
        const fs::path out = scratch(name);
        std::vector<std::string> args{"render", "-o", out.string(), "--frames", "1"};
        args.insert(args.end(), scene.begin(), scene.end());
        args.insert(args.end(), {"--set", "contact.length=" + length});
        EXPECT_EQ(runCli(args).exitCode, 0);
        return readPfm(out / "visibility.pfm");
    };
    const FloatImage without = visibilityOf("0", "render-no-contact");
    const FloatImage with = visibilityOf("0.3", "render-contact");
    std::vector<std::string> show = scene;
    show.insert(show.end(), {"--set", "contact.length=0.3", "--hide-ui", "--show", "contact"});
    const Rgb contact = viewImage(show, "show-contact");
    ASSERT_EQ(contact.width * contact.height, static_cast<int>(with.pixels.size()));
    size_t found = 0, finite = 0;
    for (int i = 0; i < contact.width * contact.height; ++i) {
        const uint8_t* p = &contact.pixels[3 * size_t(i)];
        ASSERT_EQ(p[0], p[1]);
        ASSERT_EQ(p[1], p[2]);
        ASSERT_TRUE(p[0] == 0 || p[0] == 255) << "pixel " << i << ": " << int(p[0]);
        if (!std::isfinite(with.pixels[i]))
            continue;
        ++finite;
        const float c = p[0] == 255 ? 1.0f : 0.0f;
        ASSERT_NEAR(with.pixels[i], without.pixels[i] * c, 1e-6f) << "pixel " << i;
        found += c == 0.0f && without.pixels[i] > 0.5f;
    }
    EXPECT_GT(finite, with.pixels.size() / 2);
    EXPECT_GE(found, 8u) << "the layer shadows pixels the detached map left lit"; // 14 here
}

// The cascade tint follows the view distance (red nearest, then green, blue, yellow: the ground
// from the bottom of the image up), and a shadow-map layer is shown square and centred, its
// depth as grey (the spot's frustum: nearer casters darker than the ground behind them).
TEST(ViewerTest, CascadeAndShadowMapViewsShowTheirViews) {
    const Rgb tint = viewImage({"builtin:showcase", "--width", "320", "--height", "180",
                                "--hide-ui", "--show", "cascades"},
                               "cascades");
    auto dominant = [](const uint8_t* p) { // 0 red, 1 green, 2 blue
        return p[0] > p[1] && p[0] > p[2] ? 0 : p[1] > p[2] ? 1 : 2;
    };
    EXPECT_EQ(dominant(tint.at(160, 178)), 0) << "the nearest ground: cascade 0";
    int firstGreen = -1;
    for (int y = 178; y > 60 && firstGreen < 0; --y)
        if (dominant(tint.at(300, y)) == 1)
            firstGreen = y;
    EXPECT_GT(firstGreen, 60) << "cascade 1 further up";
    for (int y = 178; y > firstGreen; --y)
        ASSERT_EQ(dominant(tint.at(300, y)), 0) << "row " << y << ": cascade 0 below cascade 1";

    const Rgb map = viewImage({"builtin:spot", "--width", "320", "--height", "200", "--hide-ui",
                               "--show", "shadow-map:0"},
                              "shadow-map");
    for (int y = 0; y < 200; y += 7) { // the letterbox: (320 - 200) / 2 columns each side
        ASSERT_EQ(map.at(59, y)[0], 26) << y;
        ASSERT_EQ(map.at(260, y)[0], 26) << y;
    }
    int darkest = 255, lightest = 0;
    for (int y = 0; y < 200; ++y)
        for (int x = 60; x < 260; ++x) {
            ASSERT_EQ(map.at(x, y)[0], map.at(x, y)[2]) << "grey";
            darkest = std::min<int>(darkest, map.at(x, y)[0]);
            lightest = std::max<int>(lightest, map.at(x, y)[0]);
        }
    EXPECT_LT(darkest + 60, lightest) << "casters in front of the ground";
}

// PCSS's blocker search as the viewer shows it agrees with the visibility render writes: no
// blocker found (a dark blue) only where the pixel is fully lit, and a grey blocker depth wherever
// it is not; the penumbra view colours those pixels by width, not all alike. The receiver's
// horizon is off, so that a pixel is dimmed only by blockers.
TEST(ViewerTest, BlockerSearchViewsAgreeWithTheVisibility) {
    const std::vector<std::string> scene{
        "builtin:spot",   "--width", "256",   "--height",        "160", "--technique", "pcss",
        "--light-radius", "0.6",     "--set", "bias.horizon=off"};
    const fs::path out = scratch("render-pcss");
    std::vector<std::string> args{"render", "-o", out.string(), "--frames", "1"};
    args.insert(args.end(), scene.begin(), scene.end());
    ASSERT_EQ(runCli(args).exitCode, 0);
    const FloatImage visibility = readPfm(out / "visibility.pfm");
    // A surface facing away from the light hides it itself, no blocker needed (visibility.pfm's
    // convention): those pixels, and the terminator's, are left out.
    const FloatImage position = readPfm(out / "position.pfm"), normal = readPfm(out / "normal.pfm");
    const auto stats = nlohmann::json::parse(slurp(out / "stats.json"));
    const auto at = stats["lights"][0]["position"].get<std::vector<float>>();
    auto facesLight = [&](int i) {
        const glm::vec3 p(position.pixels[3 * size_t(i)], position.pixels[3 * size_t(i) + 1],
                          position.pixels[3 * size_t(i) + 2]);
        const glm::vec3 n(normal.pixels[3 * size_t(i)], normal.pixels[3 * size_t(i) + 1],
                          normal.pixels[3 * size_t(i) + 2]);
        return glm::dot(n, glm::normalize(glm::vec3(at[0], at[1], at[2]) - p)) > 0.05f;
    };
    std::vector<std::string> show = scene;
    show.insert(show.end(), {"--hide-ui", "--show", "blocker-depth"});
    const Rgb blockers = viewImage(show, "blockers");
    show.back() = "penumbra";
    const Rgb widths = viewImage(show, "penumbra");
    ASSERT_EQ(blockers.width * blockers.height, static_cast<int>(visibility.pixels.size()));
    auto noBlocker = [](const uint8_t* p) {
        return std::abs(p[0] - 26) <= 1 && std::abs(p[1] - 31) <= 1 && std::abs(p[2] - 77) <= 1;
    };
    size_t shadowed = 0, lit = 0;
    std::set<uint32_t> colours;
    for (int i = 0; i < blockers.width * blockers.height; ++i) {
        const float v = visibility.pixels[i];
        if (!std::isfinite(v) || !facesLight(i))
            continue;
        const uint8_t* b = &blockers.pixels[3 * size_t(i)];
        const uint8_t* w = &widths.pixels[3 * size_t(i)];
        if (noBlocker(b)) {
            ASSERT_EQ(v, 1.0f) << "pixel " << i << ": no blocker, yet not lit";
            ASSERT_TRUE(noBlocker(w)) << "pixel " << i;
            ++lit;
        }
        if (v < 1.0f) {
            ASSERT_FALSE(noBlocker(b)) << "pixel " << i << ": shadowed, yet no blocker";
            ASSERT_TRUE(b[0] == b[1] && b[1] == b[2]) << "pixel " << i << ": a grey depth";
            ASSERT_FALSE(noBlocker(w)) << "pixel " << i;
            colours.insert(uint32_t(w[0]) << 16 | uint32_t(w[1]) << 8 | w[2]);
            ++shadowed;
        }
    }
    EXPECT_GT(lit, 1000u);
    EXPECT_GT(shadowed, 500u);
    EXPECT_GT(colours.size(), 10u) << "penumbra widths vary";
}

// --show error traces the truth for the view and measures the frame as `compare` does: the same
// RMSE and misclassified fraction on the same pixels with the same rays.
TEST(ViewerTest, ErrorViewMeasuresWhatCompareMeasures) {
    const std::vector<std::string> scene{"builtin:showcase", "--width", "200", "--height", "120",
                                         "--light-angle",    "4"};
    const fs::path out = scratch("compare");
    std::vector<std::string> args{
        "compare", "-o", out.string(), "--techniques", "pcss", "--samples", "16", "--frames", "1"};
    args.insert(args.end(), scene.begin(), scene.end());
    const ProcessResult c = runCli(args);
    ASSERT_EQ(c.exitCode, 0) << c.err;
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"));
    std::vector<std::string> view = scene;
    view.insert(view.end(),
                {"--technique", "pcss", "--hide-ui", "--show", "error", "--samples", "16"});
    ProcessResult r;
    const Rgb heat = viewImage(view, "error", &r);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex("RMSE ([0-9.]+), misclassified ([0-9.]+)%")))
        << r.out;
    ASSERT_TRUE(metrics["techniques"].contains("pcss")) << metrics.dump();
    const auto& row = metrics["techniques"]["pcss"];
    EXPECT_NEAR(std::stod(m[1]), row["rmse"].get<double>(), 1e-4) << metrics.dump();
    EXPECT_NEAR(std::stod(m[2]) / 100.0, row["misclassified"].get<double>(), 2e-5);
    // The heat map, not the lit image: the sky has no comparison (a dark checker).
    EXPECT_LT(heat.at(2, 2)[0], 120);
}

TEST(ViewerTest, BadInputIsOneErrorLineAndNoScreenshot) {
    const fs::path shot = scratch("bad") / "shot.png";
    ProcessResult r = runViewer({"builtin:nope", "--frames", "2", "--screenshot", shot.string()});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(shot));
    r = runViewer({"builtin:showcase", "--show", "depth", "--frames", "1"});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("error: --show"), std::string::npos) << r.err;
    r = runViewer({"builtin:showcase", "--screenshot", shot.string()});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
    // No display at all: a clear error, not a crash.
    r = runProcess({"/usr/bin/env", "-u", "DISPLAY", "-u", "WAYLAND_DISPLAY", PENUMBRA_CLI_PATH,
                    "view", "builtin:showcase", "--frames", "1", "--screenshot", shot.string()});
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("error: display"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(shot));
}

} // namespace penumbra::test
