// The plan file: TOML (toml++), every key checked against what this file knows, every value
// against the ranges the commands check, before a single scene loads.
#include "sweep/plan.h"

#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "scene/generated.h"
#include "scene/timeline_range.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <set>

namespace penumbra::sweep {
namespace {

class PlanReader {
public:
    explicit PlanReader(std::filesystem::path path) : mPath(std::move(path)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        throw InputError(mPath.string(), fmt::format("{}: {}", key, problem));
    }

    // Every key of `table` must be one of `known` (the first unknown one is named).
    void onlyKeys(const toml::table& table, const std::string& where,
                  std::initializer_list<std::string_view> known) const {
        for (auto&& [key, value] : table)
            if (std::find(known.begin(), known.end(), key.str()) == known.end())
                fail(where + std::string(key.str()), "unknown key");
    }

    uint32_t count(const toml::table& t, std::string_view key, uint32_t fallback, int64_t min,
                   int64_t max) const {
        const toml::node* node = t.get(key);
        if (!node)
            return fallback;
        const std::optional<int64_t> v = node->value_exact<int64_t>();
        if (!v)
            fail(std::string(key), "expected a whole number");
        if (*v < min || *v > max)
            fail(std::string(key), fmt::format("{} is outside {}..{}", *v, min, max));
        return uint32_t(*v);
    }

    float number(const toml::node& node, const std::string& key) const {
        const std::optional<double> v = node.value<double>();
        if (!v || !std::isfinite(*v))
            fail(key, "expected a number");
        return float(*v);
    }

    glm::vec3 vector3(const toml::node& node, const std::string& key) const {
        const toml::array* a = node.as_array();
        if (!a || a->size() != 3)
            fail(key, "expected three numbers [x, y, z]");
        glm::vec3 v{number(*a->get(0), key), number(*a->get(1), key), number(*a->get(2), key)};
        if (v == glm::vec3(0.0f))
            fail(key, "a direction of length 0");
        return v;
    }

    // A scalar as written, for messages.
    static std::string valueText(const toml::node& n) {
        if (auto s = n.value_exact<std::string>())
            return *s;
        if (auto d = n.value<double>())
            return fmt::format("{}", *d);
        if (auto b = n.value_exact<bool>())
            return *b ? "true" : "false";
        return "a table or list";
    }

    // A scalar or an array of scalars, as the text `--set` takes.
    std::vector<std::string> values(const toml::node& node, const std::string& key) const {
        std::vector<std::string> out;
        auto one = [&](const toml::node& n) {
            if (auto s = n.value_exact<std::string>())
                out.push_back(*s);
            else if (auto i = n.value_exact<int64_t>())
                out.push_back(std::to_string(*i));
            else if (auto d = n.value_exact<double>())
                out.push_back(fmt::format("{}", *d));
            else if (auto b = n.value_exact<bool>())
                out.push_back(*b ? "true" : "false");
            else
                fail(key, "expected a value or an array of values");
        };
        if (const toml::array* a = node.as_array()) {
            if (a->empty())
                fail(key, "an empty list");
            for (const toml::node& n : *a)
                one(n);
        } else {
            one(node);
        }
        return out;
    }

    void readScenes(const toml::table& root, Plan& plan) const {
        const toml::array* scenes = root["scenes"].as_array();
        if (!scenes || scenes->empty())
            fail("scenes", "expected a non-empty list of scenes (builtin:NAME or glTF paths)");
        const std::vector<std::string_view> builtins = builtinSceneNames();
        for (size_t i = 0; i < scenes->size(); ++i) {
            const std::string key = fmt::format("scenes[{}]", i);
            const std::optional<std::string> text = scenes->get(i)->value_exact<std::string>();
            if (!text || text->empty())
                fail(key, "expected a scene name or path");
            PlanScene scene{.label = *text, .spec = *text};
            if (text->rfind("builtin:gen/", 0) == 0) {
                try {
                    parseGeneratedSpec(text->substr(12));
                } catch (const InputError& e) {
                    fail(key, e.what());
                }
            } else if (text->rfind("builtin:", 0) == 0) {
                if (std::find(builtins.begin(), builtins.end(), text->substr(8)) == builtins.end())
                    fail(key, fmt::format("no built-in scene '{}'", text->substr(8)));
            } else {
                const std::filesystem::path file = mPath.parent_path() / *text;
                std::error_code ec;
                if (!std::filesystem::is_regular_file(file, ec))
                    fail(key, fmt::format("no such file: {}", file.string()));
                scene.spec = file.string();
            }
            for (const PlanScene& other : plan.scenes)
                if (other.label == scene.label)
                    fail(key, fmt::format("'{}' is listed twice", scene.label));
            plan.scenes.push_back(std::move(scene));
        }
    }

