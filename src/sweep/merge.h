#pragma once
// `penumbra merge`: a sweep's task records summed up per scene and over the corpus. Each
// technique setting's error (every metric, with its 95% interval from the truth bootstrap)
// against its GPU cost, the Pareto front of RMSE against shadow time (every pass but the G-buffer),
// and ranks. Error figures depend only on the records' error numbers, taken in id order: the same
// tasks give the same figures however they were sharded.
#include "sweep/records.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace penumbra::sweep {

struct Estimate {
    double value = NAN, lo = NAN, hi = NAN; // mean over the views, 95% interval
    int rank = 0;                           // 1 = least error among the group's settings
};

struct SettingSummary {
    std::string setting, technique;
    size_t views = 0;                          // views it ran on
    std::map<std::string, Estimate> metrics;   // kMetricFields' names
    double visibilityMs = NAN, shadowMs = NAN; // means over the views (records.h)
    std::vector<std::string> devices;          // that measured it, sorted
    bool onFront = false; // no other setting has both less RMSE and less shadow time
};

struct GroupSummary {
    std::string name;                     // a scene as the plan names it, or "corpus"
    std::vector<SettingSummary> settings; // sorted by setting name
};

struct MergeResult {
    std::vector<GroupSummary> groups; // the corpus first, then the scenes by name
    std::vector<TaskRecord> failed;
    size_t tasks = 0;
};

// Takes the records in id order, whatever order they come in.
MergeResult mergeRecords(std::vector<TaskRecord> records);
nlohmann::json mergeJson(const MergeResult& merged);

} // namespace penumbra::sweep
