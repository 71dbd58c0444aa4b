// Merging task records (merge.h).
#include "sweep/merge.h"

#include "report/report_plot.h"
#include "sweep/truth_bootstrap.h"

#include <algorithm>
#include <numeric>
#include <set>

namespace penumbra::sweep {
namespace {

// One setting's summary over `records` (all of that setting, in id order). The interval of a
// mean over views: the replicate-wise means (each view's bootstrap is independent), their
// percentiles.
SettingSummary summarize(const std::vector<const TaskRecord*>& records) {
    SettingSummary s{.setting = records.front()->setting,
                     .technique = records.front()->technique,
                     .views = records.size()};
    std::set<std::string> devices;
    double visibility = 0, shadow = 0;
    for (const TaskRecord* r : records) {
        devices.insert(r->device);
        visibility += r->visibilityMs;
        shadow += r->shadowMs;
    }
    s.visibilityMs = visibility / double(records.size());
    s.shadowMs = shadow / double(records.size());
    s.devices.assign(devices.begin(), devices.end());
    for (const MetricField& field : kMetricFields) {
        const std::string name(field.name);
        Estimate e{.value = 0};
        size_t replicates = SIZE_MAX;
        for (const TaskRecord* r : records) {
            const auto it = r->metrics.find(name);
            e.value += it == r->metrics.end() ? NAN : it->second;
            const auto rep = r->replicates.find(name);
            replicates = std::min(replicates, rep == r->replicates.end() ? 0 : rep->second.size());
        }
        e.value /= double(records.size());
        std::vector<double> means(replicates == SIZE_MAX ? 0 : replicates, 0.0);
        for (size_t k = 0; k < means.size(); ++k) {
            for (const TaskRecord* r : records)
                means[k] += r->replicates.at(name)[k];
            means[k] /= double(records.size());
        }
        const Interval ci = basicInterval(e.value, means);
        e.lo = ci.lo, e.hi = ci.hi;
        s.metrics[name] = e;
    }
    return s;
}

GroupSummary summarizeGroup(const std::string& name, const std::vector<const TaskRecord*>& all) {
    std::map<std::string, std::vector<const TaskRecord*>> bySetting;
    for (const TaskRecord* r : all)
        bySetting[r->setting].push_back(r);
    GroupSummary g{.name = name};
    for (const auto& [setting, records] : bySetting)
        g.settings.push_back(summarize(records));
    // Ranks per metric: 1 for the least; equal values share a rank; NaN ranks last (0).
    for (const MetricField& field : kMetricFields) {
        const std::string metric(field.name);
        for (SettingSummary& s : g.settings) {
            const double v = s.metrics[metric].value;
            if (!std::isfinite(v))
                continue;
            int rank = 1;
            for (const SettingSummary& other : g.settings) {
                const double o = other.metrics.at(metric).value;
                rank += std::isfinite(o) && o < v;
            }
            s.metrics[metric].rank = rank;
        }
    }
    std::vector<PlotPoint> points;
    for (const SettingSummary& s : g.settings)
        points.push_back(
            {.name = s.setting, .cost = s.shadowMs, .rmse = s.metrics.at("rmse").value});
    const std::vector<bool> front = paretoFront(points);
    for (size_t i = 0; i < g.settings.size(); ++i)
        g.settings[i].onFront = front[i];
    return g;
}

nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

} // namespace

MergeResult mergeRecords(std::vector<TaskRecord> records) {
    std::sort(records.begin(), records.end(),
              [](const TaskRecord& a, const TaskRecord& b) { return a.id < b.id; });
    MergeResult m{.tasks = records.size()};
    std::vector<const TaskRecord*> ok;
    std::map<std::string, std::vector<const TaskRecord*>> byScene;
    for (const TaskRecord& r : records) {
        if (r.failed) {
            m.failed.push_back(r);
            continue;
        }
        ok.push_back(&r);
        byScene[r.scene].push_back(&r);
    }
    m.groups.push_back(summarizeGroup("corpus", ok));
    for (const auto& [scene, list] : byScene)
        m.groups.push_back(summarizeGroup(scene, list));
    return m;
}

nlohmann::json mergeJson(const MergeResult& m) {
    nlohmann::json j{{"tasks", m.tasks}, {"failed", nlohmann::json::array()}};
    for (const TaskRecord& r : m.failed) {
        j["failed"].push_back({{"id", r.id},
                               {"scene", r.scene},
                               {"light", r.light},
                               {"camera", r.camera},
                               {"setting", r.setting},
                               {"error", r.error}});
        if (r.time)
            j["failed"].back()["time"] = *r.time;
    }
    j["groups"] = nlohmann::json::array();
    for (const GroupSummary& g : m.groups) {
        nlohmann::json settings = nlohmann::json::array();
        for (const SettingSummary& s : g.settings) {
            nlohmann::json error = nlohmann::json::object();
            for (const auto& [name, e] : s.metrics)
                error[name] = {{"value", number(e.value)},
                               {"ci95", {number(e.lo), number(e.hi)}},
                               {"rank", e.rank}};
            settings.push_back({{"setting", s.setting},
                                {"technique", s.technique},
                                {"views", s.views},
                                {"error", error},
                                {"cost",
                                 {{"visibility_ms", number(s.visibilityMs)},
                                  {"shadow_ms", number(s.shadowMs)},
                                  {"pareto", s.onFront},
                                  {"devices", s.devices}}}});
        }
        j["groups"].push_back({{"name", g.name}, {"settings", settings}});
    }
    return j;
}

} // namespace penumbra::sweep
