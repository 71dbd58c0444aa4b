#pragma once
// `penumbra view`: the interactive viewer (docs/cli.md). A GLFW window with a Vulkan swapchain,
// the frame of SceneRenderer recorded with two frames in flight, and a Dear ImGui interface.
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "viewer_state.h"

#include <functional>
#include <string>

namespace penumbra::viewer {

struct ViewerOptions {
    RenderOptions render;   // width x height: the window's size at start (the frame follows it)
    uint32_t frames = 0;    // > 0: draw this many frames, then exit (0: until the window closes)
    std::string screenshot; // with frames: the last presented image, as PNG
    bool hideUi = false;    // draw the scene without the interface (Tab toggles it)
    bool vsync = true;
    // What the window shows at start: the mode, its light (visibility, error) or layer (shadow
    // map), technique B for the A/B split, and the truth's rays per pixel. Showing the error
    // starts the ground truth at once; with `frames`, the frames wait for it.
    DisplayMode show = DisplayMode::Scene;
    int showIndex = 0; // -1: pages without a level
    std::optional<Technique> compareWith;
    uint32_t truthSamples = 64;
    int device = -1;
    bool validation = false;
    // An animated scene: the scene posed at a time (empty: nothing moves), the time it starts
    // at, its animation's length (0: none, the clock runs on) and whether it plays at start.
    std::function<Scene(double)> poseAt;
    double time = 0.0, duration = 0.0;
    bool play = false;
};

// The time a scripted run (`frames` > 0) advances each frame while it plays: a steady 60
// frames a second, whatever the device's speed, so that frame k shows the start plus k / 60 s.
inline constexpr double kScriptedFrameSeconds = 1.0 / 60.0;

// Runs the viewer until the window closes (or `frames` frames). Throws InputError on bad input:
// no display, no device that can present, options the device cannot honour, an unwritable
// screenshot path; std::runtime_error on validation errors.
void runViewer(const Scene& scene, const ViewerOptions& options);

} // namespace penumbra::viewer
