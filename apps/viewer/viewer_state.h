#pragma once
// What the viewer's interface edits and the frame loop reads: the render options, the lights,
// the camera mode, what the window shows, and the live timings.
#include "camera_control.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"
#include "report/metrics.h"

#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::viewer {

enum class DisplayMode {
    Scene,
    Visibility,
    ShadowMap,
    Cascades,
    Error,
    BlockerDepth,
    Penumbra,
    Contact, // the contact layer's own result for one light (what it multiplies in)
    Pages,   // virtual maps: one level's page table (rendered this frame, cached, kept, dropped)
    Pool     // virtual maps: the physical pool, each page tinted by the level it holds
};

// Whether the technique reports a blocker depth and penumbra width (evaluateTechnique's y and w):
// the members that model the light's size with a shadow map (pcss, vssm, msm-soft).
bool hasBlockerSearch(Technique technique);

inline constexpr size_t kHistoryFrames = 120;

struct ViewerState {
    RenderOptions options;     // width and height follow the window
    std::vector<Light> lights; // the scene's, as edited (sizes included)
    CameraMode cameraMode = CameraMode::Orbit;
    int sceneCamera = -1;               // the scene camera last taken; -1: automatic framing
    std::optional<int> takeSceneCamera; // set by the interface: the camera to jump to
    DisplayMode display = DisplayMode::Scene;
    int displayLight = 0; // shadow-casting light shown by Visibility, Error, BlockerDepth, Penumbra
    int displayLayer = 0; // shadow-map layer shown by ShadowMap
    int displayLevel = -1;     // virtual-map level shown by Pages (VirtualPages::levels' index);
                               // -1: the finest level with pages, as the frame changes
    int shownLevel = 0;        // the one shown
    bool wholeTable = false;   // else the square around its used pages
    glm::uvec3 pageWindow{0u}; // the pages shown: first x, first y, side
    std::vector<std::string> levelNames; // the last frame's virtual-map levels, for the interface
    bool compare = false;                // A/B: technique B right of the split
    Technique techniqueB = kComparedTechnique;
    float split = 0.5f; // of the width
    bool vsync = true;
    bool hideUi = false;
    // Time, for an animated scene: where it stands (the interface's slider scrubs it), whether
    // it plays (Space toggles it), and the animation's length (0: none; the clock runs on).
    bool animated = false;
    bool playing = false;
    double time = 0.0, duration = 0.0;
    std::string animation;
    // Ground truth: what the interface asked for and what the loop reports back.
    bool truthRequested = false;
    int truthSamples = 64;
    double truthProgress = -1; // < 0: no job
    std::string truthStatus;
    std::optional<ErrorMetrics> errorMetrics;
    // Live timings: GPU ms per pass (technique A) and CPU frame time, the last kHistoryFrames.
    std::map<std::string, std::deque<float>> gpuHistory;
    std::deque<float> frameHistory;
    RenderResult lastFrame; // lights, views, field of the last frame (no pixels)
    std::string status;     // one line: progress, or an error the last change caused
};

// The scene's lights, as the interface may show them, and the device's limits it respects.
struct ViewerLimits {
    uint32_t maxShadowMapSize = 4096;
};

void pushHistory(std::deque<float>& history, float value);

// The "show" section (show_panel.cpp): what the window shows, and the ground truth.
void showPanel(ViewerState& state);

// The "time" section (time_panel.cpp): play, pause and the time slider of an animated scene.
void timePanel(ViewerState& state);

// The interface (panels.cpp). Edits `state`; returns nothing, the loop compares what changed.
void drawPanels(ViewerState& state, const Scene& scene, const ViewerLimits& limits);

} // namespace penumbra::viewer
