// Fault injection through the CLI: each command runs with PENUMBRA_FAULT=allocation:N for
// N = 1, 2, ... (the Nth device-memory allocation fails as out of device memory) until it
// succeeds. Every failing run must end in exactly one `error:` line naming what ran out, a
// non-zero exit (not a crash or an abort), no validation message and no output directory.
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

// Sweeps `args` over every allocation; `outputs` (the -o directory, or a file and what is written
// beside it in `folder`) must not exist after a failure, and the first must after the success.
// Returns how many allocations the command made.
size_t sweepAllocations(const std::string& what, std::vector<std::string> args,
                        const std::vector<fs::path>& outputs, const fs::path& folder = {}) {
    for (size_t n = 1; n < 400; ++n) {
        for (const fs::path& o : outputs)
            fs::remove_all(o);
        if (!folder.empty())
            fs::create_directories(folder);
        setenv("PENUMBRA_FAULT", ("allocation:" + std::to_string(n)).c_str(), 1);
        const ProcessResult r = runCli(args);
        unsetenv("PENUMBRA_FAULT");
        if (r.exitCode == 0) {
            std::printf("%s: %zu device allocations, each failure refused cleanly\n", what.c_str(),
                        n - 1);
            EXPECT_TRUE(fs::exists(outputs.front())) << what;
            return n - 1;
        }
        const std::string at = what + ", allocation " + std::to_string(n);
        EXPECT_TRUE(r.exitCode == 2 || r.exitCode == 3) << at << " exit " << r.exitCode << "\n"
                                                        << r.err;
        EXPECT_EQ(errorLines(r.err), 1u) << at << "\n" << r.err;
        EXPECT_NE(r.err.find("out of memory allocating"), std::string::npos) << at << "\n" << r.err;
        for (const fs::path& o : outputs)
            EXPECT_FALSE(fs::exists(o)) << at << ": a partial output was left: " << o;
        if (::testing::Test::HasFailure())
            return 0;
    }
    ADD_FAILURE() << what << ": never succeeded";
    return 0;
}

} // namespace

TEST(CliFaults, EveryDeviceAllocationFailureEndsInOneErrorLine) {
    const fs::path out = outputScratch("faults");
    const std::vector<std::string> small = {"--width",           "24", "--height", "16",
                                            "--shadow-map-size", "64"};
    auto with = [&](std::vector<std::string> args) {
        args.insert(args.end(), small.begin(), small.end());
        return args;
    };
    // A sun, a spot and a bulb (showcase's sun with room's bulb is two scenes; demo has all).
    EXPECT_GT(sweepAllocations("render",
                               with({"render", "builtin:demo", "-o", out.string(), "--technique",
                                     "pcss", "--frames", "1"}),
                               {out}),
              5u);
    EXPECT_GT(sweepAllocations("compare",
                               with({"compare", "builtin:demo", "-o", out.string(), "--techniques",
                                     "hard,vsm", "--samples", "1"}),
                               {out}),
              5u);
    const fs::path json = out / "bench.json";
    EXPECT_GT(sweepAllocations("bench",
                               with({"bench", "builtin:demo", "-o", json.string(), "--techniques",
                                     "hard,msm", "--frames", "1"}),
                               {json, out / "bench.html"}, out),
              5u);
}
