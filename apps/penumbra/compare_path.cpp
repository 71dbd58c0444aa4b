// `compare --camera-path`: renders each row along the path and measures its shimmer
// (src/report/shimmer.h). Moving camera: each frame is rendered with its own shadow views and
// with the previous frame's, and the two compared pixel by pixel (what the views' change did to
// the same visible points). Moving sun: the camera stands still, and each frame's change is
// compared with the truth's, traced per frame.
#include "compare_path.h"
#include "pool_shortage.h"

#include "report/light_mask.h"
#include "report/shimmer.h"

#include <cstdio>

namespace penumbra::cli {
namespace {

// A fraction of a shadow-map texel at the camera's target: the dolly moves by sub-texel steps.
float dollyStep(const RenderResult& first, const Scene& scene, const Camera& camera) {
    for (const LightShadow& s : first.lights)
        if (!s.views.empty()) {
            const ShadowViewInfo& v = s.views.front();
            const Light& light = scene.lights[s.sceneLight];
            return 0.37f * (v.projection == "perspective"
                                ? v.texelWorldSize * glm::length(camera.target - light.position)
                                : v.texelWorldSize);
        }
    return 0.01f * glm::length(camera.target - camera.position);
}

} // namespace

std::vector<PathRow> measurePathShimmer(SceneRenderer& renderer, const Scene& scene,
                                        const std::vector<RenderOptions>& rows,
                                        const std::vector<std::string>& rowNames, CameraPath path,
                                        uint32_t frameCount, const ReferenceOptions& reference) {
    const RenderOptions& base = rows.front();
    const Camera start = scene.camera(base.camera);
    const std::vector<PathFrame> frames = pathFrames(
        path, start, scene.lights, frameCount, dollyStep(renderer.render(base), scene, start));
    // The lights of each frame as the renderer and the truth see them (size overrides applied).
    std::vector<Scene> lit(frames.size(), scene);
    for (size_t t = 0; t < frames.size(); ++t) {
        lit[t].lights = frames[t].lights;
        applyLightSizeOverrides(lit[t], base.lightRadiusOverride, base.lightAngleOverride);
    }
    std::vector<ReferenceResult> truths; // per frame, for the moving sun
    if (path == CameraPath::Sun)
        for (size_t t = 0; t < frames.size(); ++t) {
            std::fprintf(stderr, "penumbra: ground truth of path frame %zu/%zu\n", t + 1,
                         frames.size());
            ReferenceOptions quiet = reference;
            quiet.progress = false;
            truths.push_back(computeReference(
                lit[t],
                renderer.render(base, SceneRenderer::FrameState{.lights = frames[t].lights}),
                quiet));
        }

    std::vector<PathRow> out;
    for (size_t r = 0; r < rows.size(); ++r) {
        PathRow row;
        std::fprintf(stderr, "penumbra: %s along the %s path, %u frames\n", rowNames[r].c_str(),
                     kCameraPathNames[static_cast<int>(path)], frameCount);
        RenderOptions o = rows[r];
        o.frames = 1;
        // Per frame: the visibility to compare, and what it is compared with.
        std::vector<RenderResult> now, before;
        PoolShortage shortage; // said once a row, after its path
        for (size_t t = 0; t < frames.size(); ++t) {
            const SceneRenderer::FrameState state{.camera = frames[t].camera,
                                                  .lights = frames[t].lights};
            now.push_back(renderer.render(o, state));
            shortage.add(now.back());
            if (const auto& pages = now.back().virtualMaps) {
                uint32_t rendered = 0;
                for (uint32_t n : pages->renderedPerFrame)
                    rendered += n;
                row.pagesRendered.push_back(rendered);
                row.pagesResident.push_back(pages->resident);
            }
            if (path != CameraPath::Sun && t > 0) {
                SceneRenderer::FrameState previousViews = state;
                previousViews.shadowCamera = frames[t - 1].camera;
                before.push_back(renderer.render(o, previousViews));
            }
        }
        if (const std::string said = shortage.warning(rowNames[r]); !said.empty())
            std::fprintf(stderr, "penumbra: %s\n", said.c_str());
        std::vector<std::vector<std::vector<uint8_t>>> masks; // [frame][layer]
        for (size_t t = 0; t < frames.size(); ++t)
            masks.push_back(lightMasks(lit[t], now[t]));
        std::vector<ShimmerPair> pairs;
        for (size_t t = 1; t < frames.size(); ++t)
            for (size_t l = 0; l < now[t].visibility.size(); ++l) {
                if (path == CameraPath::Sun)
                    pairs.push_back({.visibility = now[t].visibility[l],
                                     .previous = now[t - 1].visibility[l],
                                     .truth = truths[t].visibility[l],
                                     .previousTruth = truths[t - 1].visibility[l],
                                     .mask = masks[t][l],
                                     .previousMask = masks[t - 1][l]});
                else
                    pairs.push_back({.visibility = now[t].visibility[l],
                                     .previous = before[t - 1].visibility[l],
                                     .mask = masks[t][l],
                                     .previousMask = masks[t][l]});
            }
        row.shimmer = measureShimmer(pairs).shimmer;
        out.push_back(std::move(row));
    }
    return out;
}

} // namespace penumbra::cli
