#pragma once
// stats.json of `penumbra render` (design.md §1): the device, the scene, every parameter in
// effect and the GPU time per pass (median of the timed frames after one warm-up frame).
#include "penumbra/renderer.h"

#include <nlohmann/json.hpp>

#include <string>

namespace penumbra {

struct RenderRun {
    std::string sceneSpec;
    const Scene& scene;
    const RenderOptions& options;
    const DeviceInfo& device;
    const RenderResult& result;
};

nlohmann::json renderStats(const RenderRun& run);
// The command line's scene control as applied (stats.json's and reference.json's scene edits).
nlohmann::json sceneEditsJson(const SceneEdits& edits);
// The device as stats.json and the bench's JSON name it.
nlohmann::json deviceJson(const DeviceInfo& device);

// "visibility.pfm" for the first shadow-casting light, "visibility_<i>.pfm" after it.
std::string visibilityFileName(size_t index);

} // namespace penumbra
