// Technique `pcf` [Reeves, Salesin, Cook 1987]: the fraction of shadow-map tests a kernel passes,
// every kernel built from bilinear comparison taps; edge-only PCF [Isidoro 2006]. Shader:
// shaders/include/shadow_pcf.glsl (the kernel is the specialization constant FILTER), its block
// shaders/include/params_pcf.h; its CPU mirror is pcfReference below.
#include "bias.h"
#include "params_pcf.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_filters.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

uint32_t choice(const ParameterValues& p, const char* key) {
    return static_cast<uint32_t>(p.number(key));
}

float number(const ParameterValues& p, const char* key) {
    return static_cast<float>(p.number(key));
}

// [Isidoro 2006]: four taps at the kernel's corners decide when they agree fully.
bool probeDecides(const FilterInput& in, const gpu::PcfParams& p, const CpuReceiver& r,
                  glm::vec2 dzRange, float& result) {
    const float reach = p.kernel == FILTER_POISSON ? p.radius * 0.70710678f
                                                   : 0.5f * static_cast<float>(p.size - 1u);
    const float size = static_cast<float>(in.map.size);
    const glm::vec2 centre = r.uv * size;
    const MarginTracker& m = in.margins;
    const float sum = bilinearTap(in.map, centre + glm::vec2(-reach, -reach), size, r, dzRange, m) +
                      bilinearTap(in.map, centre + glm::vec2(reach, -reach), size, r, dzRange, m) +
                      bilinearTap(in.map, centre + glm::vec2(-reach, reach), size, r, dzRange, m) +
                      bilinearTap(in.map, centre + glm::vec2(reach, reach), size, r, dzRange, m);
    result = sum * 0.25f;
    return sum == 0.0f || sum == 4.0f;
}

// shadowPcfUnsnapped, transcribed (a probe's kernel scale is 1).
float pcfUnsnapped(const FilterInput& in) {
    const gpu::PcfParams p = in.params.get<gpu::PcfParams>();
    const gpu::FrameData& f = in.frame;
    const CpuReceiver r = receiverOf(in.probe);
    const glm::vec2 dzRange(f.biasParams.x, f.biasParams.y);
    const float size = static_cast<float>(in.map.size);
    if (p.kernel == FILTER_HARDWARE) {
        const float lift =
            f.biasMode.w == BIAS_ADAPTIVE ? gpu::footprintLift(r.gradient, size, -dzRange.x) : 0.0f;
        return bilinearTap(in.map, r.uv * size, size,
                           CpuReceiver{r.uv, r.depth - lift, glm::vec2(0.0f)}, dzRange, in.margins,
                           f.biasMode.y != 0u ? f.biasMode.z : 0u);
    }
    float early = 0.0f;
    if (p.edgeOnly != 0u && p.kernel != FILTER_BILINEAR && probeDecides(in, p, r, dzRange, early))
        return early;
    if (p.kernel == FILTER_POISSON)
        return poissonTaps(in.map, r, f, p.samples, p.radius,
                           gpu::rotationTurns(p.rotation, in.probe.pixel), dzRange, in.margins);
    const int n = p.kernel == FILTER_BILINEAR ? 1 : static_cast<int>(p.size);
    return pcfGrid(in.map, r, p.kernel, n, p.sigma, dzRange, in.margins);
}

glm::vec4 pcfReference(const FilterInput& in) {
    return {gpu::snapToExtremes(pcfUnsnapped(in)), 0.0f, 0.0f, 0.0f};
}

} // namespace

