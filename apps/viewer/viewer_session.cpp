#include "viewer_session.h"

#include "page_views.h"

#include "penumbra/error.h"
#include "render/renderer_impl.h"
#include "scene/framing.h"
#include "shadows/technique.h"
#include "vk/check.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <thread>

namespace penumbra::viewer {
namespace {

bool sameCamera(const Camera& a, const Camera& b) {
    return a.position == b.position && a.target == b.target && a.up == b.up && a.yfov == b.yfov &&
           a.orthographic == b.orthographic && a.ymag == b.ymag;
}

bool sameLights(const std::vector<Light>& a, const std::vector<Light>& b) {
    if (a.size() != b.size())
        return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].position != b[i].position || a[i].direction != b[i].direction ||
            a[i].radius != b[i].radius || a[i].angularDiameter != b[i].angularDiameter)
            return false;
    return true;
}

void printProgress(const std::string& stage) {
    std::fprintf(stderr, "penumbra: %s\n", stage.c_str());
}

} // namespace

ViewerSession::ViewerSession(Renderer& renderer, const Scene& scene, const ViewerOptions& options,
                             VkExtent2D extent)
    : mRenderer(renderer), mScene(scene), mPoseAt(options.poseAt), mPosedAt(options.time),
      mCamera(scene.camera(options.render.camera),
              glm::length(scene.bounds().max - scene.bounds().min)) {
    for (size_t i = 0; i < scene.cameras.size(); ++i)
        if (options.render.camera.empty() || scene.cameras[i].name == options.render.camera) {
            mFollowedCamera = ownCamera(scene, static_cast<int>(i));
            if (mFollowedCamera)
                break;
        }
    mState.options = options.render;
    mState.options.width = extent.width;
    mState.options.height = extent.height;
    mState.vsync = options.vsync;
    mState.hideUi = options.hideUi;
    mState.display = options.show;
    mState.displayLight = mState.displayLayer = std::max(0, options.showIndex);
    // -1 (pages without a level, and any other start): the finest level with pages.
    mState.displayLevel = options.show == DisplayMode::Pages ? options.showIndex : -1;
    mState.truthSamples = static_cast<int>(options.truthSamples);
    mState.truthRequested = options.show == DisplayMode::Error;
    mScripted = options.frames > 0;
    mState.animated = static_cast<bool>(options.poseAt);
    mState.playing = mState.animated && options.play;
    mState.time = options.time;
    mState.duration = options.duration;
    mState.animation = scene.animation;
    if (options.compareWith) {
        mState.compare = true;
        mState.techniqueB = *options.compareWith;
    }
    // The command line's light sizes become the lights' own, which the interface edits.
    Scene lit;
    lit.lights = scene.lights;
    applyLightSizeOverrides(lit, options.render.lightRadiusOverride,
                            options.render.lightAngleOverride);
    mState.lights = lit.lights;
    mState.options.lightRadiusOverride = mState.options.lightAngleOverride = -1.0f;
    for (size_t i = 0; i < scene.cameras.size(); ++i)
        if (scene.cameras[i].name == options.render.camera || options.render.camera.empty()) {
            mState.sceneCamera = static_cast<int>(i);
            break;
        }
    std::fprintf(stderr, "penumbra: uploading scene\n");
    mA = std::make_unique<SceneRenderer>(renderer, scene);
    mA->check(mState.options); // the command line's options: an error ends the viewer
    mLastGood = mState.options;
}

ViewerSession::~ViewerSession() = default;

void ViewerSession::resize(VkExtent2D extent) {
    mState.options.width = mLastGood.width = extent.width;
    mState.options.height = mLastGood.height = extent.height;
}

void ViewerSession::drawInterface() {
    drawPanels(mState, mScene,
               {.maxShadowMapSize = std::min(8192u, mRenderer.device().maxImageDimension2D)});
}

SceneRenderer::FrameState ViewerSession::frameState() const {
    return {.camera = mCamera.camera(), .lights = mState.lights, .cut = mCut};
}

// The interface's options when this device can render them; else the last that could, with the
// reason on the status line.
RenderOptions ViewerSession::checkedOptions(Technique technique) {
    RenderOptions o = mState.options;
    o.technique = technique;
    try {
        validate(o);
        mA->check(o);
        if (technique == mState.options.technique)
            mLastGood = mState.options;
        return o;
    } catch (const InputError& e) {
        mState.status = e.what();
        if (technique == mState.options.technique)
            mState.options = mLastGood;
        RenderOptions fallback = mLastGood;
        fallback.technique = mLastGood.technique;
        return fallback;
    }
}

