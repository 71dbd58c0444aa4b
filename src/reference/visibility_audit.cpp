#include "reference/visibility_audit.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra {

VisibilityAudit auditVisibility(const Scene& lit, const RenderResult& result,
                                const RenderResult& hard,
                                const std::vector<std::vector<uint8_t>>& masks,
                                const AuditOptions& options) {
    VisibilityAudit audit;
    const uint32_t w = result.width, h = result.height;
    if (w == 0 || h == 0 || result.visibility.empty())
        return audit;
    PENUMBRA_CHECK(hard.width == w && hard.height == h &&
                       hard.visibility.size() == result.visibility.size(),
                   "the hard picture is not of the audited view");
    for (const std::vector<uint8_t>& mask : masks)
        PENUMBRA_CHECK(mask.size() == size_t{w} * h, "a light's mask is not of the audited view");
    audit.stride = std::max(1u, w / std::max(options.across, 1u));
    const uint32_t s = audit.stride;
    // The grid's G-buffer: each cell's centre pixel.
    RenderResult grid{.width = (w + s - 1) / s, .height = (h + s - 1) / s};
    std::vector<size_t> source;
    for (uint32_t y = 0; y < grid.height; ++y)
        for (uint32_t x = 0; x < grid.width; ++x) {
            const size_t i =
                size_t{std::min(y * s + s / 2, h - 1)} * w + std::min(x * s + s / 2, w - 1);
            source.push_back(i);
            for (int c = 0; c < 3; ++c) {
                grid.position.push_back(result.position[3 * i + c]);
                grid.normal.push_back(result.normal[3 * i + c]);
            }
        }
    const ReferenceResult truth = computeReference(
        lit, grid, {.samples = options.samples, .embreeConfig = options.embreeConfig});
    double squared = 0.0, hardSquared = 0.0;
    uint64_t blocked = 0, open = 0, lost = 0, added = 0;
    const size_t lights = std::min(truth.visibility.size(), result.visibility.size());
    // Whether cell g's truth reads fully shadowed (or fully lit) away from shadow edges: its
    // four neighbours on the grid, `stride` pixels off, on the same side of one half (or
    // background), as compare's metrics take acne and leak beyond 2 pixels of the edges.
    const auto settled = [&](const std::vector<float>& t, size_t g, bool shadowed) {
        const auto side = [&](size_t k) { return !(t[k] >= 0.5f) == shadowed || std::isnan(t[k]); };
        const size_t x = g % grid.width, y = g / grid.width;
        return (shadowed ? t[g] <= 1e-6f : t[g] >= 1.0f - 1e-6f) && (x == 0 || side(g - 1)) &&
               (x + 1 == grid.width || side(g + 1)) && (y == 0 || side(g - grid.width)) &&
               (y + 1 == grid.height || side(g + grid.width));
    };
    for (size_t l = 0; l < lights; ++l)
        for (size_t g = 0; g < source.size(); ++g) {
            const float t = truth.visibility[l][g], v = result.visibility[l][source[g]];
            const float plain = hard.visibility[l][source[g]];
            const float occluder = truth.occluderDistance[l][g];
            if (!std::isfinite(t) || !std::isfinite(v) || !std::isfinite(plain) ||
                std::isnan(occluder) || (l < masks.size() && masks[l][source[g]] == 0))
                continue;
            const bool centreOpen = std::isinf(occluder);
            squared += (double(v) - t) * (double(v) - t);
            hardSquared += (double(plain) - t) * (double(plain) - t);
            ++audit.pixels;
            if (centreOpen) {
                ++open;
                added += v < 0.5f;
            } else if (occluder > 0.0f) { // another surface, not the receiver's own back
                ++blocked;
                lost += v >= 0.5f;
            }
            if (settled(truth.visibility[l], g, true)) {
                ++audit.umbra;
                audit.leaked += v > 0.1f;
            } else if (settled(truth.visibility[l], g, false)) {
                ++audit.fullyLit;
                audit.acne += v < 0.9f;
            }
        }
    if (audit.pixels == 0)
        return audit;
    audit.rmse = std::sqrt(squared / double(audit.pixels));
    audit.hardRmse = std::sqrt(hardSquared / double(audit.pixels));
    audit.lost = blocked == 0 ? 0.0 : double(lost) / double(blocked);
    audit.added = open == 0 ? 0.0 : double(added) / double(open);
    return audit;
}

std::string auditRefusal(const VisibilityAudit& audit, double limit, const AuditNames& names) {
    if (limit <= 0.0 || audit.pixels == 0)
        return {};
    const double allowed = std::sqrt(limit * audit.hardRmse * limit * audit.hardRmse +
                                     kAuditSlackPixels / double(audit.pixels));
    const double least = kAuditLeastPixels / (double(audit.stride) * audit.stride);
    const auto past = [&](uint64_t count, uint64_t of) {
        return double(of) >= least && double(count) > kAuditSpotShare * double(of) + 1.0;
    };
    std::string why;
    if (audit.rmse > allowed && audit.hardRmse > 0.0)
        why = fmt::format("its shadow errs {:.2f}x as much as the {} technique's (RMSE {:.4f} "
                          "against {:.4f}; {}={} allows {:.4f})",
                          audit.rmse / audit.hardRmse, names.plain, audit.rmse, audit.hardRmse,
                          names.refuseKey, limit, allowed);
    else if (audit.rmse > allowed)
        why = fmt::format("its shadow errs where the {} technique's is exact (RMSE {:.4f}; "
                          "{}={} allows {:.4f})",
                          names.plain, audit.rmse, names.refuseKey, limit, allowed);
    // Away from edges, every pixel counts however few rest on the umbra (a wide sun's field that
    // lost a third of a small shadow, kept by its RMSE since hard's was as large).
    const uint64_t settled = audit.umbra + audit.fullyLit, wrong = audit.leaked + audit.acne;
    if (double(wrong) > kAuditSettledShare * double(settled) + 1.0)
        why += fmt::format("{}it reads {:.2f}% of the pixels away from shadow edges on the wrong "
                           "side ({} of {})",
                           why.empty() ? "" : "; ", 100.0 * double(wrong) / double(settled), wrong,
                           settled);
    if (past(audit.leaked, audit.umbra))
        why += fmt::format(
            "{}it lights {:.2f}% of the umbra ({} of {} pixels)", why.empty() ? "" : "; ",
            100.0 * double(audit.leaked) / double(audit.umbra), audit.leaked, audit.umbra);
    if (past(audit.acne, audit.fullyLit))
        why += fmt::format(
            "{}it darkens {:.2f}% of the fully lit pixels ({} of {})", why.empty() ? "" : "; ",
            100.0 * double(audit.acne) / double(audit.fullyLit), audit.acne, audit.fullyLit);
    if (why.empty())
        return {};
    return fmt::format(
        "{} refuses this view: {}, over {} pixels of a grid every {} pixels, checked with rays; "
        "its field loses {:.1f}% of the shadowed pixels and darkens {:.1f}% of the lit ones, its "
        "voxels too coarse for these casters: raise {}, or set {}=0 to render it anyway",
        names.technique, why, audit.pixels, audit.stride, 100.0 * audit.lost, 100.0 * audit.added,
        names.resolutionKey, names.refuseKey);
}

} // namespace penumbra
