// The module list and what the frame asks of any module.
#include "shadows/technique.h"

#include "bias.h"
#include "bindings.h"
#include "moments.h"
#include "penumbra/error.h"
#include "shadows/poisson.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {

uint32_t bytesPerTexel(MapFormat format) {
    switch (format) {
    case MapFormat::Depth32:
    case MapFormat::R32F:
    case MapFormat::R32UI:
        return 4;
    case MapFormat::RG32F:
    case MapFormat::RG32UI:
    case MapFormat::RGBA16:
        return 8;
    case MapFormat::RGBA32F:
    case MapFormat::RGBA32UI:
        break;
    }
    return 16;
}

bool holdsIntegers(MapFormat format) {
    return format == MapFormat::R32UI || format == MapFormat::RG32UI ||
           format == MapFormat::RGBA32UI;
}

std::span<const TechniqueModule* const> allModules() {
    static const TechniqueModule* const modules[] = {
#define PENUMBRA_TECHNIQUE(id, Name, module, shader) &module##Module(),
#include "technique_list.h"
    };
    return modules;
}

ParameterInfo GaussianBlur::sizeParameter() const {
    return {.key = sizeKey,
            .type = ParameterType::Int,
            .defaultValue = 7,
            .min = 1,
            .max = 63,
            .unit = "texels (odd)",
            .description = "taps of the separable Gaussian blur (sigma = size / 6; 1: no blur, "
                           "bilinear interpolation only)",
            .oddOnly = true};
}

std::vector<MapDecl> GaussianBlur::maps() const {
    return {{.name = "rows", .format = format},
            {.name = output, .format = format, .formatFor = outputFormatFor}};
}

std::vector<PostPassDecl> GaussianBlur::passes() const {
    return {{.shader = rowsShader, .inputs = {kDepthMap}, .outputs = {"rows"}},
            {.shader = columnsShader, .inputs = {"rows"}, .outputs = {output}}};
}

double GaussianBlur::radiusTexels(const ParameterValues& p) const {
    return 0.5 * (p.number(sizeKey) - 1.0) + 1.0;
}

std::vector<MapDecl> SummedAreaTable::maps() const {
    return {{.name = "rowSums", .format = format}, {.name = kMomentTable, .format = format}};
}

std::vector<PostPassDecl> SummedAreaTable::passes() const {
    return {{.shader = rowsShader,
             .inputs = {kDepthMap},
             .outputs = {"rowSums"},
             .dispatch = PostDispatch::Lines},
            {.shader = columnsShader,
             .inputs = {"rowSums"},
             .outputs = {kMomentTable},
             .dispatch = PostDispatch::Lines}};
}

ParameterInfo cubeRadiusParameter(std::string_view key) {
    // 96 by measurement under close bulbs (docs/techniques.md, "Soft shadows against the truth").
    return {.key = key,
            .type = ParameterType::Float,
            .defaultValue = 96.0,
            .min = 1.0,
            .max = 256.0,
            .unit = "texels",
            .description = "the same on a point light's cube faces, where no coarser view takes "
                           "over a wider kernel (also their guard band)"};
}

std::vector<ParameterInfo> SoftSearch::parameters() const {
    return {{.key = maxRadiusKey,
             .type = ParameterType::Float,
             .defaultValue = 64.0,
             .min = 1.0,
             .max = 256.0,
             .unit = "texels",
             .description = "largest blocker-search and filter half-width, in texels of the map "
                            "sampled on spots and a sun's cascades (also the cascades' guard band; "
                            "wider boxes leave the table fewer fixed-point bits)"},
            cubeRadiusParameter(cubeRadiusKey),
            {.key = subdivisionKey,
             .type = ParameterType::Int,
             .defaultValue = static_cast<double>(defaultSubdivision),
             .min = 1,
             .max = VSSM_MAX_SUBDIVISION,
             .unit = "sub-kernels per axis",
             .description = "kernel subdivision for non-planar receivers: the search and filter "
                            "boxes are cut into n x n sub-kernels, each bounded on its own against "
                            "the receiver's plane (1: the whole box at once)"},
            {.key = refineKey,
             .type = ParameterType::Bool,
             .defaultValue = 1,
             .description = "search again over the region where blockers at the first estimate's "
                            "depth can hide the light (the penumbra's own box), so blockers far "
                            "off to the side do not widen it"}};
}

