#include "render_playback.h"

#include "compare_timeline.h"
#include "penumbra/error.h"
#include "penumbra/pass_times.h"
#include "pool_shortage.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace penumbra::cli {

void checkPlayback(const PlaybackInputs& in, const Scene& first, uint32_t frames) {
    if (!(in.fps > 0.0 && in.fps <= 10000.0))
        throw InputError("--fps",
                         fmt::format("{} is not a rate in (0, 10000] frames a second", in.fps));
    const double last = in.sceneOptions.time.value_or(0.0) + double(frames - 1) / in.fps;
    if (!std::isfinite(last))
        throw InputError("--fps", fmt::format("at {} a second frame {} would be at {} s, not a "
                                              "time",
                                              in.fps, frames, last));
    if (first.animation.empty() && !lightsOrbit(in.sceneOptions))
        throw InputError("--fps", fmt::format("'{}' has no animation and no light that orbits: "
                                              "nothing would move",
                                              in.sceneSpec));
}

PlayedFrames playFrames(Renderer& renderer, const PlaybackInputs& in, const Scene& first,
                        const RenderOptions& options) {
    const double start = in.sceneOptions.time.value_or(0.0);
    SceneOptions posed = in.sceneOptions;
    posed.ground = posed.ground || first.automaticGround; // the first frame's choice holds
    posed.noGround = !posed.ground;
    RenderOptions one = options;
    one.frames = 1;
    PlayedFrames played;
    std::vector<PassTime> passes;
    std::vector<uint32_t> pagesPerFrame;
    PoolShortage shortage; // said once, after the last pose (the poses render quietly)
    for (uint32_t k = 0; k < options.frames; ++k) {
        const double exact = start + static_cast<double>(k) / in.fps;
        posed.time = std::strtod(fmt::format("{:.12g}", exact).c_str(), nullptr);
        std::fprintf(stderr, "penumbra: frame %u/%u at %g s\n", k + 1, options.frames, *posed.time);
        if (k == 0) { // at rest, after its warm-up
            played.scene = first;
            played.uploaded = std::make_unique<SceneRenderer>(renderer, played.scene);
            played.result = played.uploaded->render(one);
        } else { // the next frame of the same renderer: what the technique kept shows
            played.scene = loadPose(
                [&] { return loadSceneReporting(in.sceneSpec, in.global, posed, options, true); },
                fmt::format("--fps frame {} of {}, at {:g} s", k + 1, options.frames, *posed.time));
            pinToFirstFrame(played.scene, first);
            played.uploaded->repose(played.scene);
            played.result = played.uploaded->render(one, {.continues = true});
        }
        if (const auto& pages = played.result.virtualMaps) // every pose's frames, from the
            pagesPerFrame.insert(pagesPerFrame.end(),      // first warm-up on
                                 pages->renderedPerFrame.begin(), pages->renderedPerFrame.end());
        shortage.add(played.result);
        appendFrameTimes(passes, played.result.passes, k); // each pose one frame
    }
    setMedians(passes);
    played.result.passes = std::move(passes);
    if (auto& pages = played.result.virtualMaps) {
        pages->renderedPerFrame = std::move(pagesPerFrame);
        pages->droppedFrames = shortage.frames;
    }
    if (const std::string said = shortage.warning(); !said.empty())
        std::fprintf(stderr, "penumbra: %s\n", said.c_str());
    return played;
}

} // namespace penumbra::cli