const TechniqueModule& pcfModule() {
    static const TechniqueModule module{
        .info =
            {.id = Technique::Pcf,
             .name = "pcf",
             .summary =
                 "percentage-closer filtering: the fraction of shadow-map tests a kernel passes",
             .reference = "Reeves, Salesin, Cook 1987, 'Rendering antialiased shadows with depth "
                          "maps'; Isidoro 2006 (edge-only PCF); Tuft 2010 (receiver-plane bias)",
             .families = {"bias", "pcf", "csm", "composite"},
             // The defaults first (box 5x5), as every technique's row of its defaults.
             .variants =
                 {{.label = ""},
                  {.label = "bilinear", .sets = {{"pcf.filter", "bilinear"}}},
                  {.label = "hardware", .sets = {{"pcf.filter", "hardware"}}},
                  {.label = "box3", .sets = {{"pcf.filter", "box"}, {"pcf.size", "3"}}},
                  {.label = "box7", .sets = {{"pcf.filter", "box"}, {"pcf.size", "7"}}},
                  {.label = "box11", .sets = {{"pcf.filter", "box"}, {"pcf.size", "11"}}},
                  {.label = "gauss7", .sets = {{"pcf.filter", "gaussian"}, {"pcf.size", "7"}}},
                  {.label = "poisson16",
                   .sets = {{"pcf.filter", "poisson"}, {"pcf.samples", "16"}}},
                  {.label = "poisson32",
                   .sets = {{"pcf.filter", "poisson"}, {"pcf.samples", "32"}}},
                  {.label = "adaptive-box7",
                   .sets = {{"pcf.filter", "box"}, {"pcf.size", "7"}, {"pcf.adaptive", "true"}}}}},
        .parameters =
            {{.key = "pcf.filter",
              .type = ParameterType::Choice,
              .defaultValue = 2,
              .choices = {std::begin(gpu::kFilterChoices), std::end(gpu::kFilterChoices)},
              .description = "kernel: bilinear 4-tap, one hardware comparison tap, box or Gaussian "
                             "NxN of bilinear taps, or a rotated Poisson disk of bilinear taps"},
             {.key = "pcf.size",
              .type = ParameterType::Int,
              .defaultValue = 5,
              .min = 3,
              .max = 15,
              .unit = "texels (odd)",
              .description = "box and Gaussian kernel width N (N x N taps)",
              .oddOnly = true},
             {.key = "pcf.sigma",
              .type = ParameterType::Float,
              .defaultValue = 0.0,
              .min = 0.0,
              .max = 16.0,
              .unit = "texels",
              .description = "Gaussian standard deviation; 0 = size / 4"},
             {.key = "pcf.samples",
              .type = ParameterType::Int,
              .defaultValue = 16,
              .min = 1,
              .max = 64,
              .description = "Poisson-disk taps"},
             {.key = "pcf.radius",
              .type = ParameterType::Float,
              .defaultValue = 2.5,
              .min = 0.5,
              .max = 32.0,
              .unit = "texels",
              .description = "Poisson-disk radius"},
             {.key = "pcf.rotation",
              .type = ParameterType::Choice,
              .defaultValue = 2,
              .choices = {std::begin(gpu::kRotationChoices), std::end(gpu::kRotationChoices)},
              .description = "per-pixel rotation of the Poisson disk: none, a hash, or interleaved "
                             "gradient noise [Jimenez 2014]"},
             {.key = "pcf.adaptive",
              .type = ParameterType::Bool,
              .defaultValue = 0,
              .description =
                  "edge-only PCF [Isidoro 2006]: four corner taps decide whether a pixel "
                  "is near a shadow edge; only then the full kernel runs"}},
        .constants =
            [](const ParameterValues& p) {
                return std::vector<SpecConstant>{{SPEC_FILTER, choice(p, "pcf.filter")}};
            },
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                const uint32_t size = choice(p, "pcf.size");
                const float sigma =
                    number(p, "pcf.sigma") > 0.0f ? number(p, "pcf.sigma") : 0.25f * float(size);
                block.set(gpu::PcfParams{.kernel = choice(p, "pcf.filter"),
                                         .size = size,
                                         .samples = choice(p, "pcf.samples"),
                                         .rotation = choice(p, "pcf.rotation"),
                                         .radius = number(p, "pcf.radius"),
                                         .sigma = sigma,
                                         .edgeOnly = choice(p, "pcf.adaptive")});
            },
        .reference = pcfReference,
        .blurRadiusTexels =
            [](const ParameterValues& p) {
                // A bilinear tap reaches one texel past its centre.
                switch (choice(p, "pcf.filter")) {
                case FILTER_BOX:
                case FILTER_GAUSSIAN:
                    return 0.5 * (p.number("pcf.size") - 1.0) + 1.0;
                case FILTER_POISSON:
                    return p.number("pcf.radius") + 1.0;
                default:
                    return 1.0;
                }
            },
        .readsVirtualMaps = true};
    return module;
}

} // namespace penumbra::shadows
