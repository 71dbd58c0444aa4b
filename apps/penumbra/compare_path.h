#pragma once
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "report/camera_path.h"

#include <string>
#include <vector>

namespace penumbra::cli {

// What a row did along the path: its shimmer, and with virtual maps the pages each frame of the
// path rendered (the pages its view uncovered; its warm-ups render them) and those resident.
struct PathRow {
    double shimmer = 0.0;
    std::vector<uint32_t> pagesRendered;
    std::vector<uint32_t> pagesResident;
};

// Each row (rows[r], named rowNames[r]) along `path` over `frames` frames.
std::vector<PathRow> measurePathShimmer(SceneRenderer& renderer, const Scene& scene,
                                        const std::vector<RenderOptions>& rows,
                                        const std::vector<std::string>& rowNames, CameraPath path,
                                        uint32_t frames, const ReferenceOptions& reference);

} // namespace penumbra::cli
