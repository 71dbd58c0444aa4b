#include "reference/field_refusal.h"

#include "penumbra/error.h"
#include "reference/visibility_audit.h"
#include "report/light_mask.h"
#include "shadows/technique.h"

#include <fmt/format.h>

namespace penumbra {

void refuseUnheldField(SceneRenderer& renderer, const RenderOptions& options,
                       const RenderResult& result, const ProgressFn& note) {
    const auto& declared = shadows::moduleOf(options.technique).tracedField;
    if (!declared)
        return;
    const double limit = options.parameters.number(declared->refuseKey);
    if (limit <= 0.0)
        return;
    RenderOptions plain = options;       // the same view, lights and map size
    plain.technique = kDefaultTechnique; // the plain depth test
    plain.frames = 1;
    const RenderResult hard = renderer.render(plain);
    Scene lit = renderer.scene();
    applyLightSizeOverrides(lit, options.lightRadiusOverride, options.lightAngleOverride);
    std::vector<std::vector<uint8_t>> masks; // the pixels compare counts, light by light
    for (const LightShadow& s : result.lights)
        if (s.visibilityIndex >= 0)
            masks.push_back(lightMask(lit.lights[s.sceneLight], result));
    const VisibilityAudit audit = auditVisibility(lit, result, hard, masks);
    if (note)
        note(fmt::format("{} audit: RMSE {:.4f} against {}'s {:.4f} over {} pixels (every "
                         "{}); lost {:.2f}%, added {:.2f}%; leak {} of {}, acne {} of {}",
                         techniqueName(options.technique), audit.rmse,
                         techniqueName(kDefaultTechnique), audit.hardRmse, audit.pixels,
                         audit.stride, 100.0 * audit.lost, 100.0 * audit.added, audit.leaked,
                         audit.umbra, audit.acne, audit.fullyLit));
    const std::string reason = auditRefusal(audit, limit,
                                            {.technique = techniqueName(options.technique),
                                             .plain = techniqueName(kDefaultTechnique),
                                             .refuseKey = declared->refuseKey,
                                             .resolutionKey = declared->resolutionKey});
    if (!reason.empty())
        throw InputError(lit.name, reason);
}

} // namespace penumbra
