// The truth bootstrap (truth_bootstrap.h).
#include "sweep/truth_bootstrap.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <thread>

namespace penumbra::sweep {

std::vector<uint32_t> truthSamplesPerLayer(const Scene& lit, const RenderResult& result,
                                           uint32_t samples) {
    std::vector<uint32_t> out(result.visibility.size(), samples);
    for (const LightShadow& s : result.lights) {
        if (s.visibilityIndex < 0)
            continue;
        const Light& l = lit.lights[s.sceneLight];
        const bool exact =
            l.type == LightType::Directional ? l.angularDiameter <= 0.0f : l.radius <= 0.0f;
        if (exact)
            out[size_t(s.visibilityIndex)] = 1;
    }
    return out;
}

ReferenceResult bootstrapTruth(const ReferenceResult& truth,
                               std::span<const uint32_t> samplesPerLayer, uint64_t seed,
                               uint32_t index) {
    std::mt19937_64 random(seed ^ (0x9e3779b97f4a7c15ull * (uint64_t(index) + 1)));
    ReferenceResult redrawn = truth;
    for (size_t l = 0; l < redrawn.visibility.size(); ++l) {
        const uint32_t n = l < samplesPerLayer.size() ? samplesPerLayer[l] : 1;
        if (n <= 1)
            continue; // exact
        for (float& t : redrawn.visibility[l]) {
            if (!std::isfinite(t) || t <= 0.0f || t >= 1.0f)
                continue; // background, or no variance to draw from
            std::binomial_distribution<uint32_t> draw(n, double(t));
            t = float(double(draw(random)) / n);
        }
    }
    return redrawn;
}

std::vector<ReferenceResult> bootstrapTruths(const ReferenceResult& truth,
                                             std::span<const uint32_t> samplesPerLayer,
                                             uint32_t replicates, uint64_t seed) {
    std::vector<ReferenceResult> out;
    for (uint32_t r = 0; r < replicates; ++r)
        out.push_back(bootstrapTruth(truth, samplesPerLayer, seed, r));
    return out;
}

std::vector<ErrorMetrics>
bootstrapMetrics(const ReferenceResult& truth, std::span<const uint32_t> samplesPerLayer,
                 uint32_t replicates, uint64_t seed,
                 const std::function<ErrorMetrics(const ReferenceResult&)>& metrics) {
    std::vector<ErrorMetrics> out(replicates);
    std::atomic<uint32_t> next{0};
    auto work = [&] {
        for (uint32_t r = next++; r < replicates; r = next++)
            out[r] = metrics(bootstrapTruth(truth, samplesPerLayer, seed, r));
    };
    const uint32_t threads =
        std::clamp<uint32_t>(std::thread::hardware_concurrency(), 1, std::max(replicates, 1u));
    std::vector<std::thread> workers;
    for (uint32_t t = 1; t < threads; ++t)
        workers.emplace_back(work);
    work();
    for (std::thread& w : workers)
        w.join();
    return out;
}

Interval basicInterval(double estimate, std::vector<double> replicates) {
    std::erase_if(replicates, [](double v) { return !std::isfinite(v); });
    if (replicates.empty() || !std::isfinite(estimate))
        return {NAN, NAN};
    std::sort(replicates.begin(), replicates.end());
    const double last = double(replicates.size() - 1);
    const double low = replicates[size_t(std::floor(0.025 * last))];
    const double high = replicates[size_t(std::ceil(0.975 * last))];
    return {std::clamp(2 * estimate - high, 0.0, 1.0), std::clamp(2 * estimate - low, 0.0, 1.0)};
}

} // namespace penumbra::sweep
