// The technique and parameter tables behind `--technique`, `--set` and `penumbra techniques`,
// gathered from the technique modules (src/shadows/technique.h): each registers its own rows and
// parameter family; the families every technique reads (bias, csm, composite) are registered
// here.
// The renderer reads values by key, so a new family adds rows, not plumbing.
#include "bias.h"
#include "penumbra/error.h"
#include "penumbra/settings.h"
#include "shadows/layer.h"
#include "shadows/technique.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>

namespace penumbra {
namespace {

// Every technique reads the layers' families too: any layer runs on top of any technique.
const std::vector<TechniqueInfo>& techniqueTable() {
    static const std::vector<TechniqueInfo> table = [] {
        std::vector<TechniqueInfo> t;
        for (const shadows::TechniqueModule* m : shadows::allModules()) {
            t.push_back(m->info);
            if (t.back().variants.empty()) // no rows of its own: its defaults, as one row
                t.back().variants.push_back({.label = ""});
            if (m->readsVirtualMaps)
                t.back().families.push_back("virtual");
            for (const shadows::LayerModule* layer : shadows::allLayers())
                t.back().families.push_back(layer->name);
        }
        return t;
    }();
    return table;
}

// The families every technique reads (bias, csm, composite) and each module's own.
const std::vector<ParameterInfo>& parameterTable() {
    static const std::vector<ParameterInfo> bias{
        {.key = "bias.mode",
         .type = ParameterType::Choice,
         .defaultValue = 1, // measured: docs/techniques.md, "Adaptive depth bias"
         .choices = {std::begin(gpu::kBiasModeChoices), std::end(gpu::kBiasModeChoices)},
         .description = "fixed: bias.constant and bias.slope offset the casters in the shadow "
                        "pass; adaptive [Dou et al. 2014]: the map stores exact depths and each "
                        "receiver is biased from its own triangle's plane at every tap (whatever "
                        "bias.receiver says), lifted by bias.adaptive texels and by what its "
                        "curvature (bias.curvature) can bring within each tap's reach"},
        {.key = "bias.adaptive",
         .type = ParameterType::Float,
         .defaultValue = 0.25,
         .min = 0.0,
         .max = 10.0,
         .unit = "texels (of the receiver's texel footprint along the light's ray)",
         .description = "bias.mode=adaptive: the receiver's constant lift towards the light, "
                        "the paper's adaptive epsilon, in world units of the receiver's texel "
                        "over N.L"},
        {.key = "bias.curvature",
         .type = ParameterType::Float,
         .defaultValue = 1.0,
         .min = 0.0,
         .max = 10.0,
         .unit = "",
         .description = "bias.mode=adaptive: scales the surface's measured curvature in each "
                        "tap's lift and in the reach of the receiver plane's correction (0: "
                        "flat surfaces everywhere)"},
        {.key = "bias.crease",
         .type = ParameterType::Float,
         .defaultValue = 20.0, // measured: docs/techniques.md, "Creases"
         .min = 0.0,
         .max = 100.0,
         .unit = "slope (cot of the angle between a surface and the light's rays)",
         .description = "bias.mode=adaptive: a filter tap whose 2x2 texels lie on a plane that "
                        "passes behind the receiver (a wall rising from its floor, a box standing "
                        "on it) tests lit, nothing on that plane can hide the light; planes "
                        "steeper than this, or than the light's size allows, are taken for a "
                        "caster's edge (0: off)"},
        {.key = "bias.constant",
         .type = ParameterType::Float,
         .defaultValue = 0.0005,
         .min = 0.0,
         .max = 0.1,
         .unit = "light depth (fraction of the shadow map's [0,1] depth range)",
         .description = "constant depth offset added to every caster in the shadow pass"},
        {.key = "bias.slope",
         .type = ParameterType::Float,
         .defaultValue = 2.0,
         .min = 0.0,
         .max = 50.0,
         .unit = "rasterizer slope factor",
         .description = "slope-scaled depth bias: multiplies the caster's max depth slope per "
                        "texel (hardware depth bias)"},
        {.key = "bias.normal",
         .type = ParameterType::Float,
         .defaultValue = 0.3,
         .min = 0.0,
         .max = 20.0,
         .unit = "shadow-map texels",
         .description = "normal offset: the receiver moves along its normal by this many texels, "
                        "scaled by 1 - N.L, before the lookup"},
        {.key = "bias.horizon",
         .type = ParameterType::Choice,
         .defaultValue = 1,
         .choices = {std::begin(gpu::kHorizonChoices), std::end(gpu::kHorizonChoices)},
         .description = "clip a light with a size by the receiver's own tangent plane, the part "
                        "of it below the surface's horizon being hidden by the surface itself, "
                        "which no shadow map holds: in the techniques that model the light's size "
                        "(soft), in every technique (all), or none (off)"},
        {.key = "bias.receiver",
         .type = ParameterType::Choice,
         .defaultValue = 2,
         .choices = {std::begin(gpu::kReceiverChoices), std::end(gpu::kReceiverChoices)},
         .description = "receiver-plane depth bias [Tuft 2010]: each tap compares against the "
                        "receiver's depth at that tap, from screen-space neighbours (screen) or "
                        "from the surface normal in light space (light)"},
        {.key = "bias.receiverClamp",
         .type = ParameterType::Float,
         .defaultValue = 0.05,
         .min = 0.0,
         .max = 1.0,
         .unit = "light depth",
         .description = "largest receiver-plane correction per tap (guards silhouettes, where "
                        "the plane is a poor fit)"},
        {.key = "bias.receiverSides",
         .type = ParameterType::Choice,
         .defaultValue = 1,
         .choices = {"both", "near"},
         .description = "which receiver-plane corrections apply: both signs, or only those that "
                        "bring a tap's depth nearer the light (near: the plane cannot extrapolate "
                        "beneath a neighbouring surface at a concave crease)"}};
    // Cascaded shadow maps for directional lights [Engel 2006; Zhang et al. 2006, parallel-split
    // shadow maps]: src/core/cascades.cpp, docs/techniques.md "Cascades".
    static const std::vector<ParameterInfo> csm{
        {.key = "csm.cascades",
         .type = ParameterType::Int,
         .defaultValue = 4,
         .min = 1,
         .max = 8,
         .unit = "shadow views",
         .description = "cascades of a directional light, each fitted to a slice of the camera's "
                        "view distance (1: one map over the whole scene)"},
        {.key = "csm.lambda",
         .type = ParameterType::Float,
         .defaultValue = 0.9, // measured: docs/techniques.md, "Cascades"
         .min = 0.0,
         .max = 1.0,
         .unit = "",
         .description = "split scheme: 0 uniform, 1 logarithmic, between them the practical "
                        "split's blend"},
        {.key = "csm.blend",
         .type = ParameterType::Float,
         .defaultValue = 0.1,
         .min = 0.0,
         .max = 0.5,
         .unit = "fraction of a cascade",
         .description = "the last part of each cascade, blended into the next one (no seam)"},
        {.key = "csm.stabilize",
         .type = ParameterType::Bool,
         .defaultValue = 1,
         .description = "fit each cascade to its slice's bounding sphere and snap it to whole "
                        "texels, so shadows do not crawl when the camera moves or turns"}};
    // Virtual shadow maps [Unreal Engine 5; EEVEE-Next]: src/core/virtual_maps.h,
    // docs/techniques.md "Virtual shadow maps". Read by the techniques that read their map texel
    // by texel (TechniqueModule::readsVirtualMaps).
    static const std::vector<ParameterInfo> virtualMaps{
        {.key = "virtual.enabled",
         .type = ParameterType::Bool,
         .defaultValue = 0,
         .description = "store the shadow views as virtual maps: pages of a very large map "
                        "rendered only where visible pixels need them, kept across frames in a "
                        "physical pool (0: cascades and cube faces of --shadow-map-size)"},
        {.key = "virtual.size",
         .type = ParameterType::Int,
         .defaultValue = 16384,
         .min = 1024,
         .max = 65536,
         .unit = "texels (a power of two)",
         .description = "a virtual map level's side: a sun's clipmap level, a spot's frustum, a "
                        "cube face"},
        {.key = "virtual.pageSize",
         .type = ParameterType::Int,
         .defaultValue = 128,
         .min = 16,
         .max = 1024,
         .unit = "texels (a power of two)",
         .description = "a page's side: the unit that is requested, rendered and cached"},
        {.key = "virtual.levels",
         .type = ParameterType::Int,
         .defaultValue = 12,
         .min = 1,
         .max = 16,
         .unit = "levels",
         .description = "a sun's clipmap levels up to the one over the whole scene, each twice "
                        "the extent of the one below (the finest: the scene's extent / 2^(levels "
                        "- 1)); above it, its mips down to one page, as a spot's and a cube "
                        "face's levels"},
        {.key = "virtual.poolSize",
         .type = ParameterType::Int,
         .defaultValue = 8192,
         .min = 256,
         .max = 32768,
         .unit = "texels (a multiple of virtual.pageSize)",
         .description = "the physical pool's side: (poolSize / pageSize)^2 pages shared by every "
                        "light; when full, pixels read coarser pages"},
        {.key = "virtual.lodBias",
         .type = ParameterType::Float,
         .defaultValue = -0.5, // docs/techniques.md: half the error of 0's misclassified pixels
         .min = -4.0,
         .max = 4.0,
         .unit = "levels",
         .description = "a pixel reads the finest level whose texel is no finer than itself, "
                        "this many levels coarser (+) or finer (-)"},
        {.key = "virtual.lodFromImage",
         .type = ParameterType::Bool,
         .defaultValue = 1, // docs/techniques.md: half four cascades' error at 512x512
         .unit = "",
         .description = "virtual.lodBias counts from a 1920x1080 image: a smaller one reads "
                        "half a level finer per halving of its pixels (at most 2 levels, a "
                        "480x270 image), a larger one coarser (at most 1): about the pages a "
                        "1080p image asks for, at any size"},
        {.key = "virtual.deviceDecides",
         .type = ParameterType::Bool,
         .defaultValue = 0, // docs/techniques.md: the host's decisions are faster on llvmpipe
         .unit = "",
         .description = "decide the pages on the device within the frame (marking, allocation, "
                        "eviction, page table, indirect page draws: no read-back, no frame of "
                        "lag); 0: on the host from the requests the frame before read back"},
        {.key = "virtual.staticLayer",
         .type = ParameterType::Bool,
         .defaultValue = 1, // docs/techniques.md: 2-4x less `shadow` in motion, the same bits
         .unit = "",
         .description = "keep each page's static layer (the casters no pose has moved) in a "
                        "second pool of virtual.poolSize^2: a page that only moving casters "
                        "touched is that layer copied and the moving casters drawn over it; the "
                        "host's decisions only (virtual.deviceDecides draws every caster)"}};
    static const std::vector<ParameterInfo> composite{
        {.key = "composite.shadowIntensity",
         .type = ParameterType::Float,
         .defaultValue = 1.0,
         .min = 0.0,
         .max = 1.0,
         .unit = "",
         .description = "how dark shadows are: direct light x (1 - intensity x (1 - visibility))"},
        {.key = "composite.ambient",
         .type = ParameterType::Float,
         .defaultValue = 0.12,
         .min = 0.0,
         .max = 1.0,
         .unit = "fraction of base colour",
         .description = "constant ambient term added to every lit pixel"},
        {.key = "composite.exposure",
         .type = ParameterType::Float,
         .defaultValue = 0.0,
         .min = -30.0,
         .max = 30.0,
         .unit = "EV (stops)",
         .description = "scales every light by 2^EV before the tone curve; glTF intensities "
                        "in lux or candela need negative values (about -16 for a 100000-lux "
                        "sun)"},
        {.key = "composite.fused",
         .type = ParameterType::Bool,
         .defaultValue = 1,
         .description = "shade in the last shadowed light's visibility dispatch (one pass fewer "
                        "over the G-buffer): its time then counts under `composite`, and "
                        "`visibility` holds the other lights' dispatches only; 0 times every "
                        "light's visibility on its own"}};
    static const std::vector<ParameterInfo> table = [] {
        std::vector<ParameterInfo> t = bias;
        for (const shadows::TechniqueModule* m : shadows::allModules())
            t.insert(t.end(), m->parameters.begin(), m->parameters.end());
        for (const shadows::LayerModule* layer : shadows::allLayers())
            t.insert(t.end(), layer->parameters.begin(), layer->parameters.end());
        t.insert(t.end(), csm.begin(), csm.end());
        t.insert(t.end(), virtualMaps.begin(), virtualMaps.end());
        t.insert(t.end(), composite.begin(), composite.end());
        return t;
    }();
    return table;
}

const ParameterInfo* findParameter(std::string_view key) {
    for (const ParameterInfo& p : parameterTable())
        if (p.key == key)
            return &p;
    return nullptr;
}

std::string knownKeys() {
    std::string keys;
    for (const ParameterInfo& p : parameterTable())
        keys += (keys.empty() ? "" : ", ") + std::string(p.key);
    return keys;
}

double parseValue(const ParameterInfo& p, std::string_view text) {
    auto bad = [&](const std::string& why) {
        return InputError("--set", fmt::format("{}={}: {}", p.key, text, why));
    };
    if (p.type == ParameterType::Bool) {
        if (text == "true" || text == "1" || text == "on")
            return 1.0;
        if (text == "false" || text == "0" || text == "off")
            return 0.0;
        throw bad("expected true or false");
    }
    if (p.type == ParameterType::Choice) {
        for (size_t i = 0; i < p.choices.size(); ++i)
            if (p.choices[i] == text)
                return static_cast<double>(i);
        throw bad(fmt::format("expected one of {}", fmt::join(p.choices, ", ")));
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() ||
        !std::isfinite(value))
        throw bad("not a finite number");
    if (p.type == ParameterType::Int && value != std::floor(value))
        throw bad("expected an integer");
    if (p.oddOnly && std::fmod(value, 2.0) == 0.0)
        throw bad("expected an odd number");
    if (value < p.min || value > p.max)
        throw bad(fmt::format("out of range [{}, {}]", p.min, p.max));
    return value;
}

} // namespace

std::span<const TechniqueInfo> allTechniques() {
    return techniqueTable();
}

std::string_view techniqueName(Technique technique) {
    for (const TechniqueInfo& t : techniqueTable())
        if (t.id == technique)
            return t.name;
    fatal(__FILE__, __LINE__, "techniqueName: unregistered technique");
}

const TechniqueInfo& findTechnique(std::string_view name) {
    for (const TechniqueInfo& t : techniqueTable())
        if (t.name == name)
            return t;
    std::string names;
    for (const TechniqueInfo& t : techniqueTable())
        names += (names.empty() ? "" : ", ") + std::string(t.name);
    throw InputError("--technique",
                     fmt::format("unknown technique '{}' (available: {})", name, names));
}

std::span<const ParameterInfo> allParameters() {
    return parameterTable();
}

namespace {

// Every variant of every technique, without layers.
std::vector<TechniqueRow> variantRows() {
    std::vector<TechniqueRow> all;
    for (const TechniqueInfo& t : techniqueTable())
        for (const TechniqueVariant& v : t.variants) {
            TechniqueRow row{.name = v.label.empty() ? std::string(t.name)
                                                     : fmt::format("{}[{}]", t.name, v.label),
                             .technique = t.id};
            for (const auto& [key, value] : v.sets)
                row.sets.emplace_back(key, value);
            all.push_back(std::move(row));
        }
    return all;
}

std::string rowNames(const std::vector<TechniqueRow>& rows) {
    std::string names;
    for (const TechniqueRow& row : rows)
        names += (names.empty() ? "" : ", ") + row.name;
    std::string layers;
    for (const shadows::LayerModule* layer : shadows::allLayers())
        layers += (layers.empty() ? "" : ", ") + std::string(layer->name);
    return fmt::format("{}; each may take +LAYER: {}", names, layers);
}

// `row` with the layers named after it in `item` ("pcf[box3]+contact").
TechniqueRow withLayers(TechniqueRow row, const std::vector<std::string>& layers) {
    for (const std::string& layer : layers) {
        row.name += "+" + layer;
        row.layers.push_back(layer);
    }
    return row;
}

} // namespace

std::vector<TechniqueRow> comparisonRows(std::string_view list) {
    const std::vector<TechniqueRow> all = variantRows();
    if (list.empty()) {
        std::vector<TechniqueRow> rows = all;
        for (const shadows::LayerModule* layer : shadows::allLayers())
            for (std::string_view base : layer->rows)
                for (const TechniqueRow& row : all)
                    if (row.name == base)
                        rows.push_back(withLayers(row, {std::string(layer->name)}));
        return rows;
    }
    std::vector<TechniqueRow> rows;
    size_t start = 0;
    while (start <= list.size()) {
        const size_t comma = std::min(list.find(',', start), list.size());
        std::string_view item = list.substr(start, comma - start);
        start = comma + 1;
        if (item.empty())
            continue;
        // "row+layer+layer": the row, then its layers in order.
        std::vector<std::string> layers;
        if (const size_t plus = item.find('+'); plus != std::string_view::npos) {
            std::string_view rest = item.substr(plus + 1);
            for (size_t next = 0; next != std::string_view::npos; rest = rest.substr(next + 1)) {
                next = rest.find('+');
                const std::string_view name = rest.substr(0, next);
                if (!shadows::findLayer(name)) {
                    std::vector<std::string_view> names;
                    for (const shadows::LayerModule* layer : shadows::allLayers())
                        names.push_back(layer->name);
                    throw InputError("--techniques",
                                     fmt::format("unknown layer '{}' in '{}' (layers: {})", name,
                                                 item, fmt::join(names, ", ")));
                }
                if (std::find(layers.begin(), layers.end(), name) != layers.end())
                    throw InputError("--techniques",
                                     fmt::format("'{}' names the layer '{}' twice", item, name));
                layers.emplace_back(name);
                if (next == std::string_view::npos)
                    break;
            }
            item = item.substr(0, plus);
        }
        bool found = false;
        for (const TechniqueRow& row : all)
            if (row.name == item || row.name.starts_with(std::string(item) + "[")) {
                found = true;
                const TechniqueRow layered = withLayers(row, layers);
                // A technique's name brings all its rows: a row named again is not repeated.
                if (std::none_of(rows.begin(), rows.end(),
                                 [&](const TechniqueRow& r) { return r.name == layered.name; }))
                    rows.push_back(layered);
            }
        if (!found)
            throw InputError("--techniques", fmt::format("unknown technique or variant '{}' "
                                                         "(available: {})",
                                                         item, rowNames(all)));
    }
    if (rows.empty())
        throw InputError("--techniques", "the list is empty");
    return rows;
}

void applyRow(const TechniqueRow& row, ParameterValues& params, double sceneRadius) {
    for (const auto& [key, value] : row.sets)
        params.set(key, value);
    // A row runs exactly the layers it names: the caller's settings configure those.
    for (const shadows::LayerModule* layer : shadows::allLayers()) {
        const bool named =
            std::find(row.layers.begin(), row.layers.end(), layer->name) != row.layers.end();
        if (!named)
            params.set(layer->off.first, layer->off.second);
        else if (!layer->enabled(params) && layer->rowSettings)
            for (const auto& [key, value] : layer->rowSettings(sceneRadius))
                params.set(key, value);
    }
}

ParameterValues::ParameterValues() {
    for (const ParameterInfo& p : parameterTable())
        mValues.emplace(p.key, p.defaultValue);
}

void ParameterValues::set(std::string_view key, std::string_view value) {
    const ParameterInfo* p = findParameter(key);
    if (!p)
        throw InputError("--set",
                         fmt::format("unknown parameter '{}' (known: {})", key, knownKeys()));
    mValues.find(key)->second = parseValue(*p, value);
    mSet.emplace(key);
}

void ParameterValues::assign(std::string_view keyEqualsValue) {
    const size_t eq = keyEqualsValue.find('=');
    if (eq == std::string_view::npos || eq == 0)
        throw InputError("--set", fmt::format("'{}': expected key=value", keyEqualsValue));
    set(keyEqualsValue.substr(0, eq), keyEqualsValue.substr(eq + 1));
}

double ParameterValues::number(std::string_view key) const {
    const auto it = mValues.find(key);
    PENUMBRA_CHECK(it != mValues.end(), "unregistered parameter " + std::string(key));
    return it->second;
}

std::string ParameterValues::text(std::string_view key) const {
    const ParameterInfo* p = findParameter(key);
    PENUMBRA_CHECK(p != nullptr, "unregistered parameter " + std::string(key));
    const double v = number(key);
    if (p->type == ParameterType::Bool)
        return v != 0.0 ? "true" : "false";
    if (p->type == ParameterType::Choice)
        return std::string(p->choices[static_cast<size_t>(v)]);
    return fmt::format("{}", v);
}

void validate(const RenderOptions& o) {
    if (o.width == 0)
        throw InputError("--width", "must be at least 1");
    if (o.height == 0)
        throw InputError("--height", "must be at least 1");
    if (o.shadowMapSize < 16)
        throw InputError("--shadow-map-size",
                         fmt::format("{} is too small (minimum 16)", o.shadowMapSize));
    if (o.frames == 0)
        throw InputError("--frames", "must be at least 1");
    if (o.frames > 10000)
        throw InputError("--frames", "at most 10000");
    if (o.lightRadiusOverride >= 0.0f && !std::isfinite(o.lightRadiusOverride))
        throw InputError("--light-radius", "not a finite number");
    if (o.lightAngleOverride > 30.0f)
        throw InputError("--light-angle", "at most 30 degrees");
}

} // namespace penumbra
