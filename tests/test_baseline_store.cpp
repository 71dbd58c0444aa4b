// The stored figures' files as the GPU tests read and write them (tests/baseline_store.h): a
// row measured but not stored fails, a row stored but not measured fails, and writing rounds to
// the six decimals tools/baselines.py compares.
#include "baseline_store.h"
#include "scratch_dir.h"

#include <gtest/gtest-spi.h>

#include <cstdlib>
#include <fstream>

using namespace penumbra::test;

namespace {

std::filesystem::path storedTable(const std::string& rows) {
    const std::filesystem::path root = scratchDir("baselines", "stored", true);
    std::filesystem::create_directories(root / "rows");
    std::ofstream(root / "rows/setup.json") << R"({"setup": "a test", "rows": )" << rows << "}";
    return root;
}

} // namespace

TEST(BaselineStore, ReadsEachRowsFigures) {
    const auto root = storedTable(R"({"hard": {"rmse": 0.02, "acne": 0.5}})");
    BaselineTable table("rows", "setup", "a test", root);
    const Figures* hard = table.stored("hard");
    ASSERT_NE(hard, nullptr);
    EXPECT_EQ(hard->at("rmse"), 0.02);
    EXPECT_EQ(hard->at("acne"), 0.5);
    EXPECT_FALSE(table.writing());
}

TEST(BaselineStore, ARowMeasuredButNotStoredFails) {
    const auto root = storedTable(R"({"hard": {"rmse": 0.02}})");
    EXPECT_NONFATAL_FAILURE(
        {
            BaselineTable table("rows", "setup", "a test", root);
            table.stored("hard");
            EXPECT_EQ(table.stored("pcf"), nullptr);
        },
        "row pcf has no stored figures");
}

TEST(BaselineStore, ARowStoredButNotMeasuredFails) {
    const auto root = storedTable(R"({"hard": {"rmse": 0.02}, "gone": {"rmse": 0.1}})");
    EXPECT_NONFATAL_FAILURE(
        {
            BaselineTable table("rows", "setup", "a test", root);
            table.stored("hard");
        },
        "stored row gone was not measured");
}

TEST(BaselineStore, AMissingFileFailsUnlessWriting) {
    const auto root = scratchDir("baselines", "empty", true);
    EXPECT_NONFATAL_FAILURE(BaselineTable("rows", "setup", "a test", root), "no stored figures");
}

TEST(BaselineStore, WritingStoresWhatWasMeasuredRoundedAndComparesNothing) {
    const auto out = scratchDir("baselines", "written", true);
    ::setenv("PENUMBRA_WRITE_BASELINES", out.c_str(), 1);
    {
        BaselineTable table("rows", "setup", "a test", scratchDir("baselines", "none", true));
        EXPECT_TRUE(table.writing());
        EXPECT_EQ(table.stored("hard"), nullptr); // no failure: nothing is compared
        table.record("hard", {{"rmse", 0.01234567}, {"leak", 0.0}});
    }
    ::unsetenv("PENUMBRA_WRITE_BASELINES");
    std::ifstream in(out / "rows/setup.json");
    ASSERT_TRUE(in.good());
    const nlohmann::json written = nlohmann::json::parse(in);
    EXPECT_EQ(written.at("setup"), "a test");
    EXPECT_DOUBLE_EQ(written.at("rows").at("hard").at("rmse").get<double>(), 0.012346);
    EXPECT_EQ(written.at("rows").at("hard").at("leak").get<double>(), 0.0);
}
