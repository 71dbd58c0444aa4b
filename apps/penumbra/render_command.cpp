#include "commands.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"
#include "report/field_slice.h"
#include "report/stats.h"
#include "shadows/sdf_field.h"
#include "shadows/technique.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>

namespace penumbra::cli {
namespace {

struct RenderArgs {
    SceneOptions sceneOptions;
    std::string scene, output, technique = "hard";
    std::string fieldSlice = "y";
    std::vector<std::string> sets;
    RenderOptions options;
};

void writeOutputs(StagedOutputDir& out, const RenderResult& r, const RenderRun& run) {
    out.write("image.png", encodePng(r.width, r.height, 4, r.image));
    writeViewFiles(out, r, r.visibility);
    const std::string stats = renderStats(run).dump(2) + "\n";
    out.write("stats.json",
              std::span(reinterpret_cast<const uint8_t*>(stats.data()), stats.size()));
}

int runRender(const RenderArgs& args, const GlobalOptions& global) {
    RenderOptions options = args.options;
    options.technique = findTechnique(args.technique).id;
    for (const std::string& set : args.sets)
        options.parameters.assign(set);
    validate(options);
    const FieldSlice slice = parseFieldSlice(args.fieldSlice);
    const Scene scene = loadSceneReporting(args.scene, global, args.sceneOptions);
    // Created before the long work so an unwritable path fails fast; removed again on error.
    StagedOutputDir out(args.output);

    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    renderer.check(scene, options);
    if (shadows::moduleOf(options.technique).tracesField) { // the slice lies in the field
        const shadows::FieldLayout layout = shadows::fieldLayout(
            scene.bounds(), static_cast<uint32_t>(options.parameters.number("sdf.resolution")));
        (void)slicePosition(slice, layout.origin, layout.voxel, layout.size);
    }
    const DeviceInfo& device = renderer.device();
    std::fprintf(stderr, "penumbra: %s on %s (%s), %ux%u, shadow map %u, technique %s\n",
                 scene.name.c_str(), device.name.c_str(), device.driverName.c_str(), options.width,
                 options.height, options.shadowMapSize, args.technique.c_str());
    std::fprintf(stderr, "penumbra: uploading scene\n");
    SceneRenderer sceneRenderer(renderer, scene);
    const RenderResult result = sceneRenderer.render(options, [](const std::string& stage) {
        std::fprintf(stderr, "penumbra: %s\n", stage.c_str());
    });
    writeOutputs(out, result, {args.scene, scene, options, device, result});
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
    std::printf("GPU ms per pass (median of %u frames after 1 warm-up):", options.frames);
    double total = 0;
    for (const PassTime& p : result.passes) {
        std::printf("  %s %.3f", p.pass.c_str(), p.medianMs);
        total += p.medianMs;
    }
    std::printf("  | total %.3f\n", total);
    if (const auto& f = result.field) {
        std::printf("distance field %ux%ux%u voxels of %.4g (%.1f MiB), built once per scene: "
                    "%.1f ms CPU, GPU",
                    f->voxels.x, f->voxels.y, f->voxels.z, f->voxelSize,
                    static_cast<double>(f->bytes) / (1 << 20), f->buildCpuMs);
        for (const PassTime& p : f->buildPasses)
            std::printf("  %s %.3f", p.pass.c_str(), p.medianMs);
        std::printf("  | total %.3f ms\n", f->buildGpuMs);
    }
    return 0;
}

} // namespace

void addViewOptions(CLI::App& cmd, RenderOptions& o, SceneOptions& scene) {
    cmd.add_option("--width", o.width, "image width in pixels")->capture_default_str();
    cmd.add_option("--height", o.height, "image height in pixels")->capture_default_str();
    CLI::Option* camera = cmd.add_option("--camera", o.camera,
                                         "glTF camera name (default: the first, else automatic)");
    cmd.add_option("--camera-pos", scene.cameraPosition,
                   "X,Y,Z: an ad-hoc camera at this world position (needs --look-at)")
        ->excludes(camera);
    cmd.add_option("--look-at", scene.lookAt, "X,Y,Z: the point the ad-hoc camera looks at")
        ->excludes(camera);
    cmd.add_option("--fov", scene.fovDegrees,
                   "the ad-hoc camera's vertical field of view in degrees (default 45.8)")
        ->excludes(camera);
    cmd.add_option("--sun-dir", scene.sunDirection,
                   "X,Y,Z: the direction a sun's light travels (world space); replaces the "
                   "default light of a scene without lights, else adds a sun");
    cmd.add_option("--light-pos", scene.lightPositions,
                   "NAME=X,Y,Z: move the spot or point light NAME (repeatable)");
    cmd.add_option("--light-dir", scene.lightDirections,
                   "NAME=X,Y,Z: aim the spot or sun NAME (repeatable)");
    cmd.add_option("--light-radius", o.lightRadiusOverride,
                   "spot/point light radius in world units (overrides the scene)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--light-angle", o.lightAngleOverride,
                   "directional light angular diameter in degrees (overrides the scene)")
        ->check(CLI::Range(0.0, 30.0));
}

void writeViewFiles(StagedOutputDir& out, const RenderResult& g,
                    const std::vector<std::vector<float>>& visibility) {
    for (size_t i = 0; i < visibility.size(); ++i)
        out.write(visibilityFileName(i), encodePfm(g.width, g.height, 1, visibility[i]));
    out.write("position.pfm", encodePfm(g.width, g.height, 3, g.position));
    out.write("normal.pfm", encodePfm(g.width, g.height, 3, g.normal));
}

void addTechniqueOptions(CLI::App& cmd, RenderOptions& o, std::vector<std::string>& sets) {
    cmd.add_option("--shadow-map-size", o.shadowMapSize, "shadow map side in texels")
        ->capture_default_str();
    cmd.add_option("--set", sets, "technique parameter family.name=value (repeatable)");
    cmd.add_option("--frames", o.frames, "timed frames after one warm-up frame")
        ->capture_default_str();
}

void addReferenceOptions(CLI::App& cmd, ReferenceOptions& options) {
    cmd.add_option("--samples", options.samples,
                   "ground-truth rays per pixel and light for lights with a size (1..65536)")
        ->capture_default_str();
    cmd.add_option("--embree-config", options.embreeConfig,
                   "Embree device configuration, e.g. threads=2");
}

Scene loadSceneReporting(const std::string& spec, const GlobalOptions& global,
                         const SceneOptions& o) {
    SceneEdits edits{.fovDegrees = o.fovDegrees};
    // Parsed before the scene loads: a typing mistake costs no loading time.
    if (!o.sunDirection.empty())
        edits.sunDirection = parseVector3(o.sunDirection, "--sun-dir");
    if (!o.cameraPosition.empty())
        edits.cameraPosition = parseVector3(o.cameraPosition, "--camera-pos");
    if (!o.lookAt.empty())
        edits.lookAt = parseVector3(o.lookAt, "--look-at");
    for (const std::string& text : o.lightPositions)
        edits.lightPositions.push_back(parseNamedVector3(text, "--light-pos"));
    for (const std::string& text : o.lightDirections)
        edits.lightDirections.push_back(parseNamedVector3(text, "--light-dir"));
    std::vector<std::string> warnings;
    Scene scene = loadScene(spec, {.maxFileSize = global.maxFileSize,
                                   .maxTriangles = global.maxTriangles,
                                   .warnings = &warnings});
    for (const std::string& w : warnings)
        std::fprintf(stderr, "penumbra: warning: %s\n", w.c_str());
    applySceneEdits(scene, edits);
    return scene;
}

std::span<const uint8_t> bytesOf(const std::string& text) {
    return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

Action addRenderCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "render SCENE with one shadow technique into DIR");
    std::string builtins;
    for (std::string_view name : builtinSceneNames())
        builtins += (builtins.empty() ? "" : ", ") + std::string(name);
    cmd->add_option("scene", args->scene, "builtin:NAME (" + builtins + ") or a glTF file")
        ->required();
    cmd->add_option("-o,--output", args->output, "output directory")->required();
    cmd->add_option("--technique", args->technique, "shadow technique (see `penumbra techniques`)")
        ->capture_default_str();
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addTechniqueOptions(*cmd, args->options, args->sets);
    cmd->add_option("--field-slice", args->fieldSlice,
                    "sdf only: the slice of the distance field written to field_slice.png, "
                    "AXIS or AXIS:POSITION (x, y, z; world units; default the box's middle)")
        ->capture_default_str();
    return [args, &global] { return runRender(*args, global); };
}

} // namespace penumbra::cli
