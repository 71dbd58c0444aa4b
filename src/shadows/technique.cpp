// The module list and what the frame asks of any module.
#include "shadows/technique.h"

#include "bias.h"
#include "moments.h"
#include "bindings.h"
#include "penumbra/error.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {

static_assert(TECHNIQUE_HARD == uint32_t(Technique::Hard) &&
                  TECHNIQUE_PCF == uint32_t(Technique::Pcf) &&
                  TECHNIQUE_PCSS == uint32_t(Technique::Pcss) &&
                  TECHNIQUE_SECOND_DEPTH == uint32_t(Technique::SecondDepth) &&
                  TECHNIQUE_VSM == uint32_t(Technique::Vsm) &&
                  TECHNIQUE_ESM == uint32_t(Technique::Esm) &&
                  TECHNIQUE_EVSM == uint32_t(Technique::Evsm) &&
                  TECHNIQUE_SAVSM == uint32_t(Technique::Savsm) &&
                  TECHNIQUE_MSM == uint32_t(Technique::Msm) &&
                  TECHNIQUE_VSSM == uint32_t(Technique::Vssm) &&
                  TECHNIQUE_MSM_SOFT == uint32_t(Technique::MsmSoft) &&
                  TECHNIQUE_SDF == uint32_t(Technique::Sdf),
              "the visibility pass's technique ids are penumbra::Technique's");

uint32_t bytesPerTexel(MapFormat format) {
    switch (format) {
    case MapFormat::Depth32:
    case MapFormat::R32F:
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
    return format == MapFormat::RG32UI || format == MapFormat::RGBA32UI;
}

std::span<const TechniqueModule* const> allModules() {
    static const TechniqueModule* const modules[] = {
        &hardModule(), &pcfModule(),  &pcssModule(),    &secondDepthModule(),
        &vsmModule(),  &esmModule(),  &evsmModule(),    &savsmModule(),
        &msmModule(),  &vssmModule(), &msmSoftModule(), &sdfModule()};
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

std::vector<ParameterInfo> SoftSearch::parameters() const {
    return {{.key = maxRadiusKey,
             .type = ParameterType::Float,
             .defaultValue = 64.0,
             .min = 1.0,
             .max = 256.0,
             .unit = "texels",
             .description = "largest blocker-search and filter half-width, in texels of the map "
                            "sampled (also the guard band of cube faces and cascades; wider boxes "
                            "leave the table fewer fixed-point bits)"},
            {.key = subdivisionKey,
             .type = ParameterType::Int,
             .defaultValue = 3,
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

SoftSearch::Packed SoftSearch::pack(const ParameterValues& p) const {
    const double cap = p.number(maxRadiusKey);
    return {.maxRadius = static_cast<float>(cap),
            .subdivision = static_cast<uint32_t>(p.number(subdivisionKey)),
            .refine = p.number(refineKey) != 0.0 ? 1u : 0u,
            .tableScale = fixedPointScale(2.0 * cap)};
}

double SoftSearch::radiusTexels(const ParameterValues& p) const {
    return p.number(maxRadiusKey) + 1.0;
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

MapFormat formatOf(const MapDecl& map, const ParameterValues& params) {
    return map.formatFor ? map.formatFor(params) : map.format;
}

bool mipmappedOf(const MapDecl& map, const ParameterValues& params) {
    return map.mipmappedFor && map.mipmappedFor(params);
}

uint64_t shadowMapBytes(const TechniqueModule& module, uint32_t size,
                        const ParameterValues& params) {
    if (module.tracesField)
        return 0; // no shadow map: the field's memory is the scene's (src/render/distance_field.h)
    const uint64_t texels = uint64_t{size} * size;
    uint64_t chain = 0; // the texels of a full mip chain
    for (uint32_t level = 0; (size >> level) > 0; ++level)
        chain += uint64_t{size >> level} * (size >> level);
    uint64_t bytes = bytesPerTexel(MapFormat::Depth32) * texels;
    for (const MapDecl& map : module.maps)
        bytes += bytesPerTexel(formatOf(map, params)) * (mipmappedOf(map, params) ? chain : texels);
    return bytes;
}

uint32_t viewGuardTexels(const TechniqueModule& module, const ParameterValues& params) {
    const double footprint = module.blurRadiusTexels ? module.blurRadiusTexels(params) : 0.0;
    // A bilinear tap reads 1.5 texels past its centre; the normal offset moves the receiver up to
    // bias.normal texels after its face was chosen.
    return static_cast<uint32_t>(std::ceil(footprint) + 2.0 +
                                 std::ceil(params.number("bias.normal")));
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
    if (module.constants)
        for (const SpecConstant& c : module.constants(params))
            constants.push_back(c);
    return constants;
}

} // namespace penumbra::shadows
