// `penumbra compare`: every technique row and the ground truth on the same pixels; writes
// report.html (self-contained), metrics.json, and each row's images and analysis buffers.
#include "commands.h"
#include "compare_path.h"
#include "compare_timeline.h"
#include "core/image_io.h"
#include "penumbra/error.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "reference/field_refusal.h"
#include "report/blur_band.h"
#include "report/heatmap.h"
#include "report/html_report.h"
#include "report/light_mask.h"
#include "report/metrics.h"
#include "report/page_image.h"
#include "report/stats.h"
#include "report/truth_notes.h"
#include "shadows/technique.h"
#include "truth_cache_option.h"

#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <memory>

namespace penumbra::cli {
namespace {

struct CompareArgs {
    SceneOptions sceneOptions;
    std::string scene, output, techniques;
    std::vector<std::string> sets;
    RenderOptions options;
    ReferenceOptions reference{.progress = true};
    std::string cameraPath; // empty: no shimmer
    std::string truthCache; // empty: no cache
    std::string timeline;   // empty: the one frame
    uint32_t pathFrames = 8;
    // OpenEXR alone: what image tools open, and 50 to 250 times smaller than PFM for these
    // images (docs/cli.md); `--format pfm` or `both` on request.
    FloatFormat format = FloatFormat::Exr;
};

// File-name prefix of a row: "pcf[box7]" -> "pcf-box7", "pcf[box3]+contact" -> "pcf-box3-contact".
std::string filePrefix(const std::string& row) {
    std::string out;
    for (char c : row)
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')
            out += c;
        else if (c == '[' || c == '+')
            out += '-';
    return out;
}

std::string describeLight(const Light& l) {
    return l.type == LightType::Directional
               ? fmt::format("{}: directional, angular diameter {} deg", l.name, l.angularDiameter)
               : fmt::format("{}: {}, radius {}", l.name, lightTypeName(l.type), l.radius);
}

BlurReach blurRadiusTexels(const RenderOptions& o) {
    return shadows::blurRadii(shadows::moduleOf(o.technique), o.parameters);
}

int runCompare(const CompareArgs& args, const GlobalOptions& global) {
    std::vector<TechniqueRow> rows = comparisonRows(args.techniques);
    std::vector<RenderOptions> rowOptions;
    for (const TechniqueRow& row : rows)
        rowOptions.push_back(optionsFor(args.options, row, args.sets));
    validate(args.reference);
    CameraPath path{};
    if (!args.cameraPath.empty() && !cameraPathFromName(args.cameraPath, path))
        throw InputError("--camera-path",
                         fmt::format("'{}' is not dolly, orbit or sun", args.cameraPath));
    std::optional<Timeline> timeline;
    SceneOptions sceneOptions = args.sceneOptions;
    if (!args.timeline.empty()) {
        timeline = parseTimeline(args.timeline);
        sceneOptions.time = timeline->start; // the usual outputs are the first frame's
    }
    Scene scene = loadSceneReporting(args.scene, global, sceneOptions, args.options);
    // A row's layers that the settings leave off take the layer's settings for this scene's size.
    for (size_t i = 0; i < rows.size(); ++i)
        applyRow(rows[i], rowOptions[i].parameters, scene.bounds().radius());
    StagedOutputDir out(args.output);
    Renderer renderer({.deviceIndex = global.device, .validation = global.validation});
    // A row the device cannot hold (its maps past the device's memory or limits) is skipped and
    // marked in the table and the report; only when no row fits is it an error.
    std::vector<ReportRow> skipped;
    std::exception_ptr firstRefusal;
    for (size_t r = rows.size(); r-- > 0;) {
        try {
            renderer.check(scene, rowOptions[r]);
        } catch (const InputError& e) {
            firstRefusal = std::current_exception();
            skipped.insert(skipped.begin(),
                           {.name = rows[r].name,
                            .technique = std::string(techniqueName(rows[r].technique)),
                            .skipped = e.what()});
            rows.erase(rows.begin() + std::ptrdiff_t(r));
            rowOptions.erase(rowOptions.begin() + std::ptrdiff_t(r));
        }
    }
    if (rows.empty())
        std::rethrow_exception(firstRefusal); // the error it always was, without warnings
    for (const ReportRow& row : skipped)
        std::fprintf(stderr, "penumbra: warning: %s skipped: %s\n", row.name.c_str(),
                     row.skipped.c_str());
    const DeviceInfo& device = renderer.device();

    std::vector<Technique> techniques;
    for (const TechniqueRow& row : rows)
        techniques.push_back(row.technique);
    warnOpenGeometry(scene, techniques);     // after every check
    SceneRenderer uploaded(renderer, scene); // one upload and one set of targets for all rows
    std::vector<RenderResult> results;
    const size_t rendering = rows.size();
    std::vector<size_t> refusedWhileRendering; // of `skipped`: warned once the rest is rendered
    for (size_t r = 0, shown = 1; r < rows.size(); ++shown) {
        std::fprintf(stderr, "penumbra: rendering %s (%zu/%zu) on %s\n", rows[r].name.c_str(),
                     shown, rendering, device.name.c_str());
        // The distance field's build (sdf: once, minutes on a large scene) and warnings; not
        // each frame's stages. A pool too small is said for the row once after a timeline or a
        // camera path, whose frames include this view's.
        const bool poolSaidLater = timeline || !args.cameraPath.empty();
        results.push_back(uploaded.render(rowOptions[r], [&](const std::string& stage) {
            if (poolSaidLater && stage.find("the virtual pool holds") != std::string::npos)
                return;
            if (stage.find("distance field") != std::string::npos ||
                stage.rfind("warning:", 0) == 0)
                std::fprintf(stderr, "penumbra: %s\n", stage.c_str());
        }));
        try { // sdf.refuse: a row whose field cannot hold the view's casters is skipped
            refuseUnheldField(uploaded, rowOptions[r], results.back(), [](const std::string& line) {
                std::fprintf(stderr, "penumbra: %s\n", line.c_str());
            });
            ++r;
        } catch (const InputError& e) {
            firstRefusal = std::current_exception();
            refusedWhileRendering.push_back(skipped.size());
            skipped.push_back({.name = rows[r].name,
                               .technique = std::string(techniqueName(rows[r].technique)),
                               .skipped = e.what()});
            results.pop_back();
            rows.erase(rows.begin() + std::ptrdiff_t(r));
            rowOptions.erase(rowOptions.begin() + std::ptrdiff_t(r));
        }
    }
    if (rows.empty())
        std::rethrow_exception(firstRefusal); // one error line, no warning before it
    for (size_t k : refusedWhileRendering)
        std::fprintf(stderr, "penumbra: warning: %s skipped: %s\n", skipped[k].name.c_str(),
                     skipped[k].skipped.c_str());
    Scene lit = scene; // the light sizes the reference must use
    applyLightSizeOverrides(lit, args.options.lightRadiusOverride, args.options.lightAngleOverride);
    const RenderResult& gbuffer = results.front(); // every row sees the same view
    const std::vector<bool> sized = shadowLightsSized(lit, gbuffer);
    std::fprintf(stderr, "penumbra: ground truth, %s\n",
                 truthRaysText(args.reference.samples, sized).c_str());
    const ReferenceResult truth =
        truthThroughCache(args.truthCache, lit, args.options.camera, gbuffer, args.reference);
    const uint32_t w = gbuffer.width, h = gbuffer.height;

    ReportData report{.scene = args.scene,
                      .device = device.name,
                      .driver = device.driverName + " " + device.driverInfo,
                      .width = w,
                      .height = h,
                      .shadowMapSize = args.options.shadowMapSize,
                      .samples = args.reference.samples,
                      .referenceSeconds = truth.seconds,
                      .raysPerSecond =
                          truth.traceSeconds > 0 ? double(truth.rays) / truth.traceSeconds : 0};
    report.lightSized = sized;
    std::vector<std::vector<uint8_t>> masks;
    for (const LightShadow& s : gbuffer.lights)
        if (s.visibilityIndex >= 0) {
            report.lights.push_back(describeLight(lit.lights[s.sceneLight]));
            masks.push_back(lightMask(lit.lights[s.sceneLight], gbuffer));
        }
    report.pageScale = pageScale(w);
    if (!truth.visibility.empty())
        report.referenceVisibilityPng =
            encodePng(reduceImage(visibilityImage(w, h, truth.visibility[0]), report.pageScale));
    // The reference's files at the top level, with how far each pixel's occluder is.
    writeViewFiles(out, gbuffer, truth.visibility, args.format, truth.transmittance);
    for (size_t l = 0; l < truth.occluderDistance.size(); ++l)
        writeFloatImage(out, l == 0 ? "occluder" : fmt::format("occluder_{}", l), args.format, w, h,
                        1, truth.occluderDistance[l]);
    std::vector<PathRow> shimmer;
    if (!args.cameraPath.empty()) {
        std::vector<std::string> names;
        for (const TechniqueRow& row : rows)
            names.push_back(row.name);
        shimmer = measurePathShimmer(uploaded, scene, rowOptions, names, path, args.pathFrames,
                                     args.reference);
        report.cameraPath = args.cameraPath;
        report.pathFrames = args.pathFrames;
    }
    std::vector<TimelineRow> measured;
    if (timeline) {
        std::vector<std::string> names;
        std::vector<BlurReach> blur;
        for (size_t r = 0; r < rows.size(); ++r) {
            names.push_back(rows[r].name);
            blur.push_back(blurRadiusTexels(rowOptions[r]));
        }
        measured = runTimeline(renderer,
                               {.sceneSpec = args.scene,
                                .global = global,
                                .sceneOptions = args.sceneOptions,
                                .rowNames = names,
                                .rowOptions = rowOptions,
                                .blur = blur,
                                .reference = args.reference},
                               *timeline);
        for (size_t k = 0; k < timeline->frames; ++k)
            report.timelineTimes.push_back(timeline->at(k));
        out.write("timeline.json", bytesOf(timelineJson(*timeline, measured).dump(2) + "\n"));
        out.write("timeline.csv", bytesOf(timelineCsv(*timeline, measured)));
        std::printf("%-22s %12s %12s %12s %12s %10s %10s %14s   (timeline: %zu frames, %g..%g s)\n",
                    "technique", "mean RMSE", "max RMSE", "flicker", "as played", "pop-in",
                    "lag frames", "GPU ms moving", timeline->frames, timeline->start,
                    timeline->at(timeline->frames - 1));
        for (const TimelineRow& row : measured) {
            const nlohmann::json j = timelineJson(*timeline, {row})["rows"][row.name];
            std::printf("%-22s %12.5f %12.5f %12.6f %12.6f %10.5f %10zu %14.3f\n", row.name.c_str(),
                        j["rmse_over_time"]["mean"].get<double>(),
                        j["rmse_over_time"]["max"].get<double>(), row.flicker, row.movingFlicker,
                        row.lag.popIn, row.lag.lagFrames,
                        j["gpu_ms_moving_over_time"]["mean"].get<double>());
        }
    }

    // One view for every row: its measure once, not a ray hierarchy per row.
    const nlohmann::json view = viewJson(scene, scene.camera(args.options.camera));
    for (size_t r = 0; r < rows.size(); ++r) {
        const RenderResult& result = results[r];
        ReportRow row{.name = rows[r].name,
                      .technique = std::string(techniqueName(rows[r].technique)),
                      .metrics = metricsAgainstTruth(lit, result, truth.visibility, masks,
                                                     blurRadiusTexels(rowOptions[r]),
                                                     truth.occluderDistance),
                      .modelsLightSize = shadows::moduleOf(rows[r].technique).modelsLightSize,
                      .shimmer = shimmer.empty() ? NAN : shimmer[r].shimmer,
                      .pathPagesRendered =
                          shimmer.empty() ? std::vector<uint32_t>{} : shimmer[r].pagesRendered,
                      .pathPagesResident =
                          shimmer.empty() ? std::vector<uint32_t>{} : shimmer[r].pagesResident};
        for (const auto& [key, value] : rows[r].sets)
            row.parameters.emplace_back(key, value);
        row.rmsePerChannel = firstLightRmsePerChannel(result, truth.transmittance, masks);
        if (!measured.empty()) {
            row.rmseOverTime = measured[r].rmse;
            row.gpuMsOverTime = measured[r].gpuMs;
            row.movingRmseOverTime = measured[r].movingRmse;
            row.movingGpuMsOverTime = measured[r].movingGpuMs;
            row.flicker = measured[r].flicker;
            row.movingFlicker = measured[r].movingFlicker;
            row.popIn = measured[r].lag.popIn;
            row.lagFrames = measured[r].lag.lagFrames;
        }
        row.gpuMs = result.passes;
        // Full-size files beside the report, the page's images reduced (page_image.h).
        const std::string prefix = filePrefix(rows[r].name);
        const uint32_t scale = report.pageScale;
        const RgbaImage litImage{w, h, result.image};
        row.imageFile = prefix + ".image.png";
        const std::vector<uint8_t> litPng = encodePng(litImage);
        out.write(row.imageFile, litPng);
        row.imagePng = scale == 1 ? litPng : encodePng(reduceImage(litImage, scale));
        if (!truth.visibility.empty()) {
            row.visibilityPng =
                encodePng(reduceImage(visibilityImage(w, h, result.visibility[0]), scale));
            const RgbaImage heatmap =
                signedErrorHeatmap(w, h, result.visibility[0], truth.visibility[0], masks[0]);
            row.heatmapFile = prefix + ".heatmap.png";
            const std::vector<uint8_t> heatmapPng = encodePng(heatmap);
            out.write(row.heatmapFile, heatmapPng);
            row.heatmapPng = scale == 1 ? heatmapPng : encodePng(reduceImage(heatmap, scale));
        }
        for (size_t l = 0; l < result.visibility.size(); ++l) {
            const std::string light = l == 0 ? "" : fmt::format("_{}", l);
            if (l < result.transmittance.size()) // the translucent layer's light per channel
                writeFloatImage(out, prefix + ".visibility" + light, args.format, w, h, 3,
                                result.transmittance[l]);
            else
                writeFloatImage(out, prefix + ".visibility" + light, args.format, w, h, 1,
                                result.visibility[l]);
            if (l < truth.visibility.size()) // the heat map's data: this row minus the truth
                writeFloatImage(out, prefix + ".difference" + light, args.format, w, h, 1,
                                signedError(result.visibility[l], truth.visibility[l]));
        }
        const RenderRun run{.sceneSpec = args.scene,
                            .scene = scene,
                            .options = rowOptions[r],
                            .device = device,
                            .result = result,
                            .floatExtension = namingExtension(args.format),
                            .view = &view};
        out.write(prefix + ".stats.json", bytesOf(renderStats(run).dump(2) + "\n"));
        report.rows.push_back(std::move(row));
    }
    for (ReportRow& row : skipped)
        report.rows.push_back(std::move(row));
    out.write("metrics.json", bytesOf(metricsJson(report).dump(2) + "\n"));
    out.write("report.html", bytesOf(renderHtmlReport(report)));
    if (renderer.validationErrors() > 0)
        throw std::runtime_error(fmt::format("vulkan validation: {} error(s); no output written",
                                             renderer.validationErrors()));
    out.commit();

    std::printf("%-22s %9s %9s %11s %8s %8s %8s %8s %8s %10s%s\n", "technique", "RMSE", "MAE",
                "misclass.%", "acne%", "leak%", "acne>b%", "leak>b%", "leak@c%", "GPU ms",
                shimmer.empty() ? "" : "    shimmer");
    for (const ReportRow& row : report.rows) {
        if (!row.skipped.empty()) {
            std::printf("%-22s skipped: %s\n", row.name.c_str(), row.skipped.c_str());
            continue;
        }
        double total = 0;
        for (const PassTime& p : row.gpuMs)
            total += p.medianMs;
        std::printf("%-22s %9.5f %9.5f %11.3f %8.3f %8.3f %8.3f %8.3f %8.2f %10.3f",
                    row.name.c_str(), row.metrics.rmse, row.metrics.mae,
                    100 * row.metrics.misclassified, 100 * row.metrics.acne, 100 * row.metrics.leak,
                    100 * row.metrics.acneBeyondBlur, 100 * row.metrics.leakBeyondBlur,
                    100 * row.metrics.leakNearContact, total);
        if (!shimmer.empty())
            std::printf(" %10.5f", row.shimmer);
        std::printf("\n");
    }
    std::printf("ground truth: %.3g rays in %.1f s (%.2f Mrays/s)\n", double(truth.rays),
                truth.seconds, report.raysPerSecond * 1e-6);
    std::printf("report: %s\n", (out.path() / "report.html").c_str());
    return 0;
}

} // namespace

Action addCompareCommand(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "render each technique and the ground truth; write report.html and metrics.json");
    addSceneArgument(*cmd, args->scene);
    cmd->add_option("-o,--output", args->output, "output directory, created if missing")
        ->type_name("DIR")
        ->required();
    cmd->add_option("--techniques", args->techniques,
                    "the rows: technique names (all their variants), variants such as "
                    "`pcf[box7]`, either followed by `+LAYER` to run with that layer "
                    "(`pcf[box3]+contact`); default: every row, then each layer's own rows "
                    "with it. `--set`s apply to every row")
        ->type_name("a,b,...");
    addViewOptions(*cmd, args->options, args->sceneOptions);
    addTechniqueOptions(*cmd, args->options, args->sets);
    addReferenceOptions(*cmd, args->reference);
    addTruthCacheOption(*cmd, args->truthCache);
    addFormatOption(*cmd, args->format);
    cmd->add_option("--camera-path", args->cameraPath,
                    "measure shimmer along a path: `dolly` (the camera forward by 0.37 of a "
                    "shadow-map texel a frame), `orbit` (0.1 degrees a frame about its target), "
                    "`sun` (every directional light turns 0.05 degrees a frame)")
        ->type_name("PATH");
    cmd->add_option("--timeline", args->timeline,
                    "an animated scene over time: each frame from START to END seconds, STEP "
                    "apart, posed, rendered by every row (at rest and in motion) and traced; "
                    "per-frame metrics and each row's flicker, lag and pop-in in timeline.json "
                    "and timeline.csv (the other outputs are START's)")
        ->type_name("START:END:STEP")
        ->check(nonEmptyValue("a timeline START:END:STEP"))
        ->excludes("--time")
        ->excludes("--camera-path");
    cmd->add_option("--path-frames", args->pathFrames, "frames along --camera-path, 2..64")
        ->type_name("N")
        ->check(CLI::Range(2, 64))
        ->capture_default_str();
    return [args, &global] { return runCompare(*args, global); };
}

} // namespace penumbra::cli
