#pragma once
// Running a shard of a sweep: its tasks view by view (one scene upload and one truth per view),
// each task's record written as soon as it is done, tasks with a record skipped.
#include "cli_options.h"
#include "sweep/plan.h"
#include "sweep/tasks.h"

#include <filesystem>
#include <span>

namespace penumbra::cli {

struct SweepRunStats {
    size_t ran = 0, skipped = 0, failed = 0, truthsComputed = 0, truthsCached = 0;
};

SweepRunStats runSweepTasks(const sweep::Plan& plan, const sweep::SweepTasks& tasks,
                            std::span<const size_t> mine, const std::filesystem::path& output,
                            const std::filesystem::path& truthCache, const GlobalOptions& global);

} // namespace penumbra::cli
