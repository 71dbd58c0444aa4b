// Technique `msm` [Peters and Klein 2015, 'Moment shadow mapping']: four moments (z, z^2, z^3,
// z^4) of the depth mapped to [-1, 1], blurred like VSM's (shaders/include/moments_blur.glsl);
// the visibility pass reconstructs the smallest occluded fraction these moments allow (the
// Hamburger problem: momentOcclusion in moments.h, shaders/include/shadow_moments.glsl).
// msm.precision=16: the paper's optimised quantisation in 16-bit unorm maps. CPU mirror:
// src/reference/filter_reference.cpp; derivations in docs/techniques.md.
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
        .visibilityMap = "moments",
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                f.msmParams = {static_cast<float>(p.number("msm.bias")),
                               static_cast<float>(p.number("msm.size")),
                               momentsFormat(p) == MapFormat::RGBA16 ? 16.0f : 32.0f, 0.0f};
            },
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
