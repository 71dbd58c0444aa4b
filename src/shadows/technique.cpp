// The module list and what the frame asks of any module.
#include "shadows/technique.h"

#include "penumbra/error.h"

#include <cmath>

namespace penumbra::shadows {

uint32_t bytesPerTexel(MapFormat format) {
    switch (format) {
    case MapFormat::Depth32:
    case MapFormat::R32F:
        return 4;
    case MapFormat::RG32F:
        return 8;
    case MapFormat::RGBA32F:
        break;
    }
    return 16;
}

std::span<const TechniqueModule* const> allModules() {
    static const TechniqueModule* const modules[] = {
        &hardModule(), &pcfModule(),  &pcssModule(),  &secondDepthModule(), &vsmModule(),
        &esmModule(),  &evsmModule(), &savsmModule(), &msmModule()};
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
    return {{.name = "rows", .format = format}, {.name = output, .format = format}};
}

std::vector<PostPassDecl> GaussianBlur::passes() const {
    return {{.shader = rowsShader, .inputs = {kDepthMap}, .outputs = {"rows"}},
            {.shader = columnsShader, .inputs = {"rows"}, .outputs = {output}}};
}

double GaussianBlur::radiusTexels(const ParameterValues& p) const {
    return 0.5 * (p.number(sizeKey) - 1.0) + 1.0;
}

const TechniqueModule& moduleOf(Technique technique) {
    for (const TechniqueModule* m : allModules())
        if (m->info.id == technique)
            return *m;
    fatal(__FILE__, __LINE__, "moduleOf: unregistered technique");
}

uint64_t shadowMapBytes(const TechniqueModule& module, uint32_t size) {
    uint64_t perTexel = bytesPerTexel(MapFormat::Depth32);
    for (const MapDecl& map : module.maps)
        perTexel += bytesPerTexel(map.format);
    return perTexel * size * size;
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
    if (module.constants)
        for (const SpecConstant& c : module.constants(params))
            constants.push_back(c);
    return constants;
}

} // namespace penumbra::shadows
