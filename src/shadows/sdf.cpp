// Technique `sdf`: soft shadows by sphere tracing a signed distance field of the scene towards
// the light [Quilez 2010 'Penumbra shadows in raymarched SDFs', with the closest approach of
// consecutive steps, Aaltonen 2018 'GPU-based clay simulation and ray-tracing tech in Claybook'],
// the open fraction of the light's cone estimated from the nearest miss. No shadow map: the field
// is built once per scene (src/render/distance_field.h, shaders/sdf_*.comp), the tracer is
// shaders/include/shadow_sdf.glsl, their shared maths shaders/include/sdf_math.h; the CPU
// references are src/reference/distance_field.h. Derivations in docs/techniques.md.
#include "params_sdf.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

// The march's smallest step, in voxels: inside a solid the ray keeps going by at least this.
constexpr float kMinStepVoxels = 0.25f;

} // namespace

const TechniqueModule& sdfModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Sdf,
                 .name = "sdf",
                 .summary = "distance-field soft shadows: sphere tracing a signed distance field "
                            "of the scene towards the light, the cone left open from the nearest "
                            "miss",
                 .reference = "Quilez 2010, 'Penumbra shadows in raymarched SDFs'; Aaltonen 2018, "
                              "closest approach of consecutive steps",
                 .families = {"bias", "sdf", "composite"}},
        .parameters =
            {{.key = "sdf.resolution",
              .type = ParameterType::Int,
              .defaultValue = 0,
              .min = 0,
              .max = 1024,
              .unit = "voxels on the scene's longest axis",
              .description = "the field's resolution (the other axes get voxels of the same "
                             "size); 0: automatic, the finest from 256 to 1024 whose scene "
                             "holds at most 2^23 voxels; 1-15 are refused; built once per "
                             "scene and value, at most 2^27 voxels"},
             {.key = "sdf.thickness",
              .type = ParameterType::Float,
              .defaultValue = 0.75,
              .min = 0.0,
              .max = 8.0,
              .unit = "voxels",
              .description = "half-thickness given to open geometry (planes, cards, unwelded "
                             "meshes), which has no inside: its unsigned distance less this, so "
                             "that a trilinear read between voxels still finds it solid"},
             {.key = "sdf.steps",
              .type = ParameterType::Int,
              .defaultValue = 128,
              .min = 4,
              .max = 1024,
              .unit = "steps",
              .description = "most sphere-tracing steps per ray (a ray that uses them all keeps "
                             "the narrowest cone it found)"},
             {.key = "sdf.startOffset",
              .type = ParameterType::Float,
              .defaultValue = 1.0,
              .min = 0.0,
              .max = 16.0,
              .unit = "voxels",
              .description = "the ray starts this far from the receiver along its face normal, "
                             "out of its own surface's reach (self-shadowing)"},
             {.key = "sdf.refuse",
              .type = ParameterType::Float,
              .defaultValue = 1.2,
              .min = 0.0,
              .max = 100.0,
              .unit = "x hard's RMSE",
              .description = "sdf refuses a view (an error naming the scene; a row compare "
                             "skips) whose shadow, checked with the ground truth's rays on a grid "
                             "of at least 128 columns of its pixels, errs more than this many "
                             "times the hard technique's (RMSE, one grid pixel wholly wrong "
                             "allowed besides), or lights over 0.3% of the umbra or darkens over "
                             "0.3% of the fully lit pixels away from edges (where those stand for "
                             "1000 pixels, as the corpus gate counts): its field cannot hold "
                             "these casters; 0 never refuses"},
             {.key = "sdf.k",
              .type = ParameterType::Float,
              .defaultValue = 0.0,
              .min = 0.0,
              .max = 1000.0,
              .description = "penumbra sharpness: the light's edge at k x distance / travelled "
                             "(Quilez's k); 0 derives it from the light's size, the cone the "
                             "ground truth integrates over"}},
        .visibilityMaps = {}, // none: it traces the field
        // It is handed the receiver itself, and clips the light at its horizon.
        .constants =
            [](const ParameterValues&) {
                return std::vector<SpecConstant>{{SPEC_TRACES_FIELD, 1u}};
            },
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                block.set(
                    gpu::SdfParams{.steps = static_cast<float>(p.number("sdf.steps")),
                                   .startOffset = static_cast<float>(p.number("sdf.startOffset")),
                                   .k = static_cast<float>(p.number("sdf.k")),
                                   .minStep = kMinStepVoxels,
                                   .thickness = static_cast<float>(p.number("sdf.thickness"))});
            },
        .modelsLightSize = true,
        .blurRadiusTexels = [](const ParameterValues&) { return 0.0; },
        .tracedField = DistanceFieldDecl{.resolutionKey = "sdf.resolution",
                                         .thicknessKey = "sdf.thickness",
                                         .refuseKey = "sdf.refuse"},
        .needsClosedSurfaces = true};
    return module;
}

} // namespace penumbra::shadows
