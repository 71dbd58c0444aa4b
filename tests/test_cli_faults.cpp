// Fault injection through the CLI (src/core/fault_injection.h): each command runs with
// PENUMBRA_FAULT=SITE:N for N = 1, 2, ... until it succeeds, at every site it reaches:
// allocation (device memory runs out), creation (host memory runs out creating a Vulkan object),
// submit (the device is lost), embree (the ray tracer's memory runs out) and write (the disk is
// full). Every failing run must end in exactly one `error:` line saying what happened, a
// non-zero exit (not a crash or an abort), no validation message (where the layer is on, see
// thorough()) and no output.
#include "process.h"
#include "scratch_dir.h"
#include "three_light_asset.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// Checks one failing run at `site`:`n`; false once a check failed.
bool refusedCleanly(const std::string& at, const std::string& site, const ProcessResult& r,
                    const std::vector<fs::path>& outputs) {
    EXPECT_TRUE(r.exitCode == 2 || r.exitCode == 3) << at << " exit " << r.exitCode << "\n"
                                                    << r.err;
    EXPECT_EQ(errorLines(r.err), 1u) << at << "\n" << r.err;
    EXPECT_NE(r.err.find(expectedMessage(site)), std::string::npos) << at << "\n" << r.err;
    EXPECT_EQ(r.err.find("vulkan validation"), std::string::npos) << at << "\n" << r.err;
    for (const fs::path& o : outputs)
        EXPECT_FALSE(fs::exists(o)) << at << ": a partial output was left: " << o;
    return !::testing::Test::HasFailure();
}

bool everyPoint() {
    return std::getenv("PENUMBRA_FAULT_EVERY_POINT") != nullptr;
}

// `make faults` (PENUMBRA_FAULT_EVERY_POINT=1) tries every point of every command with the
// validation layer on. `make test` does so for render, whose points are the frame's own; compare,
// bench and tune repeat them before their own (more rows, the truth, their files), so there it
// tries the first 8 points of each site and every 4th after them (object creations, which are
// many and take one code path, every 16th), without the layer (render's sweep and the viewer's
// check what the layer sees): a quarter of the time.
bool thorough(const std::string& what) {
    return everyPoint() || what == "render";
}

size_t stepAfter(size_t n, const std::string& site, const std::string& what) {
    return thorough(what) || n < 8 ? 1 : site == "creation" ? 16 : 4;
}

// Sweeps `args` over the points of `site`; `outputs` (the -o directory, or a file and what is
// written beside it in `folder`) must not exist after a failure, and the first must after the
// success. Returns how many points the command passed (the last point that failed).
size_t sweep(const std::string& site, const std::string& what, std::vector<std::string> args,
             const std::vector<fs::path>& outputs, const fs::path& folder = {}) {
    size_t lastFailed = 0;
    for (size_t n = 1; n < 2000; n += stepAfter(n, site, what)) {
        for (const fs::path& o : outputs)
            fs::remove_all(o);
        if (!folder.empty())
            fs::create_directories(folder);
        setenv("PENUMBRA_FAULT", (site + ":" + std::to_string(n)).c_str(), 1);
        std::vector<std::string> full{PENUMBRA_CLI_PATH};
        if (thorough(what))
            full.push_back("--validation");
        full.insert(full.end(), args.begin(), args.end());
        const ProcessResult r = runProcess(std::move(full));
        unsetenv("PENUMBRA_FAULT");
        if (r.exitCode == 0) {
            std::printf("%s: %zu or more %s points, each failure refused cleanly\n", what.c_str(),
                        lastFailed, site.c_str());
            EXPECT_TRUE(fs::exists(outputs.front())) << what;
            return lastFailed;
        }
        if (!refusedCleanly(what + ", " + site + " " + std::to_string(n), site, r, outputs))
            return 0;
        lastFailed = n;
    }
    ADD_FAILURE() << what << ": never succeeded";
    return 0;
}

const std::vector<std::string> kSmall = {"--width",           "24", "--height", "16",
                                         "--shadow-map-size", "64"};

std::vector<std::string> small(std::vector<std::string> args) {
    args.insert(args.end(), kSmall.begin(), kSmall.end());
    return args;
}

// A sun, a spot and a bulb (its cube map), every light type's passes.
std::string threeLights() {
    static const fs::path asset = threeLightAsset(outputScratch("faults-asset"));
    return asset.string();
}

// Sweeps the command `args` (its name first) over each of `sites`. Each must reach at least two
// points (a sweep that stopped at the first would prove little).
void sweepSites(const std::vector<std::string>& sites, const std::vector<std::string>& args,
                const std::vector<fs::path>& outputs, const fs::path& folder = {}) {
    for (const std::string& site : sites)
        EXPECT_GT(sweep(site, args.front(), small(args), outputs, folder), 1u) << site;
}

} // namespace

TEST(CliFaults, RenderEndsEveryFaultInOneErrorLine) {
    const fs::path out = outputScratch("faults-render");
    sweepSites(
        {"allocation", "creation", "submit", "write"},
        {"render", threeLights(), "-o", out.string(), "--technique", "pcss", "--frames", "1"},
        {out});
}

TEST(CliFaults, CompareEndsEveryFaultInOneErrorLine) {
    const fs::path out = outputScratch("faults-compare");
    sweepSites({"allocation", "creation", "submit", "embree", "write"},
               {"compare", threeLights(), "-o", out.string(), "--techniques",
                everyPoint() ? "hard,vsm[mip]" : "hard", "--samples", "1"},
               {out});
}

TEST(CliFaults, BenchEndsEveryFaultInOneErrorLine) {
    const fs::path out = outputScratch("faults-bench");
    const fs::path json = out / "bench.json";
    sweepSites({"allocation", "creation", "submit", "write"},
               {"bench", threeLights(), "-o", json.string(), "--techniques",
                everyPoint() ? "hard,msm" : "hard", "--frames", "1"},
               {json, out / "bench.html"}, out);
}

TEST(CliFaults, TuneEndsEveryFaultInOneErrorLine) {
    const fs::path out = outputScratch("faults-tune");
    sweepSites({"allocation", "creation", "submit", "embree", "write"},
               {"tune", threeLights(), "-o", out.string(), "--technique", "pcf", "--sweep",
                "pcf.size=3,5", "--samples", "1"},
               {out});
}
