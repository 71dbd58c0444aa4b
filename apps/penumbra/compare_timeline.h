#pragma once
// `compare --timeline START:END:STEP` (issue 59): the scene posed at each time, every row
// rendered at rest and in motion and a truth traced for each frame, with per-frame metrics (RMSE,
// MAE, acne, leak, GPU time) and each row's flicker (src/report/shimmer.h) and lag
// (src/report/lag.h). Written as timeline.json and
// timeline.csv beside the usual outputs of the first frame.
#include "cli_options.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "report/blur_band.h"
#include "report/lag.h"
#include "scene/timeline_range.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::cli {

// One row's measures per frame, and over the timeline. Two renders of each frame: at rest (the
// pose rendered by a renderer of its own after warm-up: the technique's steady state) and in
// motion (the pose drawn as the next frame of one renderer that drew every frame before it,
// with no warm-up: what the technique kept from the last frame shows).
struct TimelineRow {
    // A virtual map's pages in one frame in motion: what its update asked for (the frame
    // before's requests and their coarser chains), rendered and held after it.
    struct Pages {
        uint32_t requested = 0, rendered = 0, resident = 0;
    };
    std::string name;
    std::vector<double> rmse, mae, acne, leak, gpuMs; // at rest
    std::vector<double> movingRmse, movingGpuMs;      // in motion
    std::vector<PassTime> movingPasses; // each pass's time in motion, a frame each (0: not run)
    std::vector<Pages> movingPages;     // virtual maps only: one per frame in motion
    double flicker = 0.0;               // mean |change of the error| where the truth held still
    uint64_t flickerPixels = 0;
    double movingFlicker = 0.0; // the same over the frames in motion (as played)
    uint64_t movingFlickerPixels = 0;
    Lag lag; // the motion's error against the rest's (report/lag.h)
};

struct TimelineInputs {
    const std::string& sceneSpec;
    const GlobalOptions& global;
    SceneOptions sceneOptions; // as given; each frame's time set here
    const std::vector<std::string>& rowNames;
    const std::vector<RenderOptions>& rowOptions;
    const std::vector<BlurReach>& blur;
    const ReferenceOptions& reference;
};

// A pose after the first, loaded by `load`: one it refuses names itself by `which` ("--timeline
// frame 3 of 3, at 1 s"), since the first pose was accepted.
Scene loadPose(const std::function<Scene()>& load, const std::string& which);

// An automatic camera, default light or ground follows the scene's bounds, which move with the
// animation: the first frame's are kept (the ground by the caller, through the scene options),
// so that only what the animation moves moves. A sweep's views at a time do the same.
void pinToFirstFrame(Scene& scene, const Scene& first);

// Every frame of `timeline`: the scene loaded at its time (the first frame's automatic camera,
// default light and ground kept for all, so that only what the animation moves moves), each row
// rendered, the truth traced, the metrics taken. Progress goes to stderr.
std::vector<TimelineRow> runTimeline(Renderer& renderer, const TimelineInputs& in,
                                     const Timeline& timeline);

// timeline.json's content (docs/cli.md) and timeline.csv's.
nlohmann::json timelineJson(const Timeline& timeline, const std::vector<TimelineRow>& rows);
std::string timelineCsv(const Timeline& timeline, const std::vector<TimelineRow>& rows);

} // namespace penumbra::cli
