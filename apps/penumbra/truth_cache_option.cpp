// --truth-cache (truth_cache_option.h).
#include "truth_cache_option.h"

#include "cli_options.h"
#include "sweep/truth_cache.h"

#include <cstdio>
#include <optional>

namespace penumbra::cli {

void addTruthCacheOption(CLI::App& cmd, std::string& dir) {
    cmd.add_option(
           "--truth-cache", dir,
           "compare, tune: keep the ground truth in this directory and reuse it for the same view "
           "(scene content, lights, camera, size, samples); sweep's DIR/truth is one")
        ->group(kTruthGroup)
        ->type_name("DIR");
}

ReferenceResult truthThroughCache(const std::string& dir, const Scene& lit,
                                  const std::string& camera, const RenderResult& gbuffer,
                                  const ReferenceOptions& options) {
    if (dir.empty())
        return computeReference(lit, gbuffer, options);
    const sweep::TruthCache cache(dir);
    bool computed = false;
    ReferenceResult truth = sweep::cachedTruth(
        &cache, sweep::truthKey(lit, camera, gbuffer.width, gbuffer.height, options.samples),
        [&] { return computeReference(lit, gbuffer, options); }, &computed);
    if (!computed)
        std::fprintf(stderr, "penumbra: ground truth from the cache in %s\n", dir.c_str());
    return truth;
}

} // namespace penumbra::cli
