// Technique `msm` [Peters and Klein 2015, 'Moment shadow mapping']: four moments (z, z^2, z^3,
// z^4) of the depth mapped to [-1, 1], blurred like VSM's (shaders/include/moments_blur.glsl);
// the visibility pass reconstructs the smallest occluded fraction these moments allow (the
// Hamburger problem: momentOcclusion in moments.h, shaders/include/shadow_moments.glsl).
// msm.precision=16: the paper's optimised quantisation in 16-bit unorm maps. Its block:
// params_moments.h; CPU mirror: msmReference below; derivations in docs/techniques.md.
#include <algorithm>

#include "moments.h"
#include "params_moments.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_moments.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

inline constexpr const char* kPrecisions[] = {"32", "16"};

// msm.precision: 32-bit float moments, or the optimised 16-bit quantisation in unorm texels.
MapFormat momentsFormat(const ParameterValues& p) {
    return p.number("msm.precision") == 1.0 ? MapFormat::RGBA16 : MapFormat::RGBA32F;
}

constexpr GaussianBlur kBlur{.sizeKey = "msm.size",
                             .rowsShader = "msm_blur_rows.comp",
                             .columnsShader = "msm_blur_columns.comp",
                             .output = "moments",
                             .format = MapFormat::RGBA32F,
                             .outputFormatFor = momentsFormat};

glm::vec4 storedIn16Bits(glm::vec4 moments) {
    return gpu::msmStore16(moments);
}

// shadowMsmDetail: x visibility, yz the filtered first two moments, w the receiver's depth in
// [-1, 1].
glm::vec4 msmReference(const FilterInput& in) {
    const gpu::MsmParams p = in.params.get<gpu::MsmParams>();
    const bool sixteen = p.bits == 16u;
    glm::vec4 moments = momentsAt(in.map, MOMENTS_MSM, p.size, glm::vec2(0.0f), in.view,
                                  in.probe.uv, sixteen ? &storedIn16Bits : nullptr);
    if (sixteen)
        moments = gpu::msmLoad16(moments);
    const float d = 2.0f * gpu::momentDepth(in.view, in.probe.depth) - 1.0f;
    const float v = std::clamp(1.0f - gpu::momentOcclusion(moments, d, p.momentBias), 0.0f, 1.0f);
    return {gpu::snapToExtremes(v), moments.x, moments.y, d};
}

} // namespace

const TechniqueModule& msmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Msm,
                 .name = "msm",
                 .summary = "moment shadow maps: four blurred depth moments, the smallest "
                            "occluded fraction they allow (little light bleeding)",
                 .reference = "Peters and Klein 2015, 'Moment shadow mapping'",
                 .families = {"bias", "msm", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "16",
                               .sets = {{"msm.precision", "16"}, {"msm.bias", "0.00006"}}}}},
        .parameters = {{.key = "msm.bias",
                        .type = ParameterType::Float,
                        .defaultValue = 3e-5,
                        .min = 0.0,
                        .max = 0.01,
                        .description =
                            "moment bias: the moments are pulled this far towards (0, 0.63, 0, "
                            "0.63), which keeps the reconstruction stable (the paper's 3e-5 "
                            "for 32-bit moments)"},
                       kBlur.sizeParameter(),
                       {.key = "msm.precision",
                        .type = ParameterType::Choice,
                        .defaultValue = 0,
                        .choices = {std::begin(kPrecisions), std::end(kPrecisions)},
                        .unit = "bits",
                        .description =
                            "bits per moment in the blurred map: 32-bit floats, or 16-bit unorm "
                            "under the paper's optimised quantisation (half the memory; raise "
                            "msm.bias to 6e-5 or more)"}},
        .maps = kBlur.maps(),
        .postPasses = kBlur.passes(),
        .visibilityMaps = {"moments"},
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                block.set(
                    gpu::MsmParams{.momentBias = static_cast<float>(p.number("msm.bias")),
                                   .size = static_cast<uint32_t>(p.number("msm.size")),
                                   .bits = momentsFormat(p) == MapFormat::RGBA16 ? 16u : 32u});
            },
        .reference = msmReference,
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
