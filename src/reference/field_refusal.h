#pragma once
// sdf.refuse (issue 55): the `sdf` technique's picture audited (reference/visibility_audit.h)
// beside the `hard` technique's for the same view, and refused where its field cannot hold the
// view's casters. Every command that hands a picture to its user calls it after rendering:
// render, compare, a sweep's task, Python's render; not the viewer nor bench.
#include "penumbra/renderer.h"

namespace penumbra {

// Where `options` trace the distance field (every other technique: nothing) and sdf.refuse is not
// 0: renders the view with `hard` too, audits both against rays, tells `note` the figures, and
// throws InputError naming the scene with auditRefusal's reason. `result`: `options`' picture.
void refuseUnheldField(SceneRenderer& renderer, const RenderOptions& options,
                       const RenderResult& result, const ProgressFn& note = {});

} // namespace penumbra
