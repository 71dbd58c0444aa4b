#pragma once
// Techniques, their tunable parameters (`--set family.name=value`), and the render options.
// Every parameter has a default and a valid range; `penumbra techniques` prints this table.
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

// Every technique, one per line of the technique list (shaders/include/technique_list.h, which
// the shaders read too).
enum class Technique : uint32_t {
#define PENUMBRA_TECHNIQUE(id, Name, module, shader) Name = id,
#include "technique_list.h"
};

// A parameter setting worth its own row in `compare`, e.g. label "box7" for pcf: pcf[box7].
struct TechniqueVariant {
    std::string_view label; // empty: the technique's defaults
    std::vector<std::pair<std::string_view, std::string_view>> sets;
};

struct TechniqueInfo {
    Technique id;
    std::string_view name;                  // CLI name, e.g. "hard"
    std::string_view summary;               // one line
    std::string_view reference;             // the paper or text it implements
    std::vector<std::string_view> families; // parameter families it reads, e.g. {"bias"}
    // The rows `compare` shows by default; none declared: the technique's defaults, one row
    // named as the technique.
    std::vector<TechniqueVariant> variants;
};

// One row of a comparison: a technique with its variant's parameters, and the layers it runs on
// top (src/shadows/layer.h), e.g. "pcf[box3]+contact".
struct TechniqueRow {
    std::string name; // "hard", "pcf[box7]", "pcf[box3]+contact"
    Technique technique;
    std::vector<std::pair<std::string, std::string>> sets;
    std::vector<std::string> layers; // "contact"
};

class ParameterValues;

// Expands `--techniques`: a comma-separated list of technique names (each gives all its
// variants) or row names, each optionally followed by layers ("pcf[box3]+contact", "pcf+contact":
// every pcf row with the layer); empty gives every variant of every technique and the rows each
// layer shows by default. Throws InputError.
std::vector<TechniqueRow> comparisonRows(std::string_view list);
// Applies a row to `params` (the caller's own settings already in): its variant's settings, then
// its layers: a row runs exactly the layers it names (the others are switched off), each with
// the caller's settings, or where they leave it off, the layer's row settings for a scene of
// `sceneRadius` (its bounding sphere's, world units).
void applyRow(const TechniqueRow& row, ParameterValues& params, double sceneRadius);

std::span<const TechniqueInfo> allTechniques();
std::string_view techniqueName(Technique technique);
// What every command, the Python module and a benchmark run use when no technique is named, and
// the viewer's second technique in its A/B split: the technique list names both.
inline constexpr Technique kDefaultTechnique = Technique::PENUMBRA_DEFAULT_TECHNIQUE;
inline constexpr Technique kComparedTechnique = Technique::PENUMBRA_COMPARED_TECHNIQUE;
// Throws InputError("--technique", ...) listing the valid names when `name` is unknown.
const TechniqueInfo& findTechnique(std::string_view name);

enum class ParameterType { Float, Int, Bool, Choice };

struct ParameterInfo {
    std::string_view key; // "family.name"
    ParameterType type;
    double defaultValue; // Choice: index into choices; Bool: 0 or 1
    double min, max;     // inclusive range for Float and Int
    std::vector<std::string_view> choices;
    std::string_view unit;
    std::string_view description;
    bool oddOnly = false; // Int parameters that must be odd (kernel sizes)
};

std::span<const ParameterInfo> allParameters();

// The values in effect for one render: every registered parameter, default unless set.
class ParameterValues {
public:
    ParameterValues(); // all defaults
    // Parses and range-checks `value` for `key`; throws InputError("--set", ...) on an unknown
    // key, a malformed value or one outside the valid range.
    void set(std::string_view key, std::string_view value);
    // Parses "key=value".
    void assign(std::string_view keyEqualsValue);
    double number(std::string_view key) const; // programmer error if key is unknown
    bool isSet(std::string_view key) const { return mSet.contains(key); } // by set() or assign()
    std::string text(std::string_view key) const; // value as the user would write it
    const std::map<std::string, double, std::less<>>& all() const { return mValues; }

private:
    std::map<std::string, double, std::less<>> mValues;
    std::set<std::string, std::less<>> mSet;
};

struct RenderOptions {
    uint32_t width = 1280;
    uint32_t height = 720;
    uint32_t shadowMapSize = 2048;
    uint32_t frames = 5; // timed frames after one warm-up frame
    std::string camera;  // glTF camera name; empty = first camera or automatic framing
    Technique technique = kDefaultTechnique;
    ParameterValues parameters;
    float lightRadiusOverride = -1.0f; // world units; < 0 = from the scene
    float lightAngleOverride = -1.0f;  // degrees;     < 0 = from the scene
    bool motion = false;               // the G-buffer's motion vectors too (RenderResult::motion)
};

// Checks ranges that need no device (sizes > 0, frames >= 1, ...); throws InputError.
void validate(const RenderOptions& options);

} // namespace penumbra
