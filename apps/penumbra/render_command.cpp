#include "commands.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "reference/field_refusal.h"
#include "render_playback.h"
#include "report/field_slice.h"
#include "report/stats.h"
#include "shadows/layer.h"
#include "shadows/sdf_field.h"
#include "shadows/technique.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <optional>

namespace penumbra::cli {
namespace {

struct RenderArgs {
    SceneOptions sceneOptions;
    std::string scene, output, technique = std::string(techniqueName(kDefaultTechnique));
    std::string fieldSlice = "y";
    std::vector<std::string> sets;
    RenderOptions options;
    FloatFormat format = FloatFormat::Both;
    std::optional<double> fps; // --fps: the timed frames play the animation
};

void writeOutputs(StagedOutputDir& out, const RenderResult& r, const RenderRun& run,
                  FloatFormat format) {
    out.write("image.png", encodePng(r.width, r.height, 4, r.image));
    writeViewFiles(out, r, r.visibility, format, r.transmittance);
    if (run.options.motion && !r.motion.empty()) // a history layer makes them too, unasked
        writeFloatImage(out, "motion", format, r.width, r.height, 3, r.motion);
    const std::string stats = renderStats(run).dump(2) + "\n";
    out.write("stats.json",
              std::span(reinterpret_cast<const uint8_t*>(stats.data()), stats.size()));
}

int runRender(const RenderArgs& args, const GlobalOptions& global) {
    // A technique, or one of compare's rows ("pcf[box7]", "pcf[box3]+contact") as compare runs it.
    const TechniqueRow row = rowNamed(args.technique, "--technique");
    RenderOptions options = optionsFor(args.options, row, args.sets);
    const FieldSlice slice = parseFieldSlice(args.fieldSlice);
    SceneOptions sceneOptions = args.sceneOptions;
    if (args.fps) // playing starts at 0 s, not at rest
        sceneOptions.time = sceneOptions.time.value_or(0.0);
    const PlaybackInputs playback{.sceneSpec = args.scene,
                                  .global = global,
                                  .sceneOptions = sceneOptions,
                                  .fps = args.fps.value_or(0.0)};
    if (args.fps) // refused before a warning of the load is said
        checkPlayback(playback,
                      loadSceneReporting(args.scene, global, sceneOptions, args.options,
                                         /*quiet=*/true),
                      options.frames);
    const Scene scene = loadSceneReporting(args.scene, global, sceneOptions, args.options);
    if (!row.layers.empty()) // the layers it names, as compare runs them (the others off)
        applyRow(row, options.parameters, scene.bounds().radius());
    // Created before the long work so an unwritable path fails fast; removed again on error.
    StagedOutputDir out(args.output);

    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    renderer.check(scene, options);
    if (const auto& declared = shadows::moduleOf(options.technique).tracedField) {
        const shadows::FieldLayout layout = shadows::fieldLayout( // the slice lies in the field
            scene.bounds(),
            static_cast<uint32_t>(options.parameters.number(declared->resolutionKey)));
        (void)slicePosition(slice, layout.origin, layout.voxel, layout.size);
    }
    const DeviceInfo& device = renderer.device();
    std::fprintf(stderr, "penumbra: %s on %s (%s), %ux%u, shadow map %u, technique %s\n",
                 scene.name.c_str(), device.name.c_str(), device.driverName.c_str(), options.width,
                 options.height, options.shadowMapSize, args.technique.c_str());
    warnOpenGeometry(scene, std::span(&options.technique, 1)); // after every check: no warning
                                                               // precedes an error line
    std::fprintf(stderr, "penumbra: uploading scene\n");
    PlayedFrames shown; // with --fps, the last frame's pose; else the scene as loaded
    if (args.fps) {
        shown = playFrames(renderer, playback, scene, options);
    } else {
        shown.uploaded = std::make_unique<SceneRenderer>(renderer, scene);
        shown.result = shown.uploaded->render(options, [](const std::string& stage) {
            std::fprintf(stderr, "penumbra: %s\n", stage.c_str());
        });
    }
    const Scene& shownScene = args.fps ? shown.scene : scene;
    SceneRenderer& sceneRenderer = *shown.uploaded;
    const RenderResult& result = shown.result;
    // sdf.refuse: an error line and no output where the field cannot hold the view's casters.
    refuseUnheldField(sceneRenderer, options, result, [](const std::string& line) {
        std::fprintf(stderr, "penumbra: %s\n", line.c_str());
    });
    writeOutputs(out, result,
                 {.sceneSpec = args.scene,
                  .scene = shownScene,
                  .options = options,
                  .device = device,
                  .result = result,
                  .floatExtension = namingExtension(args.format),
                  .fps = args.fps.value_or(0.0)},
                 args.format);
    if (result.field) { // what the tracer saw
        DistanceFieldInfo info;
        const std::vector<float> voxels = sceneRenderer.distanceField(info);
        const SliceImage image = fieldSlice(voxels, info, slice);
        out.write("field_slice.png", encodePng(image.width, image.height, 3, image.rgb));
    }
    if (renderer.validationErrors() > 0)
        throw std::runtime_error(fmt::format("vulkan validation: {} error(s), see messages above; "
                                             "no output written",
                                             renderer.validationErrors()));
    out.commit();

    std::string files;
    for (const std::string& f : out.staged())
        files += (files.empty() ? "" : ", ") + f;
    std::printf("wrote %s/{%s}\n", out.path().c_str(), files.c_str());
    const uint32_t warmUpCount =
        shadows::warmUpFrames(options.parameters, result.virtualMaps.has_value());
    const std::string warmUps =
        fmt::format("{} warm-up{}", warmUpCount, warmUpCount == 1 ? "" : "s");
    if (args.fps)
        std::printf("GPU ms per pass (median of %u frames at %g a second, the first pose after "
                    "%s, each later one the next frame):",
                    options.frames, *args.fps, warmUps.c_str());
    else
        std::printf("GPU ms per pass (median of %u frames after %s):", options.frames,
                    warmUps.c_str());
    double total = 0;
    for (const PassTime& p : result.passes) {
        std::printf("  %s %.3f", p.pass.c_str(), p.medianMs);
        total += p.medianMs;
    }
    std::printf("  | total %.3f\n", total);
    if (const auto& f = result.field) {
        std::printf("distance field %ux%ux%u voxels of %.4g (%.1f MiB) from %u triangles",
                    f->voxels.x, f->voxels.y, f->voxels.z, f->voxelSize,
                    static_cast<double>(f->bytes) / (1 << 20), f->triangles);
        if (f->alphaTriangles > 0)
            std::printf(" (%u alpha-tested, cut into %u pieces)", f->alphaTriangles,
                        f->alphaPieces);
        std::printf(", built once per scene: %.1f ms CPU, GPU", f->buildCpuMs);
        for (const PassTime& p : f->buildPasses)
            std::printf("  %s %.3f", p.pass.c_str(), p.medianMs);
        std::printf("  | total %.3f ms\n", f->buildGpuMs);
    }
    return 0;
}

} // namespace

Action addRenderCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "render SCENE with one shadow technique into DIR");
    addSceneArgument(*cmd, args->scene);
    cmd->add_option("-o,--output", args->output, "output directory, created if missing")
        ->type_name("DIR")
        ->required();
    cmd->add_option("--technique", args->technique,
                    "the shadow technique, or a compare row such as `pcf[box7]` (`penumbra "
                    "techniques` lists them with their parameters)")
        ->type_name("T")
        ->capture_default_str();
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addTechniqueOptions(*cmd, args->options, args->sets);
    addFormatOption(*cmd, args->format);
    cmd->add_option("--fps", args->fps,
                    "play: the `--frames` timed frames are successive poses F a second from "
                    "`--time` (default 0 s) of an animated scene (or one whose added lights "
                    "orbit), each loaded, framed as the first and drawn as the next frame of one "
                    "renderer (no warm-up between poses); the GPU times are each pass's per frame "
                    "while things move and their median, the outputs the last frame's")
        ->type_name("F")
        ->check(nonEmptyValue("a rate in frames a second"));
    cmd->add_flag("--motion", args->options.motion,
                  "also write `motion` (.pfm, .exr): each pixel's motion since the frame before, "
                  "from the G-buffer (x, y: where the surface is minus where it was, in pixels, x "
                  "right and y down; z: its depth then, NDC reverse-Z; NaN for background); "
                  "zero unless `--fps` moves the scene");
    // The techniques that trace a distance field, from the registry.
    const std::string tracing = shadows::techniquesWhere(
        [](const shadows::TechniqueModule& m) { return m.tracedField.has_value(); });
    cmd->add_option("--field-slice", args->fieldSlice,
                    fmt::format("{} only: the slice of the distance field written to "
                                "`field_slice.png`, across x, y or z, at world coordinate POS "
                                "(default: the middle of the field's box; outside it: an error)",
                                tracing))
        ->type_name("AXIS[:POS]")
        ->capture_default_str();
    return [args, &global] { return runRender(*args, global); };
}

} // namespace penumbra::cli
