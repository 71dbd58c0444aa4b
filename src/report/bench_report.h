#pragma once
// `penumbra bench`: per-pass GPU time statistics of each run (a technique, with the values of
// the parameters swept), its JSON (docs/cli.md) and a self-contained bench.html with the cost
// of each pass against each swept parameter.
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct PassStats {
    std::string pass;
    double median = 0, p10 = 0, p90 = 0; // ms over the timed frames
};

// Linear-interpolation percentiles of the frames' times (empty: zeros).
PassStats passStats(std::string pass, std::vector<double> frameMs);

struct BenchRun {
    Technique technique = kDefaultTechnique;
    std::vector<std::pair<std::string, std::string>> swept; // key, value as given
    ParameterValues parameters;                             // every value in effect
    std::vector<PassStats> passes;                          // in frame order
    PassStats total;                                        // of each frame's sum
    uint64_t shadowMapBytes = 0, screenBytes = 0, fieldBytes = 0;
    TransientMemory transient; // measured: the transient images, alone and sharing memory
    double fieldBuildMs = 0;   // sdf: the field's one-off build (GPU)
    std::optional<VirtualMapInfo> virtualMaps; // virtual.enabled: its pages and pool
    std::string skipped; // why it did not run (the device cannot hold it); empty: it ran
    uint64_t memoryBytes() const { return shadowMapBytes + screenBytes + fieldBytes; }
};

struct BenchData {
    std::string scene;
    DeviceInfo device;
    uint32_t width = 0, height = 0, shadowMapSize = 0, frames = 0;
    std::vector<std::string> sweepKeys;
    std::vector<BenchRun> runs;
};

// A run's statistics from its render: per pass, and of the frame's total.
void measureRun(BenchRun& run, const RenderResult& result);
// The device memory a render of these options holds: the technique's maps for every shadow view,
// the screen-sized targets, the distance field.
void estimateMemory(BenchRun& run, const RenderOptions& options, const RenderResult& result);

nlohmann::json benchJson(const BenchData& data);
std::string benchHtml(const BenchData& data);

} // namespace penumbra
