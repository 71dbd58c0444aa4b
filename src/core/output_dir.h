#pragma once
// All-or-nothing command outputs: files are written into a hidden staging directory and only
// renamed into place by commit(), so a failed command leaves no partial results behind.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace penumbra {

// Stages files for an output directory; without commit() the destructor undoes everything the
// object created (staged files, staging directory, and output directories it had to create).
class StagedOutputDir {
public:
    // Creates dir (and missing parents) plus dir/.penumbra-staging-<pid>; throws InputError(dir,
    // ...) if dir is not a directory or cannot be created, after removing whatever it created.
    explicit StagedOutputDir(std::filesystem::path dir);
    // Without commit(), removes staged files, the staging directory and the directories the
    // constructor created (if empty); never throws.
    ~StagedOutputDir();

    StagedOutputDir(StagedOutputDir&& other) noexcept;
    StagedOutputDir& operator=(StagedOutputDir&& other) noexcept;
    StagedOutputDir(const StagedOutputDir&) = delete;
    StagedOutputDir& operator=(const StagedOutputDir&) = delete;

    // Stages a file named name (a plain file name, no '/'), replacing an earlier one of that
    // name; throws InputError(dir/name, ...) if it cannot be written, leaving it unstaged.
    void write(const std::string& name, std::span<const uint8_t> bytes);

    // The final output directory, as given to the constructor.
    std::filesystem::path path() const { return mDir; }
    // Names of the files staged so far, in the order first written.
    std::vector<std::string> staged() const { return mStaged; }

    // Renames every staged file into path() (atomically per file, replacing existing files) and
    // removes the staging directory; throws InputError(dir/name, ...) if a rename fails.
    void commit();

private:
    // Undoes everything this object created; safe to call on a committed or moved-from object.
    void discard() noexcept;

    std::filesystem::path mDir;
    std::filesystem::path mStaging;
    std::vector<std::filesystem::path> mCreatedDirs; // outermost first
    std::vector<std::string> mStaged;
    bool mActive = false; // staging exists and is owned by this object
};

} // namespace penumbra
