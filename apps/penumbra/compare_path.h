#pragma once
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "report/camera_path.h"

#include <string>
#include <vector>

namespace penumbra::cli {

// The shimmer of each row (rows[r], named rowNames[r]) along `path` over `frames` frames.
std::vector<double> measurePathShimmer(SceneRenderer& renderer, const Scene& scene,
                                       const std::vector<RenderOptions>& rows,
                                       const std::vector<std::string>& rowNames, CameraPath path,
                                       uint32_t frames, const ReferenceOptions& reference);

} // namespace penumbra::cli
