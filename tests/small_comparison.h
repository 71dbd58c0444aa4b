#pragma once
// One small `compare` of every technique on builtin:showcase, rendered once per test process
// and shared by the CLI tests that read its files.
#include "process.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace penumbra::test {

inline const std::filesystem::path& smallComparison() {
    static const std::filesystem::path out = [] {
        const std::filesystem::path dir = outputScratch("compare-ok");
        const ProcessResult r =
            runCli({"compare", "builtin:showcase", "-o", dir.string(), "--width", "120", "--height",
                    "80", "--shadow-map-size", "512", "--frames", "1", "--samples", "4"});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return dir;
    }();
    return out;
}

} // namespace penumbra::test
