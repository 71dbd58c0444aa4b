#pragma once
// `--truth-cache DIR` of compare and tune: the truth of a view from the shared cache that sweep
// fills too (sweep/truth_cache.h), traced and stored on a miss.
#include <CLI/CLI.hpp>

#include "penumbra/reference.h"
#include "penumbra/renderer.h"

#include <string>

namespace penumbra::cli {

void addTruthCacheOption(CLI::App& cmd, std::string& dir);

// computeReference(lit, gbuffer, options), through the cache in `dir` unless it is empty; the
// key is the view `lit` and `camera` make at the G-buffer's size with options.samples.
ReferenceResult truthThroughCache(const std::string& dir, const Scene& lit,
                                  const std::string& camera, const RenderResult& gbuffer,
                                  const ReferenceOptions& options);

} // namespace penumbra::cli
