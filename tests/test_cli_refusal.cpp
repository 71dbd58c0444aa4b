// sdf.refuse through the commands (docs/cli.md, compare): a compare skips the refused sdf row and
// keeps the others, whichever position it held; a compare of nothing but refused rows and a
// render stop with one error line naming the scene and write nothing.
#include "process.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

// A long scene under a low sun that sdf's field cannot hold (5x hard's RMSE on the audit's grid).
const std::vector<std::string> kRefused = {
    "builtin:gen/long?seed=2", "--width", "256", "--height", "144", "--frames", "1"};

std::vector<std::string> with(std::vector<std::string> head, const std::vector<std::string>& tail) {
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
}

} // namespace

TEST(CliRefusal, CompareSkipsARefusedSdfRowAndKeepsTheOthers) {
    const fs::path out = outputScratch("sdf-refused");
    const ProcessResult r = runCli(
        with({"compare"},
             with(kRefused, {"-o", out.string(), "--techniques", "sdf,hard", "--samples", "16"})));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("penumbra: sdf audit: RMSE"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("warning: sdf skipped: "), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("sdf                    skipped: "), std::string::npos) << r.out;
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"))["techniques"];
    ASSERT_TRUE(metrics.contains("hard"));
    EXPECT_TRUE(metrics["hard"].contains("rmse"));
    ASSERT_TRUE(metrics.contains("sdf"));
    EXPECT_NE(metrics["sdf"]["skipped"].get<std::string>().find("sdf refuses this view"),
              std::string::npos)
        << metrics["sdf"];
    EXPECT_FALSE(fs::exists(out / "sdf.image.png"));
    EXPECT_TRUE(fs::exists(out / "hard.image.png"));
}

TEST(CliRefusal, RenderAndACompareOfRefusedRowsStopWithOneErrorLine) {
    for (const std::vector<std::string>& command :
         {std::vector<std::string>{"render", "--technique", "sdf"},
          std::vector<std::string>{"compare", "--techniques", "sdf", "--samples", "16"}}) {
        const fs::path out = outputScratch("sdf-refused-" + command[0]);
        fs::remove_all(out);
        const ProcessResult r = runCli(with(with(command, kRefused), {"-o", out.string()}));
        EXPECT_NE(r.exitCode, 0) << command[0];
        EXPECT_EQ(errorLines(r.err), 1u) << r.err;
        EXPECT_EQ(r.err.find("warning:"), std::string::npos) << "no warning before the error";
        EXPECT_NE(r.err.find("error: gen/long?seed=2: sdf refuses this view"), std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(out)) << command[0] << " left " << out;
    }
}
