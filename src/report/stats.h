#pragma once
// stats.json of `penumbra render` (docs/cli.md): the device, the scene, every parameter in
// effect and the GPU time per pass (median of the timed frames after one warm-up frame).
#include "penumbra/renderer.h"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace penumbra {

struct RenderRun {
    std::string sceneSpec;
    const Scene& scene;
    const RenderOptions& options;
    const DeviceInfo& device;
    const RenderResult& result;
    std::string_view floatExtension = "pfm"; // the visibility files stats.json names
    // viewJson(scene, the options' camera), when the caller measured it once for many runs of
    // one view (compare's rows); measured here when empty.
    const nlohmann::json* view = nullptr;
    double fps = 0.0; // render --fps: the timed frames were successive poses, this many a second
};

nlohmann::json renderStats(const RenderRun& run);
// The command line's scene control as applied (stats.json's and reference.json's scene edits).
nlohmann::json sceneEditsJson(const SceneEdits& edits);
// What the first picture shows from `camera` (scene/first_picture.h): `cast_shadow`, the share of
// the view in a visible cast shadow, and `subject`, the share showing the subject.
nlohmann::json viewJson(const Scene& scene, const Camera& camera);
// The device as stats.json and the bench's JSON name it.
nlohmann::json deviceJson(const DeviceInfo& device);

// "visibility" for the first shadow-casting light, "visibility_<i>" after it (then .pfm, .exr).
std::string visibilityFileStem(size_t index);

} // namespace penumbra
