// Virtual pages decided three ways on the same frames (docs/techniques.md, "Pages decided on the
// device"): the host cache (PageCache, withCoarserPages, pageTable: what a frame does today), its
// restatement as passes on the CPU (decidePages) and those passes on the device
// (PageDecisionPasses: GPU time from timestamps, and wall time with the submit). The default
// map's levels for a sun, a spot and a bulb over an 800-unit field (about 355,000 table entries),
// a pool of 4096 pages, a view asking for about 800 pages that moves a little every frame.
#include "core/page_decisions.h"
#include "penumbra/renderer.h"
#include "render/page_decision_passes.h"
#include "vk/timestamps.h"

#include <benchmark/benchmark.h>

#include <map>
#include <random>
#include <string>

namespace {

using namespace penumbra;

struct Frames {
    std::vector<VirtualLevel> levels;
    std::vector<std::vector<uint32_t>> requests; // a few frames' worth, cycled
};

Frames makeFrames() {
    const VirtualSettings s{};
    const Bounds field{.min = {-400, 0, -400}, .max = {400, 30, 400}};
    const Light lights[] = {{.type = LightType::Directional,
                             .direction = glm::normalize(glm::vec3(0.55f, -0.45f, -0.35f))},
                            {.type = LightType::Spot,
                             .position = {3, 40, 2},
                             .direction = glm::normalize(glm::vec3(-0.1f, -1.0f, 0.05f)),
                             .outerConeAngle = 0.6f},
                            {.type = LightType::Point, .position = {1, 12, -3}}};
    Frames f;
    uint32_t offset = 0;
    for (uint32_t i = 0; i < 3; ++i)
        for (const VirtualLevel& l :
             virtualLevels(lights[i], i, field, {0, 2, 0}, s, {.nearestSurface = 5.0f}, offset))
            f.levels.push_back(l);
    // Per frame, a 6x6 patch in each of the finest four levels of every light and face, shifted
    // by a page now and then: about 800 pages with their chains.
    std::mt19937 rng(1);
    std::uniform_int_distribution<int> shift(0, 1);
    glm::ivec2 at{40, 40};
    for (int frame = 0; frame < 16; ++frame) {
        at += glm::ivec2(shift(rng), shift(rng));
        std::vector<uint32_t> r(offset, 0u);
        for (const VirtualLevel& l : f.levels) {
            if (l.level >= 4)
                continue;
            const int n = int(l.pagesPerSide);
            for (int y = at.y; y < at.y + 6; ++y)
                for (int x = at.x; x < at.x + 6; ++x)
                    r[l.tableOffset + uint32_t(y % n) * l.pagesPerSide + uint32_t(x % n)] = 1u;
        }
        f.requests.push_back(std::move(r));
    }
    return f;
}

void PageDecisionsHostCache(benchmark::State& state) {
    const Frames f = makeFrames();
    PageCache cache(VirtualSettings{}.poolPages());
    const auto entries = static_cast<uint32_t>(f.requests[0].size());
    uint32_t frame = 0;
    for (auto _ : state) {
        const std::vector<uint32_t>& r = f.requests[frame % f.requests.size()];
        cache.update(withCoarserPages(requestedPages(f.levels, r.data()), f.levels), ++frame);
        benchmark::DoNotOptimize(pageTable(f.levels, cache, entries));
    }
    state.counters["entries"] = entries;
}
BENCHMARK(PageDecisionsHostCache)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void PageDecisionsReference(benchmark::State& state) {
    const Frames f = makeFrames();
    std::vector<PageOwner> owners(VirtualSettings{}.poolPages());
    uint32_t frame = 0;
    for (auto _ : state) {
        const std::vector<uint32_t>& r = f.requests[frame % f.requests.size()];
        benchmark::DoNotOptimize(
            decidePages(owners, {.levels = &f.levels, .requests = r, .frame = ++frame}));
    }
}
BENCHMARK(PageDecisionsReference)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void PageDecisionsDevice(benchmark::State& state) {
    Renderer renderer(DeviceOptions{});
    const vk::Context& ctx = renderer.context();
    const Frames f = makeFrames();
    render::PageDecisionPasses passes(ctx, VirtualSettings{}.poolPages());
    vk::GpuTimer timer(ctx, PAGES_PASS_TABLE + 1);
    uint32_t frame = 0;
    std::map<std::string, double> sums;
    for (auto _ : state) {
        const std::vector<uint32_t>& r = f.requests[frame % f.requests.size()];
        passes.prepare({.levels = &f.levels, .requests = r, .frame = ++frame});
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            passes.record(cmd, VK_NULL_HANDLE, &timer);
        });
        for (const PassTime& p : timer.read()) {
            sums[p.pass + "_ms"] += p.medianMs;
            sums["gpu_ms"] += p.medianMs;
        }
    }
    for (const auto& [pass, ms] : sums)
        state.counters[pass] = ms / static_cast<double>(state.iterations());
    state.SetLabel(renderer.device().name);
}
BENCHMARK(PageDecisionsDevice)->Unit(benchmark::kMillisecond)->MinTime(2.0);

} // namespace
BENCHMARK_MAIN();
