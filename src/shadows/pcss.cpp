// Technique `pcss` [Fernando 2005]: a blocker search over the light's extent, a penumbra
// estimate from similar triangles, then Poisson PCF of that width (contact hardening). Shader:
// shaders/include/shadow_pcss.glsl; CPU mirror: src/reference/filter_reference.cpp; derivations
// in docs/techniques.md.
#include "shadows/technique.h"

namespace penumbra::shadows {

const TechniqueModule& pcssModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Pcss,
                 .name = "pcss",
                 .summary =
                     "percentage-closer soft shadows: blocker search, penumbra estimate, PCF of "
                     "that width (contact hardening)",
                 .reference = "Fernando 2005, 'Percentage-closer soft shadows'",
                 .families = {"bias", "pcss", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "fast",
                               .sets = {{"pcss.blockerSamples", "8"},
                                        {"pcss.filterSamples", "16"}}}}},
        .parameters =
            {{.key = "pcss.blockerSamples",
              .type = ParameterType::Int,
              .defaultValue = 24,
              .min = 1,
              .max = 64,
              .unit = "gathers (4 texels each)",
              .description = "blocker-search taps on a Poisson disk over the search region"},
             {.key = "pcss.filterSamples",
              .type = ParameterType::Int,
              .defaultValue = 48,
              .min = 1,
              .max = 64,
              .description = "PCF taps (bilinear, Poisson disk) over the estimated penumbra"},
             {.key = "pcss.maxRadius",
              .type = ParameterType::Float,
              .defaultValue = 40.0,
              .min = 1.0,
              .max = 256.0,
              .unit = "texels",
              .description = "largest blocker-search and filter radius, in texels of the map "
                             "sampled (a sun's PCSS "
                             "moves to a coarser cascade rather than clip)"},
             {.key = "pcss.rotation",
              .type = ParameterType::Choice,
              .defaultValue = 2,
              .choices = {std::begin(gpu::kRotationChoices), std::end(gpu::kRotationChoices)},
              .description = "per-pixel rotation of both Poisson disks"}},
        .pack =
            [](const ParameterValues& p, gpu::FrameData& f) {
                auto choice = [&](const char* key) { return static_cast<uint32_t>(p.number(key)); };
                f.pcssMode = {choice("pcss.blockerSamples"), choice("pcss.filterSamples"),
                              choice("pcss.rotation"), 0u};
                f.pcssParams = {static_cast<float>(p.number("pcss.maxRadius")), 0.0f, 0.0f, 0.0f};
            },
        .modelsLightSize = true,
        .blurRadiusTexels =
            [](const ParameterValues& p) { return p.number("pcss.maxRadius") + 1.0; }};
    return module;
}

} // namespace penumbra::shadows
