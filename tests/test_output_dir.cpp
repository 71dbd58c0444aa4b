#include "core/output_dir.h"

#include "penumbra/error.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <optional>
#include <sstream>

namespace fs = std::filesystem;

namespace penumbra {
namespace {

std::vector<uint8_t> bytesOf(const std::string& text) {
    return {text.begin(), text.end()};
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Sorted names in dir, hidden ones included, so leftovers cannot go unnoticed.
std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string stagingName() {
    return ".penumbra-staging-" + std::to_string(::getpid());
}

// Gives each test its own empty directory under the system temp directory.
class StagedOutputDirTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        mTmp = fs::temp_directory_path() /
               ("penumbra-test-" + std::to_string(::getpid()) + "-" + info->name());
        fs::remove_all(mTmp);
        fs::create_directories(mTmp);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(mTmp, ec);
    }
    fs::path mTmp;
};

using StagedOutputDirDeathTest = StagedOutputDirTest;

TEST_F(StagedOutputDirTest, CommitPublishesFilesAndRemovesStaging) {
    fs::path out = mTmp / "a" / "b";
    {
        StagedOutputDir staged(out);
        EXPECT_EQ(staged.path(), out);
        staged.write("one.txt", bytesOf("1"));
        staged.write("two.bin", bytesOf("22"));
        staged.write("one.txt", bytesOf("111")); // rewrite replaces, not duplicates
        EXPECT_EQ(staged.staged(), (std::vector<std::string>{"one.txt", "two.bin"}));
        EXPECT_EQ(entries(out), std::vector<std::string>{stagingName()}); // nothing visible yet
        staged.commit();
        EXPECT_EQ(entries(out), (std::vector<std::string>{"one.txt", "two.bin"}));
    }
    EXPECT_EQ(entries(out), (std::vector<std::string>{"one.txt", "two.bin"}));
    EXPECT_EQ(readText(out / "one.txt"), "111");
    EXPECT_EQ(readText(out / "two.bin"), "22");
}

TEST_F(StagedOutputDirTest, CommitReplacesExistingFiles) {
    writeText(mTmp / "result.txt", "old");
    writeText(mTmp / "other.txt", "other");
    StagedOutputDir staged(mTmp);
    staged.write("result.txt", bytesOf("new"));
    staged.commit();
    EXPECT_EQ(readText(mTmp / "result.txt"), "new");
    EXPECT_EQ(readText(mTmp / "other.txt"), "other");
    EXPECT_EQ(entries(mTmp), (std::vector<std::string>{"other.txt", "result.txt"}));
}

TEST_F(StagedOutputDirTest, UnwindingRemovesEverythingItCreated) {
    fs::path keep = mTmp / "keep";
    fs::create_directory(keep);
    try {
        StagedOutputDir staged(keep / "x" / "y");
        staged.write("image.png", bytesOf("png"));
        throw std::runtime_error("render failed");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(entries(mTmp), std::vector<std::string>{"keep"});
    EXPECT_TRUE(entries(keep).empty());
}

TEST_F(StagedOutputDirTest, UnwindingLeavesPreexistingDirectoryUntouched) {
    writeText(mTmp / "keep.txt", "keep");
    writeText(mTmp / "out.png", "old");
    {
        StagedOutputDir staged(mTmp);
        staged.write("out.png", bytesOf("new"));
        staged.write("new.txt", bytesOf("x"));
    }
    EXPECT_EQ(entries(mTmp), (std::vector<std::string>{"keep.txt", "out.png"}));
    EXPECT_EQ(readText(mTmp / "keep.txt"), "keep");
    EXPECT_EQ(readText(mTmp / "out.png"), "old");
}

TEST_F(StagedOutputDirTest, TrailingSeparatorStillRemovesCreatedDirectory) {
    { StagedOutputDir staged(fs::path(mTmp.string() + "/x/")); }
    EXPECT_TRUE(entries(mTmp).empty());
}

TEST_F(StagedOutputDirTest, PathBelowRegularFileThrowsAndLeavesNothing) {
    writeText(mTmp / "file", "data");
    fs::path out = mTmp / "file" / "sub" / "out";
    try {
        StagedOutputDir staged(out);
        ADD_FAILURE() << "created a directory below a regular file";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), out.string());
        EXPECT_NE(std::string(e.what()).find("cannot create directory"), std::string::npos);
    }
    EXPECT_EQ(entries(mTmp), std::vector<std::string>{"file"});
    EXPECT_EQ(readText(mTmp / "file"), "data");
}

