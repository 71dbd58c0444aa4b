// A shard's tasks (sweep_run.h).
#include "sweep_run.h"

#include "compare_timeline.h"

#include "penumbra/error.h"
#include "reference/field_refusal.h"
#include "report/blur_band.h"
#include "report/light_mask.h"
#include "shadows/technique.h"
#include "sweep/records.h"
#include "sweep/truth_bootstrap.h"
#include "sweep/truth_cache.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <optional>

namespace penumbra::cli {
namespace {

using Clock = std::chrono::steady_clock;
constexpr char kPlanLightName[] = "plan light";

// The view's scene options and light sizes: a plan light replaces the scene's lights (added as
// --add-light would, then the others removed); kind "scene" keeps them at the size given.
void lightOptions(const sweep::PlanLight& light, SceneOptions& scene, RenderOptions& options) {
    if (light.kind == "scene") {
        options.lightRadiusOverride = light.size;
        options.lightAngleOverride = light.size;
        return;
    }
    auto v = [](const glm::vec3& p) { return fmt::format("{},{},{}", p.x, p.y, p.z); };
    std::string spec = light.kind + ":";
    if (light.position)
        spec += "pos=" + v(*light.position) + ",";
    if (light.direction)
        spec += "dir=" + v(*light.direction) + ",";
    if (light.coneDegrees)
        spec += fmt::format("cone={},", *light.coneDegrees);
    spec += light.kind == "sun" ? fmt::format("angle={}", light.size)
                                : fmt::format("radius={}", light.size);
    scene.addedLights.push_back(spec + ",name=" + kPlanLightName);
}

struct LoadedView {
    Scene scene, lit;
    RenderOptions base;
};

LoadedView loadView(const sweep::Plan& plan, const sweep::SweepView& view,
                    const GlobalOptions& global) {
    SceneOptions sceneOptions;
    LoadedView v{.base = {.width = plan.width,
                          .height = plan.height,
                          .shadowMapSize = plan.shadowMapSize,
                          .frames = plan.frames,
                          .camera = view.camera}};
    lightOptions(view.light, sceneOptions, v.base);
    if (view.time) {
        // Framed at the plan's first time, as a compare --timeline frames all its frames by its
        // first: the automatic camera, default light and ground hold, and only what the
        // animation moves moves. The warnings are said by the first time's views.
        sceneOptions.animation = view.animation;
        sceneOptions.time = plan.times.front();
        const bool first = *view.time == plan.times.front();
        const Scene framing =
            loadSceneReporting(view.scene.spec, global, sceneOptions, v.base, !first);
        sceneOptions.ground = framing.automaticGround;
        sceneOptions.noGround = !sceneOptions.ground;
        sceneOptions.time = view.time;
        v.scene = first ? framing
                        : loadSceneReporting(view.scene.spec, global, sceneOptions, v.base, true);
        pinToFirstFrame(v.scene, framing);
    } else {
        v.scene = loadSceneReporting(view.scene.spec, global, sceneOptions, v.base);
    }
    if (view.light.kind != "scene") {
        std::erase_if(v.scene.lights, [](const Light& l) { return l.name != kPlanLightName; });
        v.scene.defaultLight = false;
    }
    v.scene.camera(view.camera); // a camera the scene lacks is this view's error
    v.lit = v.scene;
    applyLightSizeOverrides(v.lit, v.base.lightRadiusOverride, v.base.lightAngleOverride);
    return v;
}

sweep::TaskRecord recordOf(const sweep::Plan& plan, const sweep::SweepView& view,
                           const sweep::SweepTask& task) {
    return {.id = task.id,
            .view = view.id,
            .scene = view.scene.label,
            .light = view.light.name,
            .camera = view.camera.empty() ? "(default)" : view.camera,
            .setting = task.setting.name(),
            .technique = task.setting.technique,
            .time = view.time,
            .parameters = task.setting.sets,
            .width = plan.width,
            .height = plan.height,
            .samples = plan.samples};
}

uint64_t seedOf(const std::string& hex) {
    return std::stoull(hex, nullptr, 16);
}

// Renders one task against the view's truth and fills the record's figures.
void measure(sweep::TaskRecord& record, const sweep::SweepTask& task, const LoadedView& view,
             SceneRenderer& uploaded, const RenderResult& gbuffer, const ReferenceResult& truth,
             uint32_t samples) {
    const TechniqueRow row{.name = task.setting.name(),
                           .technique = findTechnique(task.setting.technique).id,
                           .sets = task.setting.sets};
    RenderOptions options = optionsFor(view.base, row, {});
    applyRow(row, options.parameters, view.scene.bounds().radius());
    uploaded.check(options);
    const RenderResult result = uploaded.render(options);
    refuseUnheldField(uploaded, options, result); // sdf.refuse: a failed task, with the reason
    std::vector<std::vector<uint8_t>> masks;
    for (const LightShadow& s : gbuffer.lights)
        if (s.visibilityIndex >= 0)
            masks.push_back(lightMask(view.lit.lights[s.sceneLight], gbuffer));
    const shadows::TechniqueModule& module = shadows::moduleOf(options.technique);
    const BlurReach blur = shadows::blurRadii(module, options.parameters);
    const ErrorMetrics m = metricsAgainstTruth(view.lit, result, truth.visibility, masks, blur,
                                               truth.occluderDistance);
    for (const sweep::MetricField& f : sweep::kMetricFields)
        record.metrics[std::string(f.name)] = m.*f.member;
    const std::vector<uint32_t> perLayer = sweep::truthSamplesPerLayer(view.lit, result, samples);
    const std::vector<ErrorMetrics> replicates =
        sweep::bootstrapMetrics(truth, perLayer, sweep::kBootstrapReplicates, seedOf(task.id),
                                [&](const ReferenceResult& redrawn) {
                                    return metricsAgainstTruth(view.lit, result, redrawn.visibility,
                                                               masks, blur, truth.occluderDistance);
                                });
    for (const ErrorMetrics& r : replicates)
        for (const sweep::MetricField& f : sweep::kMetricFields)
            record.replicates[std::string(f.name)].push_back(r.*f.member);
    sweep::setCosts(record, result.passes);
}

// ", at 0.5 s" for a view at a time, else nothing.
std::string atTime(const sweep::SweepView& view) {
    return view.time ? fmt::format(", at {} s", *view.time) : std::string();
}

std::string clockText(double seconds) {
    const long s = long(seconds + 0.5);
    return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                     : fmt::format("{}:{:02}", s / 60, s % 60);
}

} // namespace

SweepRunStats runSweepTasks(const sweep::Plan& plan, const sweep::SweepTasks& tasks,
                            std::span<const size_t> mine, const std::filesystem::path& output,
                            const std::filesystem::path& truthCache, const GlobalOptions& global) {
    SweepRunStats stats;
    std::map<size_t, std::vector<size_t>> pending; // by view, in task order
    for (size_t t : mine) {
        std::error_code ec;
        if (std::filesystem::exists(sweep::taskRecordPath(output, tasks.tasks[t].id), ec))
            ++stats.skipped;
        else
            pending[tasks.tasks[t].view].push_back(t);
    }
    size_t total = 0;
    for (const auto& [view, list] : pending)
        total += list.size();
    std::fprintf(stderr,
                 "penumbra: sweep: %zu task(s) in this shard, %zu done already, %zu to run\n",
                 mine.size(), stats.skipped, total);
    if (total == 0)
        return stats;
    const sweep::TruthCache cache(truthCache);
    std::optional<Renderer> renderer;
    const Clock::time_point start = Clock::now();
    auto progress = [&](const sweep::SweepTask& task, const sweep::SweepView& view) {
        const size_t done = stats.ran;
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        const std::string eta =
            done == 0 ? "?" : clockText(elapsed / double(done) * double(total - done));
        std::fprintf(stderr, "penumbra: sweep [%zu/%zu] %s on %s, %s%s (elapsed %s, ETA %s)\n",
                     done + 1, total, task.setting.name().c_str(), view.scene.label.c_str(),
                     view.light.name.c_str(), atTime(view).c_str(), clockText(elapsed).c_str(),
                     eta.c_str());
    };
    for (const auto& [viewIndex, list] : pending) {
        const sweep::SweepView& view = tasks.views[viewIndex];
        auto failAll = [&](size_t from, const std::string& why) {
            for (size_t k = from; k < list.size(); ++k) {
                sweep::TaskRecord record = recordOf(plan, view, tasks.tasks[list[k]]);
                record.failed = true;
                record.error = why;
                writeTaskRecord(output, record);
                ++stats.ran, ++stats.failed;
            }
            std::fprintf(stderr, "penumbra: sweep: warning: view %s: %s\n", view.id.c_str(),
                         why.c_str());
        };
        std::optional<LoadedView> loaded;
        try {
            loaded = loadView(plan, view, global);
        } catch (const InputError& e) {
            failAll(0, e.what());
            continue;
        }
        if (!renderer)
            renderer.emplace(
                DeviceOptions{.deviceIndex = global.device, .validation = global.validation});
        SceneRenderer uploaded(*renderer, loaded->scene);
        RenderOptions gbufferOptions = loaded->base; // what the truth traces from: one frame
        gbufferOptions.frames = 1;
        const RenderResult gbuffer = uploaded.render(gbufferOptions);
        bool computed = false;
        const std::string key =
            sweep::truthKey(loaded->lit, view.camera, plan.width, plan.height, plan.samples);
        const ReferenceResult truth = sweep::cachedTruth(
            &cache, key,
            [&] {
                std::fprintf(stderr, "penumbra: sweep: tracing the truth of view %s (%s, %s%s)\n",
                             view.id.c_str(), view.scene.label.c_str(), view.light.name.c_str(),
                             atTime(view).c_str());
                return computeReference(loaded->lit, gbuffer, {.samples = plan.samples});
            },
            &computed);
        ++(computed ? stats.truthsComputed : stats.truthsCached);
        for (size_t k = 0; k < list.size(); ++k) {
            const sweep::SweepTask& task = tasks.tasks[list[k]];
            progress(task, view);
            sweep::TaskRecord record = recordOf(plan, view, task);
            record.device = renderer->device().name;
            record.truthKey = key;
            record.truthComputed = computed && k == 0;
            try {
                measure(record, task, *loaded, uploaded, gbuffer, truth, plan.samples);
            } catch (const InputError& e) { // the device cannot hold this setting
                record = recordOf(plan, view, task);
                record.failed = true;
                record.error = e.what();
                ++stats.failed;
                std::fprintf(stderr, "penumbra: sweep: warning: %s failed: %s\n",
                             task.setting.name().c_str(), e.what());
            }
            writeTaskRecord(output, record);
            ++stats.ran;
        }
    }
    if (renderer && renderer->validationErrors() > 0)
        throw std::runtime_error(
            fmt::format("vulkan validation: {} error(s)", renderer->validationErrors()));
    return stats;
}

} // namespace penumbra::cli