gpu::SoftParams SoftSearch::pack(const ParameterValues& p) const {
    const double cap = p.number(maxRadiusKey), cubeCap = p.number(cubeRadiusKey);
    // One table scale for every view: the widest box either cap allows.
    return {.maxRadius = static_cast<float>(cap),
            .tableScale = fixedPointScale(2.0 * std::max(cap, cubeCap)),
            .subdivision = static_cast<uint32_t>(p.number(subdivisionKey)),
            .refine = p.number(refineKey) != 0.0 ? 1u : 0u,
            .cubeRadius = static_cast<float>(cubeCap)};
}

double SoftSearch::radiusTexels(const ParameterValues& p) const {
    return p.number(maxRadiusKey) + 1.0;
}

double SoftSearch::cubeRadiusTexels(const ParameterValues& p) const {
    return p.number(cubeRadiusKey) + 1.0;
}

float fixedPointScale(double widestBox) {
    const double hull = std::ceil(widestBox) + 2.0;
    // Sums under 2^31 in magnitude (boxFromCorners reads them signed); at most 2^24 steps, where
    // a float still holds every integer, so quantising is exact.
    return static_cast<float>(std::min(std::floor(2147483647.0 / (hull * hull)), 16777216.0));
}

const TechniqueModule& moduleOf(Technique technique) {
    for (const TechniqueModule* m : allModules())
        if (m->info.id == technique)
            return *m;
    fatal(__FILE__, __LINE__, "moduleOf: unregistered technique");
}

void setSharedSettings(gpu::FrameData& f, const TechniqueModule& module, const ParameterValues& p,
                       bool hardwareDepthFilter, uint32_t subTexelBits) {
    auto index = [&](const char* key) { return static_cast<uint32_t>(p.number(key)); };
    f.biasMode = {index("bias.receiver"), hardwareDepthFilter ? 1u : 0u, subTexelBits,
                  index("bias.mode")};
    // Corrections bring a tap's reference depth nearer the light (negative) up to the clamp;
    // with bias.receiverSides=near none may push it away (see docs/techniques.md).
    const auto limit = static_cast<float>(p.number("bias.receiverClamp"));
    f.biasParams = {-limit, index("bias.receiverSides") == 0 ? limit : 0.0f,
                    static_cast<float>(p.number("bias.adaptive")),
                    static_cast<float>(p.number("bias.curvature"))};
    f.filterLimits = {static_cast<float>(searchCapTexels(module, p)),
                      static_cast<float>(p.number("bias.crease")), 0.0f, 0.0f};
    const auto& disk = poissonDisk();
    for (size_t i = 0; i < kPoissonPoints / 2; ++i)
        f.poisson[i] = {disk[2 * i].x, disk[2 * i].y, disk[2 * i + 1].x, disk[2 * i + 1].y};
}

FilterSettings filterSettings(const TechniqueModule& module, const ParameterValues& params,
                              bool hardwareDepthFilter, uint32_t subTexelBits) {
    FilterSettings s;
    setSharedSettings(s.frame, module, params, hardwareDepthFilter, subTexelBits);
    if (module.pack)
        module.pack(params, s.params);
    return s;
}

float ShadowMapView::texel(int i, int j) const {
    const int last = static_cast<int>(size) - 1;
    return depth[static_cast<size_t>(std::clamp(j, 0, last)) * size +
                 static_cast<size_t>(std::clamp(i, 0, last))];
}

void MarginTracker::see(float a, float b) const {
    if (margin)
        *margin = std::min(*margin, std::abs(a - b));
}

namespace {

glm::vec4 evaluateReference(Technique technique, const ShadowMapView& map, const FilterProbe& probe,
                            const FilterSettings& s, const gpu::ShadowViewData& view,
                            MarginTracker margins) {
    const TechniqueModule& module = moduleOf(technique);
    if (!module.reference)
        throw InputError(std::string(module.info.name),
                         "it traces a distance field: there is no shadow-map filter to evaluate");
    return module.reference({.map = map,
                             .probe = probe,
                             .frame = s.frame,
                             .params = s.params,
                             .view = view,
                             .margins = margins});
}

} // namespace

glm::vec4 techniqueReference(Technique technique, const ShadowMapView& map,
                             const FilterProbe& probe, const FilterSettings& settings,
                             const gpu::ShadowViewData& view) {
    return evaluateReference(technique, map, probe, settings, view, {});
}