    // `times`: a list of seconds, or "START:END:STEP" as compare --timeline reads it, at most
    // kMaxTimelineFrames either way, each time once (-0 is 0).
    void readTimes(const toml::table& root, Plan& plan) const {
        if (const toml::node* node = root.get("times")) {
            if (const std::optional<std::string> range = node->value_exact<std::string>()) {
                try {
                    const Timeline timeline = parseTimeline(*range);
                    for (size_t k = 0; k < timeline.frames; ++k)
                        plan.times.push_back(timeline.at(k));
                } catch (const InputError& e) {
                    fail("times", withoutSubject(e));
                }
            } else if (const toml::array* list = node->as_array()) {
                if (list->empty())
                    fail("times", "an empty list");
                if (list->size() > kMaxTimelineFrames)
                    fail("times",
                         fmt::format("{} times; at most {}", list->size(), kMaxTimelineFrames));
                for (const toml::node& n : *list) {
                    // Integers and floats; a string or a boolean has no value<double>.
                    const std::optional<double> seconds = n.value<double>();
                    if (!seconds || !std::isfinite(*seconds) || *seconds < 0.0)
                        fail("times",
                             fmt::format("'{}' is not a time in seconds, 0 or more", valueText(n)));
                    plan.times.push_back(*seconds + 0.0); // -0 is 0
                }
            } else {
                fail("times", "expected a list of seconds or \"START:END:STEP\"");
            }
            std::vector<double> sorted = plan.times;
            std::sort(sorted.begin(), sorted.end());
            if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
                twice != sorted.end())
                fail("times", fmt::format("{} is listed twice", *twice));
        }
        if (const toml::node* node = root.get("animation")) {
            if (plan.times.empty())
                fail("animation", "needs times (without them the scenes are at rest)");
            if (const std::optional<std::string> name = node->value_exact<std::string>())
                plan.animation = *name;
            else if (const std::optional<int64_t> index = node->value_exact<int64_t>();
                     index && *index >= 0)
                plan.animation = std::to_string(*index);
            if (plan.animation.empty())
                fail("animation", "expected an animation's name or index");
        }
    }

    void readLights(const toml::table& root, Plan& plan) const {
        const toml::node* node = root.get("lights");
        if (!node) { // the scenes' own lights at their own sizes
            plan.lights.push_back({.name = "scene", .kind = "scene", .size = -1.0f});
            return;
        }
        const toml::array* lights = node->as_array();
        if (!lights || lights->empty() || !lights->is_array_of_tables())
            fail("lights", "expected [[lights]] tables");
        std::set<std::string> names;
        for (size_t i = 0; i < lights->size(); ++i) {
            const toml::table& t = *lights->get(i)->as_table();
            const std::string at = fmt::format("lights[{}].", i);
            onlyKeys(t, at, {"name", "kind", "position", "direction", "cone", "sizes"});
            PlanLight light{.kind = t["kind"].value_or(std::string())};
            if (light.kind != "sun" && light.kind != "spot" && light.kind != "point" &&
                light.kind != "scene")
                fail(at + "kind", "expected sun, spot, point or scene");
            light.name = t["name"].value_or(fmt::format("{}{}", light.kind, i));
            const bool needsPosition = light.kind == "spot" || light.kind == "point";
            const bool needsDirection = light.kind == "spot" || light.kind == "sun";
            if (const toml::node* p = t.get("position"))
                light.position = vector3(*p, at + "position");
            if (const toml::node* d = t.get("direction"))
                light.direction = vector3(*d, at + "direction");
            if (needsPosition != light.position.has_value())
                fail(at + "position", needsPosition ? "missing" : "only spot and point lights");
            if (needsDirection != light.direction.has_value())
                fail(at + "direction", needsDirection ? "missing" : "only sun and spot lights");
            if (const toml::node* c = t.get("cone")) {
                if (light.kind != "spot")
                    fail(at + "cone", "only spot lights");
                light.coneDegrees = number(*c, at + "cone");
                if (*light.coneDegrees <= 0 || *light.coneDegrees >= 90)
                    fail(at + "cone", "expected an outer half-angle in (0, 90) degrees");
            }
            std::vector<float> sizes{-1.0f}; // scene: their own sizes
            if (const toml::node* s = t.get("sizes")) {
                sizes.clear();
                for (const std::string& v : values(*s, at + "sizes")) {
                    char* end = nullptr;
                    const float size = std::strtof(v.c_str(), &end);
                    const float max = light.kind == "sun" ? 30.0f : 1e6f;
                    if (*end || !std::isfinite(size) || size < 0 || size > max)
                        fail(at + "sizes", fmt::format("'{}' is not a size in 0..{}", v, max));
                    sizes.push_back(size);
                }
            } else if (light.kind != "scene") {
                sizes = {0.0f};
            }
            for (float size : sizes) {
                PlanLight sized = light;
                sized.size = size;
                if (sizes.size() > 1 || size >= 0)
                    sized.name = fmt::format("{}@{}", light.name, size);
                if (!names.insert(sized.name).second)
                    fail(at + "name", fmt::format("'{}' is used twice", sized.name));
                plan.lights.push_back(std::move(sized));
            }
        }
    }

