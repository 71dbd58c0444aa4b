// The viewer's frame under fault injection (src/core/fault_injection.h), as the CLI's commands
// are in test_cli_faults.cpp: `penumbra view` of a sun, a spot and a bulb for two frames with a
// screenshot, failing each allocation, object creation (the swapchain's and the interface's too),
// submission and the screenshot's write in turn. Each failing run ends in one `error:` line, a
// non-zero exit, no validation message and no screenshot. One virtual X server serves the whole
// sweep (starting one per run would double its time).
#include "process.h"
#include "scratch_dir.h"
#include "three_light_asset.h"

#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// Xvfb on the first free display from :90, until destroyed.
class VirtualDisplay {
public:
    VirtualDisplay() {
        for (int d = 90; d < 130 && mPid == 0; ++d) {
            const fs::path socket = "/tmp/.X11-unix/X" + std::to_string(d);
            if (fs::exists(socket) || fs::exists("/tmp/.X" + std::to_string(d) + "-lock"))
                continue;
            std::string display = ":" + std::to_string(d), screen = "1280x1024x24";
            std::vector<char*> argv = {const_cast<char*>("/usr/bin/Xvfb"),
                                       display.data(),
                                       const_cast<char*>("-screen"),
                                       const_cast<char*>("0"),
                                       screen.data(),
                                       const_cast<char*>("-nolisten"),
                                       const_cast<char*>("tcp"),
                                       nullptr};
            if (posix_spawn(&mPid, argv[0], nullptr, nullptr, argv.data(), environ) != 0)
                return;
            for (int wait = 0; wait < 100 && !fs::exists(socket); ++wait)
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
            mName = display;
        }
    }
    ~VirtualDisplay() {
        if (mPid > 0) {
            kill(mPid, SIGTERM);
            waitpid(mPid, nullptr, 0);
        }
    }
    const std::string& name() const { return mName; }

private:
    pid_t mPid = 0;
    std::string mName;
};

} // namespace

TEST(ViewerFaults, EveryFaultOfTheFrameEndsInOneErrorLineAndNoScreenshot) {
    ASSERT_TRUE(fs::exists("/usr/bin/Xvfb")) << "Xvfb is missing: run `make deps`";
    const VirtualDisplay display;
    ASSERT_FALSE(display.name().empty()) << "no free X display from :90";
    setenv("DISPLAY", display.name().c_str(), 1);
    const fs::path dir = outputScratch("viewer-faults");
    const std::string asset = threeLightAsset(dir / "asset").string();
    const fs::path shot = dir / "shot" / "shot.png";
    const std::vector<std::string> sites = {"allocation", "creation", "submit", "write"};
    const bool everyPoint = std::getenv("PENUMBRA_FAULT_EVERY_POINT") != nullptr;
    for (const std::string& site : sites) {
        size_t lastFailed = 0;
        // Creations: the first 8 and every 8th after them, unless `make faults` asks for all.
        for (size_t n = 1; n < 2000; n += site == "creation" && !everyPoint && n >= 8 ? 8 : 1) {
            fs::remove_all(shot.parent_path());
            setenv("PENUMBRA_FAULT", (site + ":" + std::to_string(n)).c_str(), 1);
            const ProcessResult r = runProcess({PENUMBRA_CLI_PATH, "--validation", "view", asset,
                                                "--frames", "2", "--screenshot", shot.string()});
            unsetenv("PENUMBRA_FAULT");
            if (r.exitCode == 0) {
                std::printf("view: %zu or more %s points, each failure refused cleanly\n",
                            lastFailed, site.c_str());
                EXPECT_TRUE(fs::exists(shot));
                EXPECT_GT(lastFailed, site == "write" ? 0u : 1u) << site;
                break;
            }
            const std::string at = "view, " + site + " " + std::to_string(n);
            EXPECT_TRUE(r.exitCode == 2 || r.exitCode == 3) << at << " exit " << r.exitCode << "\n"
                                                            << r.err;
            EXPECT_EQ(errorLines(r.err), 1u) << at << "\n" << r.err;
            EXPECT_NE(r.err.find(expectedMessage(site)), std::string::npos) << at << "\n" << r.err;
            EXPECT_EQ(r.err.find("vulkan validation"), std::string::npos) << at << "\n" << r.err;
            EXPECT_FALSE(fs::exists(shot)) << at << ": a screenshot was left";
            if (::testing::Test::HasFailure())
                return;
            lastFailed = n;
        }
    }
}
