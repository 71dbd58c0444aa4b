#pragma once
// The ground truth of the view on screen, traced with Embree on a thread while the viewer keeps
// drawing, and the error of a frame against it: the same metrics and heat map as `compare`.
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "report/metrics.h"

#include <atomic>
#include <thread>

namespace penumbra::viewer {

class TruthJob {
public:
    // `scene`: the scene with the frame's lights (sizes applied); `gbuffer`: a frame of it.
    TruthJob(Scene scene, RenderResult gbuffer, uint32_t samples);
    ~TruthJob(); // cancels the tracing and waits for the thread
    TruthJob(const TruthJob&) = delete;
    TruthJob& operator=(const TruthJob&) = delete;

    double progress() const; // 0..1
    bool done() const { return mDone.load(); }
    // Once done: the truth, or the error that stopped it (empty when none).
    const ReferenceResult& truth() const { return mTruth; }
    const std::string& error() const { return mError; }
    const Scene& scene() const { return mScene; }
    uint32_t samples() const { return mSamples; }

private:
    Scene mScene;
    RenderResult mGbuffer;
    uint32_t mSamples;
    ReferenceResult mTruth;
    std::string mError;
    std::atomic<uint32_t> mRows{0};
    std::atomic<bool> mCancel{false}, mDone{false};
    std::thread mThread;
};

struct ErrorView {
    ErrorMetrics metrics;
    std::vector<uint8_t> heatmap; // RGBA8, the frame's size (the legend left off)
};

// `frame` must show the pixels the truth was traced for (same camera, size and lights).
// The heat map shows shadow-casting light `light` (0-based, as RenderResult::visibility).
ErrorView measureError(const Scene& scene, const RenderResult& frame, const ReferenceResult& truth,
                       size_t light);

} // namespace penumbra::viewer
