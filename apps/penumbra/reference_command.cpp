#include "commands.h"
#include "penumbra/error.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "report/stats.h"
#include "report/truth_notes.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>

namespace penumbra::cli {
namespace {

struct ReferenceArgs {
    SceneOptions sceneOptions;
    std::string scene, output;
    RenderOptions options;
    ReferenceOptions reference{.progress = true};
    FloatFormat format = FloatFormat::Both;
};

int runReference(const ReferenceArgs& args, const GlobalOptions& global) {
    RenderOptions options = args.options;
    options.frames = 1;
    options.shadowMapSize = 64; // only the G-buffer is used; keep the shadow pass cheap
    validate(options);
    validate(args.reference);
    Scene scene = loadSceneReporting(args.scene, global, args.sceneOptions, args.options);
    StagedOutputDir out(args.output);
    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    renderer.check(scene, options);
    const RenderResult gbuffer = renderer.render(scene, options);
    applyLightSizeOverrides(scene, options.lightRadiusOverride, options.lightAngleOverride);
    const std::vector<bool> sized = shadowLightsSized(scene, gbuffer);
    std::fprintf(stderr, "penumbra: reference for %s, %ux%u, %s\n", scene.name.c_str(),
                 options.width, options.height,
                 truthRaysText(args.reference.samples, sized).c_str());
    const ReferenceResult truth = computeReference(scene, gbuffer, args.reference);
    writeViewFiles(out, gbuffer, truth.visibility, args.format, truth.transmittance);
    const double raysPerSecond =
        truth.traceSeconds > 0 ? static_cast<double>(truth.rays) / truth.traceSeconds : 0;
    const nlohmann::json info = {
        {"scene", args.scene},
        {"width", options.width},
        {"height", options.height},
        {"samples", args.reference.samples},
        {"rays_per_pixel", truthRays(args.reference.samples, sized)},
        {"rays", truth.rays},
        {"seconds", truth.seconds},
        {"rays_per_second", raysPerSecond},
        {"triangles", truth.triangles},
        {"embree", embreeVersion()},
        {"camera", scene.camera(options.camera).name},
        {"scene_edits", sceneEditsJson(scene.edits)},
        {"automatic_ground", scene.automaticGround},
        // The pose, as stats.json gives it.
        {"time", scene.time ? nlohmann::json(*scene.time) : nlohmann::json()},
        {"animation", scene.animation},
        {"animation_duration", scene.animationDuration},
        {"view", viewJson(scene, scene.camera(options.camera))}};
    out.write("reference.json", bytesOf(info.dump(2) + "\n"));
    if (renderer.validationErrors() > 0)
        throw std::runtime_error(fmt::format("vulkan validation: {} error(s); no output written",
                                             renderer.validationErrors()));
    out.commit();
    std::printf("wrote %s: %zu light(s), %.3g rays in %.2f s (%.2f Mrays/s)\n", out.path().c_str(),
                truth.visibility.size(), static_cast<double>(truth.rays), truth.seconds,
                raysPerSecond * 1e-6);
    return 0;
}

} // namespace

Action addReferenceCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<ReferenceArgs>();
    CLI::App* cmd = app.add_subcommand(
        "reference", "ray-traced ground-truth visibility (Embree) for the same view as render");
    addSceneArgument(*cmd, args->scene);
    cmd->add_option("-o,--output", args->output, "output directory, created if missing")
        ->type_name("DIR")
        ->required();
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addReferenceOptions(*cmd, args->reference);
    addFormatOption(*cmd, args->format);
    return [args, &global] { return runReference(*args, global); };
}

} // namespace penumbra::cli
