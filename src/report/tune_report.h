#pragma once
// `penumbra tune`: bias settings swept against the ray-traced truth. Each candidate's error
// beyond the technique's blur (report/metrics.h), the front of settings no other beats on both
// acne and leak, the recommendation, tune.json and a self-contained tune.html.
#include "penumbra/renderer.h"
#include "report/metrics.h"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct TuneCandidate {
    std::vector<std::pair<std::string, std::string>> sets; // swept key, value as given
    std::string setLine;    // the `--set` options that differ from the defaults ("": none)
    ErrorMetrics metrics;   // pooled over the views
    double gpuMs = 0.0;     // median frame, the first view's
    bool isDefault = false; // every swept key at the technique's settings without --sweep
    bool onFront = false;   // no other candidate has both less acne and less leak beyond blur
    // What the recommendation minimises: acne + leak beyond blur (fractions).
    double objective() const { return metrics.acneBeyondBlur + metrics.leakBeyondBlur; }
};

struct TuneData {
    std::string scene, technique, device;
    std::vector<std::string> views;    // camera names ("" : the scene's default view)
    std::vector<std::string> baseSets; // --set given, applied to every candidate
    uint32_t width = 0, height = 0, shadowMapSize = 0, samples = 0;
    std::vector<bool> lightSized; // per shadow-casting light: has a size (truth_notes.h)
    double truthSeconds = 0.0;
    std::vector<TuneCandidate> candidates;
    size_t recommended = 0, defaults = 0; // indices into candidates
};

// Sets onFront on the candidates no other dominates (less or equal in both acne and leak beyond
// blur, less in one).
void markFront(std::vector<TuneCandidate>& candidates);
// Acne + leak beyond blur closer than this (a hundredth of a percent of the pixels) is a tie.
inline constexpr double kTuneTolerance = 1e-4;

// The recommendation: among the candidates whose objective is within kTuneTolerance of the
// least and not above the defaults' (the candidate with isDefault), the one with the lowest
// RMSE (ties: fewer misclassified pixels away from edges, then the earlier): acne and leak
// first, without a larger offset's detached contact shadows when it buys next to nothing.
size_t recommend(const std::vector<TuneCandidate>& candidates);

nlohmann::json tuneJson(const TuneData& data);
std::string tuneHtml(const TuneData& data);

} // namespace penumbra
