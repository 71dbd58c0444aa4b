#pragma once
// One task's result as a file, DIR/tasks/<id>.json, written all-or-nothing: what merge reads,
// and what tells a resumed run that the task is done. A task that failed has a record too.
#include "penumbra/renderer.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::sweep {

struct TaskRecord {
    std::string id, view, scene, light, camera, setting, technique;
    std::optional<double> time; // the view's time (none: at rest)
    std::vector<std::pair<std::string, std::string>> parameters;
    bool failed = false;
    std::string error; // why it failed
    std::string device;
    std::string truthKey;
    bool truthComputed = false; // this task traced the truth (else the cache had it)
    uint32_t width = 0, height = 0, samples = 0;
    std::map<std::string, double> metrics;                 // kMetricFields' names
    std::map<std::string, std::vector<double>> replicates; // the bootstrap's, per metric
    double visibilityMs = NAN; // the per-pixel passes (CostGroup::PerPixel), median frame
    double shadowMs = NAN;     // every pass but the frame's (the G-buffer): the technique's cost
    std::vector<std::pair<std::string, double>> passes;
};

nlohmann::json taskRecordJson(const TaskRecord& record);
// InputError(file, ...) when the JSON is not a task record.
TaskRecord taskRecordFrom(const nlohmann::json& json, const std::string& file);

std::filesystem::path taskRecordPath(const std::filesystem::path& dir, const std::string& id);
// Atomic: a temporary file in the same directory, then a rename.
void writeTaskRecord(const std::filesystem::path& dir, const TaskRecord& record);
// Every DIR/tasks/*.json, sorted by id; InputError(file, ...) for one that does not parse.
std::vector<TaskRecord> readTaskRecords(const std::filesystem::path& dir);

// The per-pixel cost and the whole shadow cost from a render's passes, by the cost group each
// pass declares.
void setCosts(TaskRecord& record, const std::vector<PassTime>& passes);

} // namespace penumbra::sweep
