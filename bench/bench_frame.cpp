// The whole frame on builtin:dense (about 98k triangles, a spot light) at 1280x720 with a 2048
// shadow map and a 3x3 PCF: issue 15's raster target, kept here so that a change that slows
// the shadow or G-buffer passes shows. Wall time per frame (readback included), and each pass's
// GPU time (timestamps, median of the frame's passes) as counters.
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <string>

namespace {

void FrameDensePcf3(benchmark::State& state) {
    penumbra::Renderer renderer(penumbra::DeviceOptions{});
    const penumbra::Scene scene = penumbra::loadScene("builtin:dense");
    penumbra::SceneRenderer frames(renderer, scene);
    penumbra::RenderOptions options{.width = 1280, .height = 720, .frames = 1};
    options.technique = penumbra::Technique::Pcf;
    options.parameters.assign("pcf.size=3");
    frames.render(options); // warm-up: pipelines, targets
    std::map<std::string, double> sums;
    for (auto _ : state) {
        const penumbra::RenderResult r = frames.render(options);
        for (const penumbra::PassTime& p : r.passes)
            sums[p.pass] += p.medianMs;
    }
    for (const auto& [pass, ms] : sums)
        state.counters[pass + "_ms"] = ms / static_cast<double>(state.iterations());
    state.counters["triangles"] = static_cast<double>(scene.triangleCount());
}
BENCHMARK(FrameDensePcf3)->Unit(benchmark::kMillisecond)->MinTime(2.0);

} // namespace
BENCHMARK_MAIN();
