#pragma once
// report.html and metrics.json of `penumbra compare` (docs/cli.md): every technique's error
// against the ray-traced reference, its GPU cost, and its images, in one offline file.
#include "penumbra/renderer.h"
#include "report/metrics.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

// Text made safe inside HTML elements and quoted attributes.
std::string escapeHtml(std::string_view text);

// One technique's results, as shown in one table row and one figure of the report.
struct ReportRow {
    std::string name;                                            // e.g. "hard", "pcf[box7]"
    std::string technique;                                       // CLI technique name
    std::vector<std::pair<std::string, std::string>> parameters; // non-default, for display
    ErrorMetrics metrics;
    std::vector<PassTime> gpuMs; // per pass its median ms and cost group, in frame order
    std::vector<uint8_t> imagePng, visibilityPng, heatmapPng; // at page size (page_image.h)
    std::string imageFile, heatmapFile; // the full-size files beside report.html; may be empty
    std::string skipped;          // why it did not run (the device cannot hold it); empty: it ran
    bool modelsLightSize = false; // its penumbra follows the light's size (pcss, vssm, ...)
    double shimmer = NAN;         // mean frame-to-frame change along the camera path; NaN: no path
    // Virtual maps along the path: pages each frame rendered and those resident (else empty).
    std::vector<uint32_t> pathPagesRendered, pathPagesResident;
    // compare --timeline: per frame its RMSE and total GPU ms at rest and in motion, its flicker,
    // pop-in and longest lag (else empty, NaN, 0).
    std::vector<double> rmseOverTime, gpuMsOverTime;
    std::vector<double> movingRmseOverTime, movingGpuMsOverTime;
    double flicker = NAN, movingFlicker = NAN; // at rest, and as played (in motion)
    double popIn = NAN;
    size_t lagFrames = 0;
    // Where the truth is coloured (translucent casters): the first light's RMSE per channel (red,
    // green, blue), the row's light per channel against the truth's (a grey row's visibility in
    // every channel), over the pixels its metrics count; empty otherwise.
    std::vector<double> rmsePerChannel;
};

// Everything a report shows: the run's context, the reference, and one row per technique.
struct ReportData {
    std::string scene, device, driver; // e.g. "builtin:showcase", "llvmpipe (...)"
    uint32_t width = 0, height = 0, shadowMapSize = 0;
    uint32_t pageScale = 1; // the images are shown reduced by this factor (pageScale())
    uint32_t samples = 0;   // reference rays per pixel towards a light with a size
    double referenceSeconds = 0, raysPerSecond = 0;
    std::vector<std::string> lights; // one description per shadow-casting light
    // Per light: whether it has a size (the truth traces `samples` rays towards it, else one
    // exact ray: truth_notes.h); empty: every light has one.
    std::vector<bool> lightSized;
    std::string cameraPath; // "dolly", "orbit", "sun"; empty: no shimmer measured
    uint32_t pathFrames = 0;
    std::vector<double> timelineTimes; // compare --timeline's frames, in seconds; else empty
    std::vector<uint8_t> referenceVisibilityPng;
    std::vector<ReportRow> rows;
};

// A self-contained HTML5 page (inline CSS, SVG and one script, PNGs as data: URIs, no network
// references) that reads at 1000 pixels and wider; every string from data is HTML-escaped.
std::string renderHtmlReport(const ReportData& data);

// metrics.json: {"reference": {...}, "techniques": {"<row name>": {..., "gpu_ms": {...}}}}; a
// skipped row is {"skipped": "<why>"}.
// Row names are keys, so duplicates are a programmer error.
nlohmann::json metricsJson(const ReportData& data);
// One row's entry of metrics.json (without the camera path's keys): the Python module's metrics().
nlohmann::json metricsRowJson(const ReportRow& row);
// {"shadow_maps", "per_pixel", "frame"}: the passes' medians summed by the cost group each was
// declared with (every group present, 0 without a pass).
nlohmann::json gpuMsByCost(const std::vector<PassTime>& passes);
// Each fraction's pixels: {"acne": {"pixels": numerator, "of": denominator}, ...}.
nlohmann::json metricCountsJson(const ErrorMetrics& m);
// The note a view with fewer than kFewJudgedPixels fully lit or fully shadowed pixels away from
// edges gets (empty when it has enough), from any ran row's metrics.
std::string fewPixelsNote(const ErrorMetrics& m);

} // namespace penumbra
