// The module list and what the frame asks of any module.
#include "shadows/technique.h"

#include "penumbra/error.h"

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
    static const TechniqueModule* const modules[] = {&hardModule(), &pcfModule(), &pcssModule(),
                                                     &secondDepthModule()};
    return modules;
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
