#include "compare_timeline.h"

#include "penumbra/pass_times.h"

#include "penumbra/error.h"
#include "pool_shortage.h"
#include "report/light_mask.h"
#include "report/shimmer.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace penumbra::cli {
namespace {

// Frame k's scene, quietly: the compare command's own load of the first frame said the
// warnings. A frame refused names itself, since the first frame was accepted.
Scene loadFrame(const TimelineInputs& in, const SceneOptions& options, size_t k,
                const Timeline& timeline) {
    return loadPose(
        [&] {
            return loadSceneReporting(in.sceneSpec, in.global, options, in.rowOptions.front(),
                                      /*quiet=*/true);
        },
        fmt::format("--timeline frame {} of {}, at {:g} s", k + 1, timeline.frames,
                    timeline.at(k)));
}

double totalMs(const RenderResult& r) {
    double total = 0.0;
    for (const PassTime& p : r.passes)
        total += p.medianMs;
    return total;
}

} // namespace

Scene loadPose(const std::function<Scene()>& load, const std::string& which) {
    try {
        return load();
    } catch (const InputError& e) {
        const std::string what = e.what();
        const std::string prefix = e.subject() + ": ";
        throw InputError(e.subject(),
                         fmt::format("{} ({})",
                                     what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what,
                                     which));
    }
}

void pinToFirstFrame(Scene& scene, const Scene& first) {
    // Framed by Penumbra, whatever its name: a file's camera called "autocam" is its own.
    const auto automatic = [](const Camera& c) { return c.automatic; };
    if (!first.cameras.empty() && automatic(first.cameras.front()) && !scene.cameras.empty() &&
        automatic(scene.cameras.front()))
        scene.cameras.front() = first.cameras.front();
    if (first.defaultLight && scene.defaultLight)
        scene.lights.front() = first.lights.front();
}

