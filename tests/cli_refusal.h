#pragma once
// One refused command line: the CLI exits non-zero with one `error:` line (the last on stderr,
// after nothing but progress lines) and leaves no output behind.
#include "process.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace penumbra::test {

struct BadInput {
    const char* name;
    std::vector<std::string> args; // "{out}" is replaced by a fresh output path
    const char* expected;          // substring of the error line
};

inline void expectOneErrorLineAndNoOutput(const BadInput& bad) {
    const std::filesystem::path out = outputScratch(std::string("out-") + bad.name);
    std::vector<std::string> args;
    for (const std::string& a : bad.args)
        args.push_back(a == "{out}" ? out.string() : a);
    const ProcessResult r = runCli(args);
    EXPECT_GT(r.exitCode, 0) << "must fail cleanly (exit code -1 means it crashed)";
    ASSERT_FALSE(r.err.empty());
    ASSERT_EQ(r.err.back(), '\n') << r.err;
    const size_t lastStart = r.err.rfind('\n', r.err.size() - 2) + 1; // npos + 1 == 0
    EXPECT_EQ(r.err.compare(lastStart, 7, "error: "), 0) << r.err;
    EXPECT_EQ(r.err.find("error: "), lastStart) << "one error line:\n" << r.err;
    std::istringstream lines(r.err.substr(0, lastStart));
    for (std::string line; std::getline(lines, line);)
        EXPECT_EQ(line.rfind("penumbra: ", 0), 0u) << "unexpected stderr line: " << line;
    EXPECT_NE(r.err.find(bad.expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "partial output left at " << out;
}

} // namespace penumbra::test
