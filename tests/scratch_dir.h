#pragma once
// Per-process scratch folders for tests that write files: <tmp>/penumbra-<suite>-<pid>/<name>.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace penumbra::test {

// Creates (and returns) the folder; `fresh` empties it first.
inline std::filesystem::path scratchDir(const std::string& suite, const std::string& name = {},
                                        bool fresh = false) {
    const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                    ("penumbra-" + suite + "-" + std::to_string(::getpid())) / name;
    if (fresh)
        std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

// A path for an output folder the CLI creates: its parent exists, the folder itself does not.
inline std::filesystem::path outputScratch(const std::string& name) {
    const std::filesystem::path p = scratchDir("test", name, true);
    std::filesystem::remove(p);
    return p;
}

} // namespace penumbra::test