void ViewerSession::update(const CameraInput& input, float seconds, DisplayPass& display) {
    pushHistory(mState.frameHistory, 1000.0f * seconds);
    if (mState.animated) {
        // The first frame shows the start; each later one moves the clock on while it plays.
        // Playing past the animation's end loops; a time put there (--time, the slider) holds.
        if (mState.playing && mFramesUpdated > 0) {
            mState.time += mScripted ? kScriptedFrameSeconds : double(seconds);
            if (mState.duration > 0.0 && mState.time >= mState.duration)
                mState.time = std::fmod(mState.time, mState.duration);
        }
        mState.time = std::max(0.0, mState.time);
        if (mState.time != mPosedAt)
            pose(mState.time);
    }
    ++mFramesUpdated;
    if (mState.takeSceneCamera) {
        const int index = *mState.takeSceneCamera;
        mCamera.reset(index < 0 ? mScene.camera("") : mScene.cameras[index]);
        mFollowedCamera = ownCamera(mScene, index);
        mState.sceneCamera = index;
        mState.takeSceneCamera.reset();
        mCut = true; // a jump, not a move: temporal history would blend two views
    }
    if (mCamera.update(input, mState.cameraMode))
        mFollowedCamera.reset(); // moved by hand: it no longer follows the file's camera
    if (mState.truthRequested) {
        mState.truthRequested = false;
        startTruth();
    }
    if (!mTruth) {
        mState.truthProgress = -1;
        return;
    }
    if (!sameCamera(mTruthCamera, mCamera.camera()) || !sameLights(mTruthLights, mState.lights) ||
        mTruthSize != glm::uvec2(mState.options.width, mState.options.height)) {
        mTruth.reset();
        mState.errorMetrics.reset();
        mErrorShown = false;
        mState.truthStatus = "the view changed: the ground truth was dropped";
        return;
    }
    if (mScripted) // a scripted run's frames wait for the truth
        while (!mTruth->done())
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
    mState.truthProgress = mTruth->progress();
    if (!mTruth->done()) {
        mState.truthStatus = fmt::format("tracing {} rays per pixel: {:.0f}%", mTruth->samples(),
                                         100.0 * mState.truthProgress);
        return;
    }
    if (!mTruth->error().empty()) {
        mState.truthStatus = "ground truth failed: " + mTruth->error();
        return;
    }
    mState.truthStatus = fmt::format("ground truth: {} rays in {:.1f} s", mTruth->truth().rays,
                                     mTruth->truth().seconds);
    if (mState.display == DisplayMode::Error)
        measureError(display);
}

void ViewerSession::pose(double time) {
    Scene next;
    try {
        next = mPoseAt(time);
    } catch (const InputError& e) { // a pose the file refuses: the last good one stays
        mState.status = e.what();
        mState.playing = false;
        mState.time = mPosedAt;
        return;
    }
    for (size_t i = 0; i < next.lights.size() && i < mState.lights.size(); ++i) {
        next.lights[i].radius = mState.lights[i].radius;
        next.lights[i].angularDiameter = mState.lights[i].angularDiameter;
        next.lights[i].castsShadow = mState.lights[i].castsShadow;
    }
    // The same renderers draw the new pose (its geometry uploaded again), keeping what they
    // keep between frames (targets, history, page requests), as an engine does while things move.
    try {
        mA->repose(next);
        if (mB)
            mB->repose(next);
    } catch (const InputError& e) { // no valid triangle at this time: the last good pose stays
        mState.status = e.what();
        mState.playing = false;
        mState.time = mPosedAt;
        return;
    }
    mScene = std::move(next);
    mState.lights = mScene.lights;
    if (mFollowedCamera && *mFollowedCamera < mScene.cameras.size()) // an animated camera moves
        mCamera.reset(mScene.cameras[*mFollowedCamera]);
    mPosedAt = time;
    if (mTruth) {
        mTruth.reset();
        mState.errorMetrics.reset();
        mErrorShown = false;
        mState.truthStatus = "the scene moved: the ground truth was dropped";
    }
}

RenderResult ViewerSession::renderNow() {
    VK_CHECK(vkDeviceWaitIdle(mRenderer.context().device()));
    RenderOptions o = checkedOptions(mState.options.technique);
    o.frames = 1;
    return mA->render(o, frameState(), printProgress);
}

void ViewerSession::startTruth() {
    mTruth.reset(); // cancels a running one
    mErrorShown = false;
    mMeasuredFor.clear();
    Scene lit = mScene;
    lit.lights = mState.lights;
    RenderResult gbuffer = renderNow();
    mTruthCamera = mCamera.camera();
    mTruthLights = mState.lights;
    mTruthSize = {gbuffer.width, gbuffer.height};
    mTruth = std::make_unique<TruthJob>(std::move(lit), std::move(gbuffer),
                                        static_cast<uint32_t>(mState.truthSamples));
}

