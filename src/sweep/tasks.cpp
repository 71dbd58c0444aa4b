// Task expansion and sharding (tasks.h).
#include "sweep/tasks.h"

#include "core/fnv1a.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <map>

namespace penumbra::sweep {
namespace {

std::string describe(const PlanLight& l) {
    std::string text = fmt::format("kind={};size={}", l.kind, l.size);
    if (l.position)
        text += fmt::format(";pos={},{},{}", l.position->x, l.position->y, l.position->z);
    if (l.direction)
        text += fmt::format(";dir={},{},{}", l.direction->x, l.direction->y, l.direction->z);
    if (l.coneDegrees)
        text += fmt::format(";cone={}", *l.coneDegrees);
    return text;
}

} // namespace

std::string hashHex(std::string_view bytes) {
    return fmt::format("{:016x}", fnv1a(bytes.data(), bytes.size()));
}

SweepTasks expandTasks(const Plan& plan) {
    SweepTasks out;
    std::vector<std::optional<double>> times(plan.times.begin(), plan.times.end());
    if (times.empty())
        times.push_back(std::nullopt); // at rest, described as before times were read
    for (const PlanScene& scene : plan.scenes)
        for (const PlanLight& light : plan.lights)
            for (const std::string& camera : plan.cameras)
                for (const std::optional<double>& time : times) {
                    // The light's name is a label; what it is decides the view.
                    std::string text = fmt::format(
                        "scene={};light={};camera={};size={}x{};samples={}", scene.label,
                        describe(light), camera, plan.width, plan.height, plan.samples);
                    if (time)
                        text += fmt::format(";time={};animation={}", *time, plan.animation);
                    out.views.push_back({.scene = scene,
                                         .light = light,
                                         .camera = camera,
                                         .time = time,
                                         .animation = time ? plan.animation : "",
                                         .id = hashHex(text)});
                }
    std::sort(out.views.begin(), out.views.end(),
              [](const SweepView& a, const SweepView& b) { return a.id < b.id; });
    for (size_t v = 0; v < out.views.size(); ++v)
        for (const PlanSetting& setting : plan.settings) {
            const std::string text =
                fmt::format("view={};setting={};shadow_map={};frames={}", out.views[v].id,
                            setting.name(), plan.shadowMapSize, plan.frames);
            out.tasks.push_back({.view = v, .setting = setting, .id = hashHex(text)});
        }
    std::sort(out.tasks.begin(), out.tasks.end(), [](const SweepTask& a, const SweepTask& b) {
        return a.view != b.view ? a.view < b.view : a.id < b.id;
    });
    return out;
}

std::vector<size_t> shardTasks(const SweepTasks& tasks, uint32_t index, uint32_t count) {
    assert(count > 0 && index < count);
    std::vector<size_t> mine;
    if (tasks.views.size() < count) {
        for (size_t t = index; t < tasks.tasks.size(); t += count)
            mine.push_back(t);
        return mine;
    }
    std::map<size_t, std::vector<size_t>> byView;
    for (size_t t = 0; t < tasks.tasks.size(); ++t)
        byView[tasks.tasks[t].view].push_back(t);
    std::vector<const std::vector<size_t>*> groups;
    for (const auto& [view, list] : byView)
        groups.push_back(&list);
    std::stable_sort(groups.begin(), groups.end(),
                     [](auto* a, auto* b) { return a->size() > b->size(); });
    std::vector<size_t> load(count, 0);
    for (const std::vector<size_t>* group : groups) {
        const size_t shard = size_t(std::min_element(load.begin(), load.end()) - load.begin());
        load[shard] += group->size();
        if (shard == index)
            mine.insert(mine.end(), group->begin(), group->end());
    }
    std::sort(mine.begin(), mine.end());
    return mine;
}

} // namespace penumbra::sweep
