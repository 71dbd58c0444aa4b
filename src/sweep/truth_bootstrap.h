#pragma once
// Confidence intervals on the error metrics from the truth's finite samples. The truth of a
// pixel lit by a light with a size is a Monte-Carlo estimate t = k / n of n rays; k is binomial
// (n, p). A parametric bootstrap redraws every pixel's truth as Binomial(n, t) / n, recomputes
// every metric against the redrawn truth, and reads the metric's 95% interval off how the
// replicates spread around the measured value (the basic bootstrap; docs/sweep.md derives it).
// A light without a size has an exact truth (one ray): its pixels are never redrawn.
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "report/metrics.h"

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

namespace penumbra::sweep {

// The metrics merge reports, by the names merge.json and task records use.
struct MetricField {
    std::string_view name;
    double ErrorMetrics::*member;
};
inline constexpr MetricField kMetricFields[] = {
    {"rmse", &ErrorMetrics::rmse},
    {"mae", &ErrorMetrics::mae},
    {"misclassified", &ErrorMetrics::misclassified},
    {"acne", &ErrorMetrics::acne},
    {"leak", &ErrorMetrics::leak},
    {"acne_beyond_blur", &ErrorMetrics::acneBeyondBlur},
    {"leak_beyond_blur", &ErrorMetrics::leakBeyondBlur},
    {"leak_near_contact", &ErrorMetrics::leakNearContact}};

inline constexpr uint32_t kBootstrapReplicates = 64;

// Rays per pixel of each visibility layer of `result`: 1 for lights without a size (exact),
// else `samples`.
std::vector<uint32_t> truthSamplesPerLayer(const Scene& lit, const RenderResult& result,
                                           uint32_t samples);

// Replicate `index` of the truths drawn as described above, from a generator seeded by `seed`
// and `index` alone: the same draws however many replicates are drawn, in whatever order.
ReferenceResult bootstrapTruth(const ReferenceResult& truth,
                               std::span<const uint32_t> samplesPerLayer, uint64_t seed,
                               uint32_t index);
// Replicates 0 .. replicates-1.
std::vector<ReferenceResult> bootstrapTruths(const ReferenceResult& truth,
                                             std::span<const uint32_t> samplesPerLayer,
                                             uint32_t replicates, uint64_t seed);
// `metrics` of each replicate, replicate i at index i, computed on the machine's cores (each
// worker holds one redrawn truth at a time).
std::vector<ErrorMetrics>
bootstrapMetrics(const ReferenceResult& truth, std::span<const uint32_t> samplesPerLayer,
                 uint32_t replicates, uint64_t seed,
                 const std::function<ErrorMetrics(const ReferenceResult&)>& metrics);

// The basic bootstrap's 95% interval: the redrawn truths stand to the measured one as the
// measured one stands to the exact truth, so with q2.5 and q97.5 the replicates' percentiles,
// the metric lies in [2 estimate - q97.5, 2 estimate - q2.5] (clamped to [0, 1], where every
// metric lies). Non-finite replicates are left out; none left (or a non-finite estimate):
// {NaN, NaN}.
struct Interval {
    double lo = 0, hi = 0;
};
Interval basicInterval(double estimate, std::vector<double> replicates);

} // namespace penumbra::sweep