float smallestComparisonMargin(Technique technique, const ShadowMapView& map,
                               const FilterProbe& probe, const FilterSettings& settings,
                               const gpu::ShadowViewData& view) {
    float margin = 1e30f;
    evaluateReference(technique, map, probe, settings, view, MarginTracker{&margin});
    return margin;
}

MapFormat formatOf(const MapDecl& map, const ParameterValues& params) {
    return map.formatFor ? map.formatFor(params) : map.format;
}

bool mipmappedOf(const MapDecl& map, const ParameterValues& params) {
    return map.mipmappedFor && map.mipmappedFor(params);
}

VisibilitySlots visibilitySlots(const TechniqueModule& module, const ParameterValues& params) {
    VisibilitySlots slots;
    slots.floats.fill(kDepthMap);
    size_t floats = 0, integers = 0;
    for (std::string_view name : module.visibilityMaps) {
        bool integer = false; // the depth map's format is Depth32
        if (name != kDepthMap) {
            // Last frame's version has its map's format.
            const bool previous = name.ends_with(kPreviousMapSuffix);
            const std::string_view own =
                previous ? name.substr(0, name.size() - kPreviousMapSuffix.size()) : name;
            const auto map = std::find_if(module.maps.begin(), module.maps.end(),
                                          [&](const MapDecl& m) { return m.name == own; });
            PENUMBRA_CHECK(map != module.maps.end(),
                           std::string(module.info.name) +
                               " reads a map it does not declare: " + std::string(name));
            PENUMBRA_CHECK(!previous || map->history,
                           std::string(module.info.name) + " reads last frame's " +
                               std::string(own) + ", declared without history");
            integer = holdsIntegers(formatOf(*map, params));
        }
        size_t& used = integer ? integers : floats;
        PENUMBRA_CHECK(used < TECH_MAX_MAPS, std::string(module.info.name) +
                                                 " reads more maps of a kind than TECH_MAX_MAPS");
        (integer ? slots.integers : slots.floats)[used++] = name;
    }
    slots.readsDepthMap =
        floats == 0 || std::find(slots.floats.begin(), slots.floats.end(), kDepthMap) !=
                           slots.floats.begin() + static_cast<std::ptrdiff_t>(floats);
    if (!slots.readsDepthMap)
        std::fill(slots.floats.begin() + static_cast<std::ptrdiff_t>(floats), slots.floats.end(),
                  slots.floats[0]);
    return slots;
}

std::string techniquesWhere(bool (*property)(const TechniqueModule&)) {
    std::vector<std::string_view> names;
    for (const TechniqueModule* module : allModules())
        if (property(*module))
            names.push_back(module->info.name);
    std::string list;
    for (size_t i = 0; i < names.size(); ++i) {
        const bool last = i + 1 == names.size();
        list += i == 0 ? "" : last ? " and " : ", ";
        list += names[i];
    }
    return list.empty() ? "none" : list;
}

std::vector<ScreenPassDecl> screenPassesOf(const TechniqueModule& module,
                                           const ParameterValues& params) {
    if (!module.screenPasses)
        return {};
    std::vector<ScreenPassDecl> passes = module.screenPasses(params);
    const std::string name(module.info.name);
    for (size_t i = 0; i < passes.size(); ++i) {
        const ScreenPassDecl& pass = passes[i];
        PENUMBRA_CHECK(pass.results.empty() || pass.results == kScreenScratch,
                       name + ": a screen pass binds an image the frame does not make: " +
                           std::string(pass.results));
        if (!pass.fillsCheckerboard)
            continue;
        PENUMBRA_CHECK(i == 0, name + ": a checkerboard's fill comes first");
        PENUMBRA_CHECK(!pass.parameter.empty() && !pass.runsFor,
                       name +
                           ": a checkerboard's fill names its parameter and runs for every light");
    }
    return passes;
}

const ScreenPassDecl* checkerboardFill(std::span<const ScreenPassDecl> passes) {
    return !passes.empty() && passes.front().fillsCheckerboard ? &passes.front() : nullptr;
}

bool drawsLightMaps(const TechniqueModule& module) {
    return !module.visibilityMaps.empty();
}

uint32_t drawnMapSize(const TechniqueModule& module, uint32_t shadowMapSize) {
    return drawsLightMaps(module) ? shadowMapSize : 1u;
}