TEST_F(StagedOutputDirTest, RegularFileAsOutputDirectoryIsRejected) {
    writeText(mTmp / "file", "data");
    try {
        StagedOutputDir staged(mTmp / "file");
        ADD_FAILURE() << "accepted a regular file";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("exists and is not a directory"), std::string::npos);
    }
    EXPECT_EQ(readText(mTmp / "file"), "data");
}

TEST_F(StagedOutputDirTest, ReadOnlyParentThrowsAndLeavesNothing) {
    if (::geteuid() == 0)
        GTEST_SKIP() << "root ignores permission bits";
    fs::path ro = mTmp / "ro";
    fs::create_directory(ro);
    ASSERT_EQ(::chmod(ro.c_str(), 0555), 0);
    EXPECT_THROW(StagedOutputDir(ro / "new" / "out"), InputError);
    EXPECT_THROW(StagedOutputDir{ro}, InputError); // staging directory cannot be created
    EXPECT_TRUE(entries(ro).empty());
    ::chmod(ro.c_str(), 0755);
}

TEST_F(StagedOutputDirTest, StaleStagingDirectoryIsReplaced) {
    fs::create_directories(mTmp / stagingName() / "junk");
    StagedOutputDir staged(mTmp);
    staged.write("f", bytesOf("f"));
    staged.commit();
    EXPECT_EQ(entries(mTmp), std::vector<std::string>{"f"});
}

TEST_F(StagedOutputDirTest, WriteFailureThrowsAndUnstagesTheFile) {
    StagedOutputDir staged(mTmp);
    staged.write("a.txt", bytesOf("a"));
    fs::create_directories(mTmp / stagingName() / "b.txt" / "block"); // fopen gets EISDIR
    try {
        staged.write("b.txt", bytesOf("b"));
        ADD_FAILURE() << "write into a directory succeeded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), (mTmp / "b.txt").string());
    }
    EXPECT_EQ(staged.staged(), std::vector<std::string>{"a.txt"});
}

TEST_F(StagedOutputDirTest, FullDiskThrowsAndUnstagesTheFile) {
    // RLIMIT_FSIZE makes writes fail with EFBIG like a full disk, and binds root too.
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    if (old.rlim_max != RLIM_INFINITY && old.rlim_max < 4096)
        GTEST_SKIP();
    StagedOutputDir staged(mTmp);
    auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit small = old;
    small.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    bool threw = false;
    try {
        staged.write("big.bin", std::vector<uint8_t>(1 << 20, 7));
    } catch (const InputError&) {
        threw = true;
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, oldHandler);
    EXPECT_TRUE(threw);
    EXPECT_TRUE(staged.staged().empty());
    EXPECT_TRUE(entries(mTmp / stagingName()).empty());
}

TEST_F(StagedOutputDirTest, CommitRefusesDirectoryInTheWayBeforeMovingAnything) {
    fs::create_directory(mTmp / "b.txt");
    {
        StagedOutputDir staged(mTmp);
        staged.write("a.txt", bytesOf("a"));
        staged.write("b.txt", bytesOf("b"));
        EXPECT_THROW(staged.commit(), InputError);
    }
    EXPECT_EQ(entries(mTmp), std::vector<std::string>{"b.txt"});
}

TEST_F(StagedOutputDirTest, MovesTransferOwnership) {
    std::optional<StagedOutputDir> first;
    first.emplace(mTmp / "one");
    first->write("f", bytesOf("f"));
    StagedOutputDir second(std::move(*first));
    first.reset(); // a moved-from object must not clean up
    EXPECT_EQ(second.staged(), std::vector<std::string>{"f"});

    StagedOutputDir third(mTmp / "two");
    third = std::move(second); // discards "two", takes over "one"
    EXPECT_EQ(entries(mTmp), std::vector<std::string>{"one"});
    third.commit();
    EXPECT_EQ(readText(mTmp / "one" / "f"), "f");
}

TEST_F(StagedOutputDirDeathTest, NonPlainNamesAreProgrammerErrors) {
    StagedOutputDir staged(mTmp);
    EXPECT_DEATH(staged.write("../escape", bytesOf("x")), "plain file name");
    EXPECT_DEATH(staged.write("..", bytesOf("x")), "plain file name");
    EXPECT_DEATH(staged.write("", bytesOf("x")), "plain file name");
}

} // namespace
} // namespace penumbra