    void readTechniques(const toml::table& root, Plan& plan) const {
        const toml::array* list = root["techniques"].as_array();
        if (!list || list->empty() || !list->is_array_of_tables())
            fail("techniques", "expected [[techniques]] tables");
        for (size_t i = 0; i < list->size(); ++i) {
            const toml::table& t = *list->get(i)->as_table();
            const std::string at = fmt::format("techniques[{}].", i);
            const std::optional<std::string> name = t["name"].value_exact<std::string>();
            if (!name)
                fail(at + "name", "missing");
            const TechniqueInfo* info = nullptr;
            try {
                info = &findTechnique(*name);
            } catch (const InputError&) {
                fail(at + "name", fmt::format("no technique '{}' (penumbra techniques)", *name));
            }
            // Every other key is a parameter family: `pcf.samples = [16, 32]`.
            std::vector<std::pair<std::string, std::vector<std::string>>> axes;
            for (auto&& [family, node] : t) {
                if (family.str() == "name")
                    continue;
                const toml::table* params = node.as_table();
                if (!params)
                    fail(at + std::string(family.str()),
                         "unknown key (parameters are written family.name = value)");
                // A family the technique does not read would sweep a setting with no effect.
                const auto& families = info->families;
                if (std::find(families.begin(), families.end(), family.str()) == families.end())
                    fail(at + std::string(family.str()),
                         fmt::format("{} reads no {}.* parameters", *name, family.str()));
                for (auto&& [param, v] : *params) {
                    const std::string key = fmt::format("{}.{}", family.str(), param.str());
                    axes.emplace_back(key, values(v, at + key));
                    for (const std::string& value : axes.back().second)
                        checkParameter(key, value, at + key);
                }
            }
            std::sort(axes.begin(), axes.end());
            std::vector<PlanSetting> grid{{.technique = *name}};
            for (const auto& [key, options] : axes) {
                std::vector<PlanSetting> next;
                for (const PlanSetting& s : grid)
                    for (const std::string& value : options) {
                        PlanSetting more = s;
                        more.sets.emplace_back(key, value);
                        next.push_back(std::move(more));
                    }
                grid = std::move(next);
            }
            for (PlanSetting& s : grid) {
                for (const PlanSetting& other : plan.settings)
                    if (other.name() == s.name())
                        fail(at + "name", fmt::format("'{}' is in the plan twice", s.name()));
                plan.settings.push_back(std::move(s));
            }
        }
    }

    // ParameterValues' own check, with its message under the plan's key.
    void checkParameter(const std::string& key, const std::string& value,
                        const std::string& where) const {
        try {
            ParameterValues().set(key, value);
        } catch (const InputError& e) {
            fail(where, withoutSubject(e));
        }
    }

    static std::string withoutSubject(const InputError& e) {
        std::string why = e.what();
        const std::string prefix = e.subject() + ": ";
        if (why.rfind(prefix, 0) == 0)
            why.erase(0, prefix.size());
        return why;
    }

private:
    std::filesystem::path mPath;
};

} // namespace

std::string PlanSetting::name() const {
    std::string list;
    for (const auto& [key, value] : sets)
        list += fmt::format("{}{}={}", list.empty() ? "" : ",", key, value);
    return list.empty() ? technique : fmt::format("{}[{}]", technique, list);
}

Plan loadPlan(const std::filesystem::path& path) {
    PlanReader reader(path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(path.string(), "no such plan file");
    toml::table root;
    try {
        root = toml::parse_file(path.string());
    } catch (const toml::parse_error& e) {
        throw InputError(path.string(),
                         fmt::format("line {}: {}", e.source().begin.line, e.description()));
    }
    reader.onlyKeys(root, "",
                    {"scenes", "lights", "cameras", "width", "height", "samples", "shadow_map_size",
                     "frames", "times", "animation", "techniques"});
    Plan plan{.path = path};
    plan.width = reader.count(root, "width", plan.width, 1, 16384);
    plan.height = reader.count(root, "height", plan.height, 1, 16384);
    plan.samples = reader.count(root, "samples", plan.samples, 1, 65536);
    plan.shadowMapSize = reader.count(root, "shadow_map_size", plan.shadowMapSize, 16, 16384);
    plan.frames = reader.count(root, "frames", plan.frames, 1, 1000);
    reader.readScenes(root, plan);
    reader.readTimes(root, plan);
    reader.readLights(root, plan);
    if (const toml::node* cameras = root.get("cameras")) {
        const toml::array* a = cameras->as_array();
        if (!a || a->empty())
            reader.fail("cameras", "expected a list of camera names (\"\": the default)");
        for (const toml::node& n : *a) {
            const std::optional<std::string> name = n.value_exact<std::string>();
            if (!name)
                reader.fail("cameras", "expected camera names");
            plan.cameras.push_back(*name);
        }
    } else {
        plan.cameras = {""};
    }
    reader.readTechniques(root, plan);
    return plan;
}

} // namespace penumbra::sweep