std::vector<TimelineRow> runTimeline(Renderer& renderer, const TimelineInputs& in,
                                     const Timeline& timeline) {
    std::vector<TimelineRow> rows(in.rowNames.size());
    for (size_t r = 0; r < rows.size(); ++r)
        rows[r].name = in.rowNames[r];
    std::vector<RenderResult> previous, previousInMotion;
    ReferenceResult previousTruth;
    std::vector<std::vector<uint8_t>> previousMasks;
    // Each row's |change of the error| summed over pixels: at rest and as played.
    std::vector<double> flickerSum(rows.size(), 0.0), movingFlickerSum(rows.size(), 0.0);
    std::vector<PoolShortage> shortage(rows.size()); // each row's, still and in motion
    Scene first;
    SceneOptions options = in.sceneOptions;
    // In motion: a renderer per row that draws every frame in turn (rows differ in their maps,
    // which one renderer would remake between rows, losing what the technique kept).
    std::vector<std::unique_ptr<SceneRenderer>> moving(rows.size());
    // Latched once the rows' renderers together pass the device's local memory (each holds its
    // maps): from then on each keeps between frames only what its next frame reads.
    bool trimming = false;
    for (size_t k = 0; k < timeline.frames; ++k) {
        options.time = timeline.at(k);
        std::fprintf(stderr, "penumbra: timeline frame %zu/%zu at %g s\n", k + 1, timeline.frames,
                     *options.time);
        Scene scene = loadFrame(in, options, k, timeline);
        if (k == 0) {
            first = scene;
            // The first frame's choice of ground holds for all.
            options.ground = options.ground || scene.automaticGround;
            options.noGround = !options.ground;
        } else {
            pinToFirstFrame(scene, first);
        }
        SceneRenderer uploaded(renderer, scene);
        std::vector<RenderResult> results;
        for (const RenderOptions& o : in.rowOptions)
            results.push_back(uploaded.render(o));
        std::vector<RenderResult> inMotion;
        for (size_t r = 0; r < rows.size(); ++r) {
            RenderOptions one = in.rowOptions[r];
            one.frames = 1;
            if (k == 0) { // the motion starts at rest
                moving[r] = std::make_unique<SceneRenderer>(renderer, scene);
                inMotion.push_back(moving[r]->render(one));
            } else {
                moving[r]->repose(scene);
                inMotion.push_back(moving[r]->render(one, {.continues = true}));
            }
            if (!trimming &&
                renderer.deviceMemoryInUse().bytes > renderer.device().deviceLocalBytes) {
                trimming = true;
                std::fprintf(stderr,
                             "penumbra: the rows in motion hold more than the device's %.1f GiB "
                             "of local memory: each keeps between frames only what its next "
                             "frame reads (its GPU time in motion includes making the rest "
                             "again)\n",
                             static_cast<double>(renderer.device().deviceLocalBytes) / (1 << 30));
                for (size_t q = 0; q < r; ++q)
                    moving[q]->trim();
            }
            if (trimming)
                moving[r]->trim();
        }
        Scene lit = scene;
        const RenderOptions& base = in.rowOptions.front();
        applyLightSizeOverrides(lit, base.lightRadiusOverride, base.lightAngleOverride);
        ReferenceOptions quiet = in.reference;
        quiet.progress = false;
        ReferenceResult truth = computeReference(lit, results.front(), quiet);
        const std::vector<std::vector<uint8_t>> masks = lightMasks(lit, results.front());
        for (size_t r = 0; r < rows.size(); ++r) {
            const ErrorMetrics m = metricsAgainstTruth(lit, results[r], truth.visibility, masks,
                                                       in.blur[r], truth.occluderDistance);
            rows[r].rmse.push_back(m.rmse);
            rows[r].mae.push_back(m.mae);
            rows[r].acne.push_back(m.acne);
            rows[r].leak.push_back(m.leak);
            rows[r].gpuMs.push_back(totalMs(results[r]));
            rows[r].movingRmse.push_back(metricsAgainstTruth(lit, inMotion[r], truth.visibility,
                                                             masks, in.blur[r],
                                                             truth.occluderDistance)
                                             .rmse);
            rows[r].movingGpuMs.push_back(totalMs(inMotion[r]));
            shortage[r].add(results[r]);
            shortage[r].add(inMotion[r]);
            if (const auto& pages = inMotion[r].virtualMaps)
                rows[r].movingPages.push_back({.requested = pages->requested,
                                               .rendered = pages->rendered,
                                               .resident = pages->resident});
            appendFrameTimes(rows[r].movingPasses, inMotion[r].passes, k);
            if (k == 0)
                continue;
            const auto flickerOf = [&](const RenderResult& now, const RenderResult& before) {
                std::vector<ShimmerPair> pairs;
                for (size_t l = 0; l < truth.visibility.size(); ++l)
                    pairs.push_back({.visibility = now.visibility[l],
                                     .previous = before.visibility[l],
                                     .truth = truth.visibility[l],
                                     .previousTruth = previousTruth.visibility[l],
                                     .mask = masks[l],
                                     .previousMask = previousMasks[l]});
                return measureFlicker(pairs);
            };
            const ShimmerResult f = flickerOf(results[r], previous[r]);
            flickerSum[r] += f.shimmer * static_cast<double>(f.pixels);
            rows[r].flickerPixels += f.pixels;
            // As played: what a technique that keeps state (a history, cached pages) shows from
            // frame to frame, which its poses drawn afresh at rest cannot.
            const ShimmerResult played = flickerOf(inMotion[r], previousInMotion[r]);
            movingFlickerSum[r] += played.shimmer * static_cast<double>(played.pixels);
            rows[r].movingFlickerPixels += played.pixels;
        }
        previous = std::move(results);
        previousInMotion = std::move(inMotion);
        previousTruth = std::move(truth);
        previousMasks = masks;
    }
    for (size_t r = 0; r < rows.size(); ++r)
        if (const std::string said = shortage[r].warning(rows[r].name); !said.empty())
            std::fprintf(stderr, "penumbra: %s\n", said.c_str());
    for (size_t r = 0; r < rows.size(); ++r)
        rows[r].lag = measureLag(rows[r].rmse, rows[r].movingRmse);
    const auto mean = [](double sum, uint64_t pixels) {
        return pixels ? sum / static_cast<double>(pixels) : 0.0;
    };
    for (size_t r = 0; r < rows.size(); ++r) {
        rows[r].flicker = mean(flickerSum[r], rows[r].flickerPixels);
        rows[r].movingFlicker = mean(movingFlickerSum[r], rows[r].movingFlickerPixels);
    }
    return rows;
}