uint64_t shadowMapBytes(const TechniqueModule& module, uint32_t size,
                        const ParameterValues& params) {
    if (!drawsLightMaps(module))
        return 0; // a field's memory is the scene's (src/render/distance_field.h)
    const uint64_t texels = uint64_t{size} * size;
    uint64_t bytes = bytesPerTexel(MapFormat::Depth32) * texels;
    for (const MapDecl& map : module.maps) {
        const uint32_t side = std::max(size >> map.shrink, 1u);
        uint64_t chain = 0; // the texels of a full mip chain
        for (uint32_t level = 0; (side >> level) > 0; ++level)
            chain += uint64_t{side >> level} * (side >> level);
        const uint64_t level0 = uint64_t{side} * side;
        // A map kept with history is held twice: this frame's and last frame's.
        bytes += (map.history ? 2u : 1u) * bytesPerTexel(formatOf(map, params)) *
                 (mipmappedOf(map, params) ? chain : level0);
    }
    return bytes;
}

std::pair<double, double> blurRadii(const TechniqueModule& module, const ParameterValues& params) {
    return {module.blurRadiusTexels ? module.blurRadiusTexels(params) : 0.0,
            module.cubeRadiusTexels ? module.cubeRadiusTexels(params) : -1.0};
}

double widestRadiusTexels(const TechniqueModule& module, const ParameterValues& params) {
    const auto [views, cubeFaces] = blurRadii(module, params); // cubeFaces -1: none
    return std::max(views, cubeFaces);
}

double searchCapTexels(const TechniqueModule& module, const ParameterValues& params) {
    return module.blockerSearchKey.empty() ? 0.0 : params.number(module.blockerSearchKey);
}

double readReachTexels(const TechniqueModule& module, const ParameterValues& params) {
    return std::max({widestRadiusTexels(module, params), 1.0, searchCapTexels(module, params)});
}

namespace {
// A footprint's guard: a bilinear tap reads 1.5 texels past its centre; the normal offset moves
// the receiver up to bias.normal texels after its face was chosen.
uint32_t guardTexelsOf(double footprint, const ParameterValues& params) {
    return static_cast<uint32_t>(std::ceil(footprint) + 2.0 +
                                 std::ceil(params.number("bias.normal")));
}
} // namespace

uint32_t viewGuardTexels(const TechniqueModule& module, const ParameterValues& params,
                         bool cubeFace) {
    const double footprint = cubeFace && module.cubeRadiusTexels ? module.cubeRadiusTexels(params)
                             : module.blurRadiusTexels           ? module.blurRadiusTexels(params)
                                                                 : 0.0;
    return guardTexelsOf(footprint, params);
}

GuardBand viewGuardBand(const TechniqueModule& module, const ParameterValues& params,
                        const Light& light) {
    const uint32_t widest = viewGuardTexels(module, params, light.type == LightType::Point);
    if (!module.footprintFollowsLight)
        return widest;
    const float size = light.type == LightType::Directional
                           ? std::tan(0.5f * glm::radians(light.angularDiameter))
                           : light.radius;
    return {widest, size, guardTexelsOf(0.5, params)}; // one tap, as hard's
}

std::vector<SpecConstant> visibilityConstants(const TechniqueModule& module,
                                              const ParameterValues& params) {
    std::vector<SpecConstant> constants{
        {SPEC_TECHNIQUE, static_cast<uint32_t>(module.info.id)},
        {SPEC_RECEIVER, static_cast<uint32_t>(params.number("bias.receiver"))}};
    const auto horizon = static_cast<uint32_t>(params.number("bias.horizon"));
    constants.push_back(
        {SPEC_HORIZON,
         horizon == HORIZON_ALL || (horizon == HORIZON_SOFT && module.modelsLightSize) ? 1u : 0u});
    constants.push_back({SPEC_CASCADE_BLEND, params.number("csm.blend") > 0.0 ? 1u : 0u});
    constants.push_back(
        {SPEC_ADAPTIVE_BIAS, params.number("bias.mode") == BIAS_ADAPTIVE ? 1u : 0u});
    constants.push_back(
        {SPEC_VIRTUAL,
         module.readsVirtualMaps && params.number("virtual.enabled") != 0.0 ? 1u : 0u});
    const size_t shared = constants.size();
    if (module.constants)
        for (const SpecConstant& c : module.constants(params)) {
            for (size_t i = 0; i < shared; ++i)
                PENUMBRA_CHECK(constants[i].id != c.id, std::string(module.info.name) +
                                                            " sets a shared specialization "
                                                            "constant, id " +
                                                            std::to_string(c.id));
            constants.push_back(c);
        }
    return constants;
}

} // namespace penumbra::shadows
