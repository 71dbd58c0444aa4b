#pragma once
// Runs the penumbra CLI as a child process (posix_spawn, no shell) and captures its output.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace penumbra::test {

struct ProcessResult {
    int exitCode = -1; // -1: killed by a signal (a crash)
    std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Runs argv[0] (a path, not looked up in PATH) with the given arguments.
inline ProcessResult runProcess(std::vector<std::string> full) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("penumbra-cli-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string outPath = (dir / "stdout").string(), errPath = (dir / "stderr").string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    std::vector<char*> argv;
    for (std::string& a : full)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    ProcessResult result;
    if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0) {
        int status = 0;
        waitpid(pid, &status, 0);
        result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    posix_spawn_file_actions_destroy(&actions);
    result.out = slurp(outPath);
    result.err = slurp(errPath);
    std::filesystem::remove_all(dir);
    return result;
}

// How many lines of a command's stderr are `error:` lines (a refusal prints exactly one).
inline size_t errorLines(const std::string& err) {
    std::istringstream lines(err);
    size_t count = 0;
    for (std::string line; std::getline(lines, line);)
        count += line.rfind("error:", 0) == 0;
    return count;
}

// What the one error line of a run failed at PENUMBRA_FAULT's `site` must say
// (src/core/fault_injection.h; the CLI's and the viewer's fault sweeps).
inline std::string expectedMessage(const std::string& site) {
    if (site == "allocation")
        return "out of memory allocating";
    if (site == "creation")
        return "out of memory in vk";
    if (site == "submit")
        return "the GPU work failed (VK_ERROR_DEVICE_LOST)";
    if (site == "embree")
        return "embree: ";
    return "No space left on device";
}

// The penumbra CLI, always with the validation layer on; any validation message it prints
// (warnings included) fails the calling test.
inline ProcessResult runCli(const std::vector<std::string>& args) {
    std::vector<std::string> full{PENUMBRA_CLI_PATH, "--validation"};
    full.insert(full.end(), args.begin(), args.end());
    ProcessResult result = runProcess(std::move(full));
    EXPECT_EQ(result.err.find("vulkan validation"), std::string::npos) << result.err;
    return result;
}

} // namespace penumbra::test
