#include "core/output_dir.h"

#include "core/fault_injection.h"
#include "penumbra/error.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <utility>

namespace fs = std::filesystem;

namespace penumbra {
namespace {

std::string errnoText(int err) {
    return std::strerror(err);
}

// Strips trailing separators so that walking up from "out/" starts at "out", not "out/" itself.
fs::path withoutTrailingSeparator(fs::path path) {
    while (!path.has_filename() && path.has_relative_path())
        path = path.parent_path();
    return path;
}

bool isDirectory(const fs::path& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

} // namespace

StagedOutputDir::StagedOutputDir(fs::path dir) : mDir(std::move(dir)) {
    if (mDir.empty())
        throw InputError("output directory", "path is empty");
    fs::path target = withoutTrailingSeparator(mDir);
    struct stat st {};
    if (::stat(target.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
        throw InputError(mDir.string(), "exists and is not a directory");

    // The destructor may only remove directories this object made, so record exactly those.
    std::vector<fs::path> missing; // deepest first
    for (fs::path p = target; !p.empty(); p = p.parent_path()) {
        if (::stat(p.c_str(), &st) == 0)
            break;
        missing.push_back(p);
        if (p == p.parent_path())
            break;
    }
    auto creationError = [this](int err) {
        discard();
        return InputError(mDir.string(), "cannot create directory: " + errnoText(err));
    };
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (::mkdir(it->c_str(), 0777) == 0) {
            mCreatedDirs.push_back(*it);
            continue;
        }
        int err = errno;
        // Someone else created it meanwhile (or "x/.." resolved to one we made); not ours.
        if (err == EEXIST && isDirectory(*it))
            continue;
        throw creationError(err);
    }

    fs::path staging = target / (".penumbra-staging-" + std::to_string(::getpid()));
    int result = ::mkdir(staging.c_str(), 0700);
    if (result != 0 && errno == EEXIST) {
        // Left by a killed run whose pid was reused (common in containers); nothing owns it.
        std::error_code ec;
        fs::remove_all(staging, ec);
        result = ::mkdir(staging.c_str(), 0700);
    }
    if (result != 0)
        throw creationError(errno);
    mStaging = std::move(staging);
    mActive = true;
}

StagedOutputDir::~StagedOutputDir() {
    if (mActive)
        discard();
}

StagedOutputDir::StagedOutputDir(StagedOutputDir&& other) noexcept
    : mDir(std::move(other.mDir)), mStaging(std::move(other.mStaging)),
      mCreatedDirs(std::move(other.mCreatedDirs)), mStaged(std::move(other.mStaged)),
      mActive(std::exchange(other.mActive, false)) {}

StagedOutputDir& StagedOutputDir::operator=(StagedOutputDir&& other) noexcept {
    if (this != &other) {
        if (mActive)
            discard();
        mDir = std::move(other.mDir);
        mStaging = std::move(other.mStaging);
        mCreatedDirs = std::move(other.mCreatedDirs);
        mStaged = std::move(other.mStaged);
        mActive = std::exchange(other.mActive, false);
    }
    return *this;
}

void StagedOutputDir::write(const std::string& name, std::span<const uint8_t> bytes) {
    PENUMBRA_CHECK(mActive, "write to a committed or moved-from StagedOutputDir");
    PENUMBRA_CHECK(!name.empty() && name != "." && name != ".." &&
                       name.find('/') == std::string::npos && name.find('\0') == std::string::npos,
                   "staged output name must be a plain file name: " + name);
    fs::path file = mStaging / name;
    std::string subject = (mDir / name).string();
    // A failed write must not leave a truncated file that a later commit() would publish.
    auto fail = [&](int err, const char* what) {
        std::error_code ec;
        fs::remove(file, ec);
        std::erase(mStaged, name);
        return InputError(subject, what + errnoText(err));
    };

    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (!out)
        throw fail(errno, "cannot open for writing: ");
    size_t written = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), out);
    int err = errno;
    bool ok = written == bytes.size();
    if (injectFault(FaultSite::Write))
        ok = false, err = ENOSPC; // a full disk, as the fault sweep asks
    // fclose flushes the buffered tail, so a full disk may only show up here.
    if (std::fclose(out) != 0 && ok) {
        err = errno;
        ok = false;
    }
    if (!ok)
        throw fail(err, "cannot write: ");
    if (std::find(mStaged.begin(), mStaged.end(), name) == mStaged.end())
        mStaged.push_back(name);
}

void StagedOutputDir::commit() {
    PENUMBRA_CHECK(mActive, "commit of a committed or moved-from StagedOutputDir");
    // A directory in the way is the one rename failure we can foresee; checking every name
    // before renaming any keeps it from leaving the output half-committed.
    for (const std::string& name : mStaged) {
        struct stat st {};
        // lstat: rename(2) replaces a symlink itself, even one that points to a directory.
        if (::lstat((mDir / name).c_str(), &st) == 0 && S_ISDIR(st.st_mode))
            throw InputError((mDir / name).string(), "cannot replace: is a directory");
    }
    for (size_t i = 0; i < mStaged.size(); ++i) {
        fs::path destination = mDir / mStaged[i];
        if (::rename((mStaging / mStaged[i]).c_str(), destination.c_str()) != 0) {
            int err = errno;
            // Files already renamed are published and no longer staged.
            mStaged.erase(mStaged.begin(), mStaged.begin() + static_cast<ptrdiff_t>(i));
            throw InputError(destination.string(), "cannot move into place: " + errnoText(err));
        }
    }
    mActive = false;
    // Every file has been published; a leftover empty staging directory would be harmless.
    std::error_code ec;
    fs::remove_all(mStaging, ec);
}

void StagedOutputDir::discard() noexcept {
    std::error_code ec;
    if (!mStaging.empty())
        fs::remove_all(mStaging, ec);
    // fs::remove fails on a non-empty directory, which is what keeps others' files safe.
    for (auto it = mCreatedDirs.rbegin(); it != mCreatedDirs.rend(); ++it)
        fs::remove(*it, ec);
    mStaging.clear();
    mCreatedDirs.clear();
    mStaged.clear();
    mActive = false;
}

} // namespace penumbra