void ViewerSession::measureError(DisplayPass& display) {
    const RenderOptions& o = mState.options;
    std::string key = fmt::format("{} {} {}", static_cast<int>(o.technique), o.shadowMapSize,
                                  mState.displayLight);
    for (const auto& [name, value] : o.parameters.all())
        key += fmt::format(" {}={}", name, value);
    if (key == mMeasuredFor)
        return;
    const RenderResult frame = renderNow();
    const ErrorView view = viewer::measureError(mTruth->scene(), frame, mTruth->truth(),
                                                static_cast<size_t>(mState.displayLight));
    display.setOverlay(view.heatmap);
    mState.errorMetrics = view.metrics;
    if (mScripted)
        std::printf("error against the ground truth (%u rays per pixel): RMSE %.4f, "
                    "misclassified %.3f%% (%.3f%% away from edges), acne %.3f%%, leak %.3f%%\n",
                    mTruth->samples(), view.metrics.rmse, 100 * view.metrics.misclassified,
                    100 * view.metrics.misclassifiedOutsideEdges, 100 * view.metrics.acne,
                    100 * view.metrics.leak);
    mMeasuredFor = key;
    mErrorShown = true;
}

gpu::DisplayPush ViewerSession::displayPush(uint32_t width) const {
    const ViewerState& s = mState;
    gpu::DisplayPush push{.mode = {DISPLAY_SCENE, 0u,
                                   s.compare
                                       ? static_cast<uint32_t>(s.split * static_cast<float>(width))
                                       : std::numeric_limits<uint32_t>::max(),
                                   0u}};
    const glm::vec3 forward = glm::normalize(mCamera.camera().target - mCamera.camera().position);
    push.forward = glm::vec4(forward, 0.0f);
    uint32_t shadowLights = 0;
    std::vector<const ShadowViewInfo*> layers;
    for (const LightShadow& l : s.lastFrame.lights) {
        shadowLights += l.visibilityIndex >= 0;
        for (const ShadowViewInfo& v : l.views)
            layers.push_back(&v);
        uint32_t cascades = 0;
        for (const ShadowViewInfo& v : l.views)
            if (v.cascade && cascades < MAX_CASCADES && push.mode.w == 0)
                push.splits[cascades / 4][cascades % 4] = v.splitFar, ++cascades;
        if (push.mode.w == 0)
            push.mode.w = cascades; // the first light with cascades
    }
    switch (s.display) {
    case DisplayMode::Scene:
        break;
    case DisplayMode::Visibility:
        if (shadowLights > 0)
            push.mode.x = DISPLAY_VISIBILITY,
            push.mode.y =
                std::min<uint32_t>(static_cast<uint32_t>(s.displayLight), shadowLights - 1);
        break;
    case DisplayMode::ShadowMap: // a field's tracer fits its lights' views but draws no map
        if (!layers.empty() && shadows::drawsLightMaps(shadows::moduleOf(s.options.technique))) {
            const uint32_t layer = std::min<uint32_t>(static_cast<uint32_t>(s.displayLayer),
                                                      static_cast<uint32_t>(layers.size() - 1));
            const ShadowViewInfo& v = *layers[layer];
            push.mode.x = DISPLAY_SHADOW_MAP;
            push.mode.y = v.layer;
            push.depthRange = {v.nearPlane, v.farPlane, v.projection == "perspective", 0.0f};
        }
        break;
    case DisplayMode::Cascades:
        push.mode.x = DISPLAY_CASCADES;
        break;
    case DisplayMode::Error:
        if (mErrorShown)
            push.mode.x = DISPLAY_OVERLAY;
        break;
    case DisplayMode::Pages:
    case DisplayMode::Pool:
        if (mPagesShown)
            push.mode.x = DISPLAY_OVERLAY;
        break;
    case DisplayMode::Contact:
        if (shadowLights > 0 && s.options.parameters.number("contact.length") > 0.0)
            push.mode.x = DISPLAY_LAYER,
            push.mode.y = std::min(static_cast<uint32_t>(s.displayLight), shadowLights - 1);
        break;
    case DisplayMode::BlockerDepth:
    case DisplayMode::Penumbra:
        if (shadowLights > 0 && hasBlockerSearch(s.options.technique)) {
            push.mode.x =
                s.display == DisplayMode::BlockerDepth ? DISPLAY_BLOCKER_DEPTH : DISPLAY_PENUMBRA;
            push.mode.y = std::min(static_cast<uint32_t>(s.displayLight), shadowLights - 1);
            push.depthRange.w = static_cast<float>(s.options.parameters.number(
                shadows::moduleOf(s.options.technique).blockerSearchKey));
        }
        break;
    }
    return push;
}

