// Fault injection through the CLI: each command runs with PENUMBRA_FAULT=SITE:N for N = 1, 2, ...
// until it succeeds: allocation (the Nth device-memory allocation fails as out of device memory)
// and submit (the Nth submission reports the device lost). Every failing run must end in exactly
// one `error:` line saying what happened, a non-zero exit (not a crash or an abort), no
// validation message and no output.
#include "process.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

size_t errorLines(const std::string& err) {
    std::istringstream lines(err);
    size_t count = 0;
    for (std::string line; std::getline(lines, line);)
        count += line.rfind("error:", 0) == 0;
    return count;
}

// Sweeps `args` over every point of `site`; `outputs` (the -o directory, or a file and what is
// written beside it in `folder`) must not exist after a failure, and the first must after the
// success. Returns how many points the command passed.
size_t sweep(const std::string& site, const std::string& what, std::vector<std::string> args,
             const std::vector<fs::path>& outputs, const fs::path& folder = {}) {
    const std::string said = site == "allocation" ? "out of memory allocating"
                                                  : "the GPU work failed (VK_ERROR_DEVICE_LOST)";
    for (size_t n = 1; n < 400; ++n) {
        for (const fs::path& o : outputs)
            fs::remove_all(o);
        if (!folder.empty())
            fs::create_directories(folder);
        setenv("PENUMBRA_FAULT", (site + ":" + std::to_string(n)).c_str(), 1);
        const ProcessResult r = runCli(args);
        unsetenv("PENUMBRA_FAULT");
        if (r.exitCode == 0) {
            std::printf("%s: %zu %s points, each failure refused cleanly\n", what.c_str(), n - 1,
                        site.c_str());
            EXPECT_TRUE(fs::exists(outputs.front())) << what;
            return n - 1;
        }
        const std::string at = what + ", " + site + " " + std::to_string(n);
        EXPECT_TRUE(r.exitCode == 2 || r.exitCode == 3) << at << " exit " << r.exitCode << "\n"
                                                        << r.err;
        EXPECT_EQ(errorLines(r.err), 1u) << at << "\n" << r.err;
        EXPECT_NE(r.err.find(said), std::string::npos) << at << "\n" << r.err;
        for (const fs::path& o : outputs)
            EXPECT_FALSE(fs::exists(o)) << at << ": a partial output was left: " << o;
        if (::testing::Test::HasFailure())
            return 0;
    }
    ADD_FAILURE() << what << ": never succeeded";
    return 0;
}

} // namespace

TEST(CliFaults, EveryDeviceAllocationAndSubmitFailureEndsInOneErrorLine) {
    const fs::path out = outputScratch("faults");
    const std::vector<std::string> small = {"--width",           "24", "--height", "16",
                                            "--shadow-map-size", "64"};
    auto with = [&](std::vector<std::string> args) {
        args.insert(args.end(), small.begin(), small.end());
        return args;
    };
    const fs::path json = out / "bench.json";
    // builtin:demo has a sun, a spot and a bulb.
    for (const std::string site : {"allocation", "submit"}) {
        EXPECT_GT(sweep(site, "render",
                        with({"render", "builtin:demo", "-o", out.string(), "--technique", "pcss",
                              "--frames", "1"}),
                        {out}),
                  1u);
        EXPECT_GT(sweep(site, "compare",
                        with({"compare", "builtin:demo", "-o", out.string(), "--techniques",
                              "hard,vsm", "--samples", "1"}),
                        {out}),
                  1u);
        EXPECT_GT(sweep(site, "bench",
                        with({"bench", "builtin:demo", "-o", json.string(), "--techniques",
                              "hard,msm", "--frames", "1"}),
                        {json, out / "bench.html"}, out),
                  1u);
    }
}
