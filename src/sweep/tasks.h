#pragma once
// A plan's tasks (one view and one technique setting each) with ids that depend only on what
// the task computes, and their division among the shards of a job array.
#include "sweep/plan.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::sweep {

// 64-bit FNV-1a as 16 hex digits: names of results and truth files, the same on every machine.
std::string hashHex(std::string_view bytes);

// What a view is made of: a scene, a light (kind and size), a camera, a time (with the plan's
// `times`), and the plan's image size and truth samples.
struct SweepView {
    PlanScene scene;
    PlanLight light;
    std::string camera;
    std::optional<double> time; // none: at rest
    std::string animation;      // the plan's, with a time
    std::string id; // hash of the description (the scene as the plan names it, not its path)
};

struct SweepTask {
    size_t view = 0; // index into the views
    PlanSetting setting;
    std::string id; // hash of the view's description, the setting and the render sizes
};

struct SweepTasks {
    std::vector<SweepView> views; // sorted by id
    std::vector<SweepTask> tasks; // sorted by (view id, task id): the order of the plan's
                                  // entries does not matter
};

SweepTasks expandTasks(const Plan& plan);

// The tasks shard `index` of `count` does. Every task falls to exactly one shard; the tasks of a
// view stay together (one truth per view) unless there are fewer views than shards, when they
// are dealt out one by one. Views go, largest first, to the shard with the fewest tasks so far.
std::vector<size_t> shardTasks(const SweepTasks& tasks, uint32_t index, uint32_t count);

} // namespace penumbra::sweep