nlohmann::json timelineJson(const Timeline& timeline, const std::vector<TimelineRow>& rows) {
    nlohmann::json times = nlohmann::json::array();
    for (size_t k = 0; k < timeline.frames; ++k)
        times.push_back(timeline.at(k));
    nlohmann::json out = {{"start", timeline.start},
                          {"end", timeline.end},
                          {"step", timeline.step},
                          {"times", times},
                          {"rows", nlohmann::json::object()}};
    for (const TimelineRow& row : rows) {
        const auto stats = [](const std::vector<double>& v) {
            double sum = 0.0, most = 0.0;
            for (double x : v)
                sum += x, most = std::max(most, x);
            return nlohmann::json{{"mean", v.empty() ? 0.0 : sum / double(v.size())},
                                  {"max", most}};
        };
        nlohmann::json byPass = nlohmann::json::object();
        for (const PassTime& p : row.movingPasses)
            byPass[p.pass] = p.frameMs;
        out["rows"][row.name] = {{"rmse", row.rmse},
                                 {"mae", row.mae},
                                 {"acne", row.acne},
                                 {"leak", row.leak},
                                 {"gpu_ms", row.gpuMs},
                                 {"rmse_over_time", stats(row.rmse)},
                                 {"gpu_ms_over_time", stats(row.gpuMs)},
                                 {"flicker", row.flicker},
                                 {"flicker_pixels", row.flickerPixels},
                                 {"rmse_moving", row.movingRmse},
                                 {"gpu_ms_moving", row.movingGpuMs},
                                 {"gpu_ms_moving_by_pass", byPass},
                                 {"rmse_moving_over_time", stats(row.movingRmse)},
                                 {"gpu_ms_moving_over_time", stats(row.movingGpuMs)},
                                 {"flicker_moving", row.movingFlicker},
                                 {"flicker_moving_pixels", row.movingFlickerPixels},
                                 {"pop_in", row.lag.popIn},
                                 {"pop_in_ratio", row.lag.popInRatio},
                                 {"lag_frames", row.lag.lagFrames},
                                 {"lagging_frames", row.lag.laggingFrames}};
        if (!row.movingPages.empty()) {
            nlohmann::json pages = {{"requested", nlohmann::json::array()},
                                    {"rendered", nlohmann::json::array()},
                                    {"resident", nlohmann::json::array()}};
            for (const TimelineRow::Pages& p : row.movingPages) {
                pages["requested"].push_back(p.requested);
                pages["rendered"].push_back(p.rendered);
                pages["resident"].push_back(p.resident);
            }
            out["rows"][row.name]["pages_moving"] = pages;
        }
    }
    return out;
}

std::string timelineCsv(const Timeline& timeline, const std::vector<TimelineRow>& rows) {
    std::string csv = "time,row,rmse,mae,acne,leak,gpu_ms,rmse_moving,gpu_ms_moving\n";
    for (size_t k = 0; k < timeline.frames; ++k)
        for (const TimelineRow& row : rows)
            csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", timeline.at(k), row.name,
                               row.rmse[k], row.mae[k], row.acne[k], row.leak[k], row.gpuMs[k],
                               row.movingRmse[k], row.movingGpuMs[k]);
    return csv;
}

} // namespace penumbra::cli
