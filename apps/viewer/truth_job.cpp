#include "truth_job.h"

#include "report/heatmap.h"
#include "report/light_mask.h"

#include <algorithm>
#include <exception>

namespace penumbra::viewer {

TruthJob::TruthJob(Scene scene, RenderResult gbuffer, uint32_t samples)
    : mScene(std::move(scene)), mGbuffer(std::move(gbuffer)), mSamples(samples) {
    mThread = std::thread([this] {
        try {
            mTruth = computeReference(
                mScene, mGbuffer, {.samples = mSamples, .rowsDone = &mRows, .cancel = &mCancel});
        } catch (const std::exception& e) {
            mError = e.what();
        }
        mDone.store(true);
    });
}

TruthJob::~TruthJob() {
    mCancel.store(true);
    mThread.join();
}

double TruthJob::progress() const {
    return mGbuffer.height ? std::min(1.0, double(mRows.load()) / mGbuffer.height) : 1.0;
}

ErrorView measureError(const Scene& scene, const RenderResult& frame, const ReferenceResult& truth,
                       size_t light) {
    const uint32_t w = frame.width, h = frame.height;
    std::vector<std::vector<uint8_t>> masks;
    for (const LightShadow& s : frame.lights)
        if (s.visibilityIndex >= 0)
            masks.push_back(lightMask(scene.lights[s.sceneLight], frame));
    std::vector<MetricLayer> layers;
    for (size_t l = 0; l < truth.visibility.size() && l < frame.visibility.size(); ++l)
        layers.push_back({frame.visibility[l], truth.visibility[l], masks[l]});
    ErrorView view{.metrics = computeMetrics(w, h, layers)};
    if (layers.empty()) {
        view.heatmap.assign(size_t{w} * h * 4, 0);
        return view;
    }
    const size_t l = std::min(light, layers.size() - 1);
    RgbaImage map = signedErrorHeatmap(w, h, frame.visibility[l], truth.visibility[l], masks[l]);
    map.pixels.resize(size_t{w} * h * 4); // the legend rows go; the panel explains the colours
    view.heatmap = std::move(map.pixels);
    return view;
}

} // namespace penumbra::viewer