void ViewerSession::record(FrameSlot& slot, uint64_t frame, DisplayPass& display) {
    const RenderOptions a = checkedOptions(mState.options.technique);
    // The passes' own results, written only when shown: the search's, or the contact layer's.
    const bool intermediates =
        ((mState.display == DisplayMode::BlockerDepth || mState.display == DisplayMode::Penumbra) &&
         hasBlockerSearch(a.technique)) ||
        mState.display == DisplayMode::Contact;
    SceneRenderer::RecordedFrame liveA = mA->record(slot.cmd, a, frameState(), frame % 2,
                                                    *slot.timerA, intermediates, printProgress);
    mState.lastFrame = std::move(liveA.result);
    showPages(a, display);
    const render::FrameOutputs* outputsB = nullptr;
    slot.timedB = false;
    if (mState.compare) {
        if (!mB) {
            std::fprintf(stderr, "penumbra: uploading the scene for technique B\n");
            mB = std::make_unique<SceneRenderer>(mRenderer, mScene);
        }
        const RenderOptions b = checkedOptions(mState.techniqueB);
        outputsB =
            mB->record(slot.cmd, b, frameState(), frame % 2, *slot.timerB, false, printProgress)
                .outputs;
        slot.timedB = true;
    }
    mCut = false; // both techniques' frames saw it
    display.record(slot.cmd, *liveA.outputs, outputsB, displayPush(a.width));
}

void ViewerSession::showPages(const RenderOptions& o, DisplayPass& display) {
    const bool pageView =
        mState.display == DisplayMode::Pages || mState.display == DisplayMode::Pool;
    mPagesShown = pageView && mState.lastFrame.virtualMaps.has_value();
    if (!mPagesShown)
        return;
    const VirtualPages pages = mA->virtualPages();
    auto isCube = [&](uint32_t light) {
        return light < mState.lights.size() && mState.lights[light].type == LightType::Point;
    };
    mState.levelNames.clear();
    int finest = -1; // the first level with a page in the pool or asked for
    for (const VirtualPages::Level& l : pages.levels) {
        const auto used = std::count_if(l.pages.begin(), l.pages.end(),
                                        [](PageState p) { return p != PageState::Absent; });
        if (used > 0 && finest < 0)
            finest = static_cast<int>(mState.levelNames.size());
        mState.levelNames.push_back(
            fmt::format("{} ({} pages)", levelName(l, isCube(l.light)), used));
    }
    const int last = static_cast<int>(pages.levels.size()) - 1;
    const int shown = mState.displayLevel < 0 ? std::max(finest, 0)
                                              : std::min(mState.displayLevel, std::max(last, 0));
    mState.shownLevel = shown;
    if (mState.display == DisplayMode::Pool)
        display.setOverlay(poolImage(pages, o.width, o.height));
    else if (!pages.levels.empty()) {
        const VirtualPages::Level& level = pages.levels[static_cast<size_t>(shown)];
        const PageWindow window =
            mState.wholeTable ? PageWindow{0, 0, level.pagesPerSide} : usedWindow(level);
        mState.pageWindow = {window.x, window.y, window.side};
        display.setOverlay(pageTableImage(level, window, o.width, o.height));
    } else
        mPagesShown = false;
    if (mScripted) { // each frame's, the last one's is the screenshot's
        const VirtualMapInfo& v = *mState.lastFrame.virtualMaps; // what the interface shows
        const glm::uvec3 w = mState.pageWindow;
        const std::string what = mState.display == DisplayMode::Pool || pages.levels.empty()
                                     ? std::string("the pool")
                                     : fmt::format("{}, pages {}..{}, {}..{}",
                                                   mState.levelNames[static_cast<size_t>(shown)],
                                                   w.x, w.x + w.z - 1, w.y, w.y + w.z - 1);
        std::printf("virtual pages: requested %u, resident %u of %u, rendered %u, cached %u, "
                    "dropped %u; shown: %s\n",
                    v.requested, v.resident, v.poolPages, v.rendered, v.cached, v.dropped,
                    what.c_str());
    }
}

void ViewerSession::printTimes() const {
    auto median = [](const std::deque<float>& h) {
        std::vector<float> v(h.begin(), h.end());
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0f : v[v.size() / 2];
    };
    std::printf("frame %.1f ms (median of %zu); GPU ms per pass:", median(mState.frameHistory),
                mState.frameHistory.size());
    for (const auto& [pass, history] : mState.gpuHistory)
        std::printf("  %s %.3f", pass.c_str(), median(history));
    std::printf("\n");
}

void ViewerSession::recordTimes(FrameSlot& slot) {
    const auto times = slot.timerA->read();
    bool same = times.size() == mState.gpuHistory.size();
    for (const PassTime& t : times)
        same = same && mState.gpuHistory.count(t.pass);
    if (!same) // another technique: other passes
        mState.gpuHistory.clear();
    for (const PassTime& t : times)
        pushHistory(mState.gpuHistory[t.pass], static_cast<float>(t.medianMs));
}

} // namespace penumbra::viewer
