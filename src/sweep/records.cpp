// Task records (records.h).
#include "sweep/records.h"

#include "penumbra/error.h"
#include "sweep/atomic_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace penumbra::sweep {
namespace {

// NaN as null (JSON has no NaN), and back.
nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}
double numberFrom(const nlohmann::json& j) {
    return j.is_number() ? j.get<double>() : NAN;
}

} // namespace

nlohmann::json taskRecordJson(const TaskRecord& r) {
    nlohmann::json j{{"id", r.id},
                     {"view", r.view},
                     {"scene", r.scene},
                     {"light", r.light},
                     {"camera", r.camera},
                     {"setting", r.setting},
                     {"technique", r.technique},
                     {"status", r.failed ? "failed" : "ok"},
                     {"width", r.width},
                     {"height", r.height},
                     {"samples", r.samples}};
    if (r.time)
        j["time"] = *r.time;
    j["parameters"] = nlohmann::json::object();
    for (const auto& [key, value] : r.parameters)
        j["parameters"][key] = value;
    if (r.failed) {
        j["error"] = r.error;
        return j;
    }
    j["device"] = r.device;
    j["truth"] = {{"key", r.truthKey}, {"computed", r.truthComputed}};
    for (const auto& [name, value] : r.metrics)
        j["metrics"][name] = number(value);
    for (const auto& [name, values] : r.replicates) {
        nlohmann::json list = nlohmann::json::array();
        for (double v : values)
            list.push_back(number(v));
        j["replicates"][name] = list;
    }
    j["gpu_ms"] = {{"visibility", number(r.visibilityMs)}, {"shadow", number(r.shadowMs)}};
    for (const auto& [pass, ms] : r.passes)
        j["gpu_ms"]["passes"][pass] = number(ms);
    return j;
}

TaskRecord taskRecordFrom(const nlohmann::json& j, const std::string& file) {
    try {
        TaskRecord r{.id = j.at("id"),
                     .view = j.at("view"),
                     .scene = j.at("scene"),
                     .light = j.at("light"),
                     .camera = j.at("camera"),
                     .setting = j.at("setting"),
                     .technique = j.at("technique"),
                     .failed = j.at("status") == "failed",
                     .width = j.at("width"),
                     .height = j.at("height"),
                     .samples = j.at("samples")};
        if (j.contains("time"))
            r.time = j.at("time").get<double>();
        for (const auto& [key, value] : j.at("parameters").items())
            r.parameters.emplace_back(key, value.get<std::string>());
        if (r.failed) {
            r.error = j.at("error");
            return r;
        }
        r.device = j.at("device");
        r.truthKey = j.at("truth").at("key");
        r.truthComputed = j.at("truth").at("computed");
        for (const auto& [name, value] : j.at("metrics").items())
            r.metrics[name] = numberFrom(value);
        if (j.contains("replicates"))
            for (const auto& [name, values] : j.at("replicates").items())
                for (const nlohmann::json& v : values)
                    r.replicates[name].push_back(numberFrom(v));
        r.visibilityMs = numberFrom(j.at("gpu_ms").at("visibility"));
        r.shadowMs = numberFrom(j.at("gpu_ms").at("shadow"));
        if (j.at("gpu_ms").contains("passes"))
            for (const auto& [pass, ms] : j.at("gpu_ms").at("passes").items())
                r.passes.emplace_back(pass, numberFrom(ms));
        return r;
    } catch (const nlohmann::json::exception& e) {
        throw InputError(file, fmt::format("not a task record: {}", e.what()));
    }
}

std::filesystem::path taskRecordPath(const std::filesystem::path& dir, const std::string& id) {
    return dir / "tasks" / (id + ".json");
}

void writeTaskRecord(const std::filesystem::path& dir, const TaskRecord& record) {
    const std::filesystem::path final = taskRecordPath(dir, record.id);
    std::error_code ec;
    std::filesystem::create_directories(final.parent_path(), ec);
    writeFileAtomically(final,
                        [&](std::ostream& out) { out << taskRecordJson(record).dump(1) << "\n"; });
}

std::vector<TaskRecord> readTaskRecords(const std::filesystem::path& dir) {
    std::vector<TaskRecord> out;
    std::error_code ec;
    if (!std::filesystem::is_directory(dir / "tasks", ec))
        throw InputError(dir.string(), "no tasks/ folder: not a sweep's output directory");
    for (const auto& entry : std::filesystem::directory_iterator(dir / "tasks")) {
        const std::filesystem::path p = entry.path();
        if (p.extension() != ".json" || p.filename().string().front() == '.')
            continue; // temporary files of tasks in flight
        std::ifstream in(p, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
        if (j.is_discarded())
            throw InputError(p.string(), "not valid JSON");
        out.push_back(taskRecordFrom(j, p.string()));
    }
    std::sort(out.begin(), out.end(),
              [](const TaskRecord& a, const TaskRecord& b) { return a.id < b.id; });
    return out;
}

void setCosts(TaskRecord& record, const std::vector<PassTime>& passes) {
    record.passes.clear();
    record.visibilityMs = 0;
    record.shadowMs = 0;
    for (const PassTime& p : passes) {
        record.passes.emplace_back(p.pass, p.medianMs);
        if (p.cost == CostGroup::Frame)
            continue; // the same for every technique
        record.shadowMs += p.medianMs;
        if (p.cost == CostGroup::PerPixel)
            record.visibilityMs += p.medianMs;
    }
}

} // namespace penumbra::sweep
