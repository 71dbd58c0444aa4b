#pragma once
// What the viewer shows and how it changes: the interface's state, the scene uploaded once per
// technique slot (A, and B for the A/B split), the camera, the ground-truth job and the error
// view. The frame loop (viewer.cpp) owns the window, the swapchain and the frames in flight.
#include "camera_control.h"
#include "display.h"
#include "frame_slot.h"
#include "truth_job.h"
#include "viewer.h"
#include "viewer_state.h"

#include <memory>
#include <optional>

namespace penumbra::viewer {

class ViewerSession {
public:
    ViewerSession(Renderer& renderer, const Scene& scene, const ViewerOptions& options,
                  VkExtent2D extent);
    ~ViewerSession();
    ViewerState& state() { return mState; }
    void resize(VkExtent2D extent);
    void drawInterface();
    // Camera input, a scene camera taken, the ground truth's progress and the error view (which
    // renders synchronously, the device idle, when the technique or its parameters changed).
    void update(const CameraInput& input, float seconds, DisplayPass& display);
    // Technique A's frame (and B's), then the display pass, into `slot`'s command buffer.
    void record(FrameSlot& slot, uint64_t frame, DisplayPass& display);
    // The GPU times of the frame `slot` carried (its fence has signalled).
    void recordTimes(FrameSlot& slot);
    // One line on stdout: the median frame time and GPU ms per pass over the history.
    void printTimes() const;

private:
    RenderOptions checkedOptions(Technique technique);
    SceneRenderer::FrameState frameState() const;
    RenderResult renderNow(); // technique A, synchronously, with its pixels
    void startTruth();
    void measureError(DisplayPass& display);
    gpu::DisplayPush displayPush(uint32_t width) const;
    // The virtual-map views (Pages, Pool): the last recorded frame's pages into the overlay.
    void showPages(const RenderOptions& options, DisplayPass& display);

    // The scene posed at `time` (an animated scene's next frame or the slider's time): uploaded
    // anew, the interface's light sizes kept, a ground truth of the old pose dropped.
    void pose(double time);

    Renderer& mRenderer;
    Scene mScene; // as posed now
    std::function<Scene(double)> mPoseAt;
    double mPosedAt = 0.0;
    uint64_t mFramesUpdated = 0;
    ViewerState mState;
    RenderOptions mLastGood;
    CameraControl mCamera;
    // The file's own camera (its index) the view follows as the scene plays, until the view is
    // moved; none for an automatic one (held, as on compare --timeline).
    std::optional<size_t> mFollowedCamera;
    std::unique_ptr<SceneRenderer> mA, mB;
    std::unique_ptr<TruthJob> mTruth;
    Camera mTruthCamera; // the view the truth was traced for
    std::vector<Light> mTruthLights;
    glm::uvec2 mTruthSize{0u};
    std::string mMeasuredFor; // what the error view on screen was measured for
    bool mErrorShown = false;
    bool mPagesShown = false;
    bool mScripted = false; // --frames: no one is watching, frames wait for slow work
    bool mCut = false;      // a scene camera taken: the next frame's history starts again
};

} // namespace penumbra::viewer
