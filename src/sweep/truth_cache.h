#pragma once
// The ground truth of a view, kept on disk under a key made of everything that decides it, so
// that sweep, compare and tune trace a view once across tasks, runs and machines that share the
// directory. Files are written to a temporary name in the directory and renamed into place: a
// reader never sees half a file, and of two writers of the same key the last rename wins with
// the same bytes.
#include "penumbra/reference.h"
#include "penumbra/scene.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace penumbra::sweep {

// Bumped whenever the truth's algorithm or file layout changes: old entries are then never read.
inline constexpr uint32_t kTruthVersion = 2;

// A hash of what the truth sees of a scene: triangles, their materials' coverage (alpha mode,
// cutoff, base alpha, vertex alpha, textures and their pixels), transmission and volume,
// double-sidedness, and the colours of translucent ones (their tint). Not lights or cameras.
std::string sceneContentHash(const Scene& scene);

// The key of a view's truth: the scene content, the lights as the truth uses them (`lit`: sizes
// overridden), the camera `cameraName` resolves to, the image size, the samples and
// kTruthVersion.
std::string truthKey(const Scene& lit, const std::string& cameraName, uint32_t width,
                     uint32_t height, uint32_t samples);

class TruthCache {
public:
    // Creates the directory when missing; InputError(dir, ...) when it cannot.
    explicit TruthCache(std::filesystem::path dir);
    std::optional<ReferenceResult> load(const std::string& key) const;
    // Writes atomically (temporary file, rename); InputError(file, ...) when it cannot.
    void store(const std::string& key, const ReferenceResult& truth) const;
    std::filesystem::path fileOf(const std::string& key) const;

private:
    std::filesystem::path mDir;
};

// The truth from `cache` (null: no cache) or, on a miss, from `compute`, then stored. `computed`
// (optional) says which.
ReferenceResult cachedTruth(const TruthCache* cache, const std::string& key,
                            const std::function<ReferenceResult()>& compute,
                            bool* computed = nullptr);

} // namespace penumbra::sweep
