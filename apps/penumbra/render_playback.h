#pragma once
// `render --fps F` (issue 59): the timed frames play the scene's animation (or its orbiting
// lights) F frames a second from --time, each frame a new pose, loaded, framed as the first and
// drawn as the next frame of one renderer (SceneRenderer::repose, no warm-up between poses), so
// that the GPU times are the cost per frame while things move, what a technique re-renders
// because something moved included.
#include "cli_options.h"
#include "penumbra/renderer.h"

#include <memory>
#include <string>

namespace penumbra::cli {

struct PlayedFrames {
    Scene scene;                             // the last frame's pose
    std::unique_ptr<SceneRenderer> uploaded; // it, uploaded (for the field's slice and refusal)
    RenderResult result; // the last frame's images; each pass's time per frame and their median
};

struct PlaybackInputs {
    const std::string& sceneSpec;
    const GlobalOptions& global;
    const SceneOptions& sceneOptions; // the first frame's time set
    double fps = 60.0;
};

// InputError("--fps", ...) unless fps is a rate in (0, 10000] that puts the last of `frames`
// at a finite time, and `first` moves with the time (an animation, or an --add-light that
// orbits).
void checkPlayback(const PlaybackInputs& in, const Scene& first, uint32_t frames);

// options.frames frames: frame k at the first's time + k / fps (to 12 digits); the first after
// its warm-up, each later one as the next frame of the same renderer. `first` is the scene
// loaded at the first frame's time.
PlayedFrames playFrames(Renderer& renderer, const PlaybackInputs& in, const Scene& first,
                        const RenderOptions& options);

} // namespace penumbra::cli
