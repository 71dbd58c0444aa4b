#pragma once
// A rendered shadow checked against rays on a coarse grid of its own pixels, beside the `hard`
// technique's for the same view (issue 55). The `sdf` technique uses it to refuse a view its
// field cannot hold (sdf.refuse): its error depends on the field's voxels against the casters'
// sizes, which no rule on the geometry alone predicts (docs/techniques.md, sdf, "The audit"). The
// rays are the ground truth's (computeReference) at every stride-th pixel of each axis, so the
// check costs about the same whatever the image's size: a few hundred thousand rays.
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct AuditOptions {
    uint32_t across = 128;    // at least this many grid columns (rows keep the aspect)
    uint32_t samples = 256;   // rays per grid pixel and light with a size
    std::string embreeConfig; // as ReferenceOptions
};

struct VisibilityAudit {
    uint32_t stride = 1;   // the grid's spacing, pixels
    uint64_t pixels = 0;   // grid pixels with a surface, over the shadow-casting lights
    double rmse = 0.0;     // the audited visibility against the rays' estimate
    double hardRmse = 0.0; // the `hard` technique's, rendered for the same view, against it
    double lost = 0.0;     // of the pixels whose ray to the light's centre is blocked: read lit
    double added = 0.0;    // of those whose centre ray is open: read dark (< 1/2)
    // compare's leak and acne on the grid: pixels whose truth is fully shadowed or fully lit
    // away from shadow edges (their four neighbours on the grid on the same side of one half),
    // and those of them read above 0.1 or below 0.9.
    uint64_t umbra = 0, leaked = 0, fullyLit = 0, acne = 0;
};

// `lit`: the scene as both results were rendered (light sizes overridden); `hard`: the same
// view with the `hard` technique; `masks`: per shadow-casting light, the pixels counted (compare's
// lightMask: those the light reaches), none for all. The results' positions, normals and
// visibility are read at the grid's pixels (the centre of each cell).
VisibilityAudit auditVisibility(const Scene& lit, const RenderResult& result,
                                const RenderResult& hard,
                                const std::vector<std::vector<uint8_t>>& masks = {},
                                const AuditOptions& options = {});

// The squared error allowed besides `limit` times hard's, in grid pixels wholly wrong: a view
// whose shadows both read almost exactly (lights without size: hard's error is a few edge
// pixels, or none on the grid) is not refused for one pixel on an edge.
inline constexpr double kAuditSlackPixels = 1.0;

// Leak and acne refuse past this share of the pixels they rest on (the corpus gate's target),
// one grid pixel allowed besides, where those are at least kAuditLeastPixels of the full view
// (the gate's rule: stride^2 full pixels a grid pixel).
inline constexpr double kAuditSpotShare = 0.003;
inline constexpr double kAuditLeastPixels = 1000.0;
// Leak and acne together refuse past this share (the gate's target) of the pixels away from
// shadow edges (fully lit or fully shadowed, on the grid), one grid pixel allowed besides, with
// no least count, as the gate's misclassified-away-from-edges figure: a small shadow lost by a
// field whose RMSE hard's large error hides (a wide sun) is refused.
inline constexpr double kAuditSettledShare = 0.003;

// What a refusal names: the tracing technique, the plain one it is measured against, and the
// keys of its limit and its field's resolution (shadows::DistanceFieldDecl).
struct AuditNames {
    std::string_view technique, plain, refuseKey, resolutionKey;
};

// Why the tracing technique refuses the view (the problem, the figures, what to change), or
// empty when its RMSE^2 <= (limit x the plain one's)^2 + kAuditSlackPixels / pixels, neither its
// leak nor its acne passes kAuditSpotShare and both together do not pass kAuditSettledShare.
// limit 0: never refuses.
std::string auditRefusal(const VisibilityAudit& audit, double limit, const AuditNames& names);

} // namespace penumbra
