#include "report/tune_report.h"

#include "report/html_report.h"
#include "report/report_plot.h"
#include "report/truth_notes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace penumbra {
namespace {

std::string label(const TuneCandidate& c) {
    std::string s;
    for (const auto& [key, value] : c.sets)
        s += (s.empty() ? "" : " ") + key + "=" + value;
    return s.empty() ? "(defaults)" : s;
}

nlohmann::json candidateJson(const TuneCandidate& c) {
    nlohmann::json sets = nlohmann::json::object();
    for (const auto& [key, value] : c.sets)
        sets[key] = value;
    const ErrorMetrics& m = c.metrics;
    return {{"sets", sets},
            {"set", c.setLine},
            {"acne_beyond_blur", m.acneBeyondBlur},
            {"leak_beyond_blur", m.leakBeyondBlur},
            {"acne", m.acne},
            {"leak", m.leak},
            {"misclassified_outside_edges", m.misclassifiedOutsideEdges},
            {"rmse", m.rmse},
            {"pixels", m.pixels},
            {"counts", metricCountsJson(m)},
            {"gpu_ms", c.gpuMs},
            {"defaults", c.isDefault},
            {"front", c.onFront}};
}

// The acne-against-leak chart: every candidate a dot, the front joined, the defaults and the
// recommendation ringed. Axes in percent, from zero.
std::string frontChart(const TuneData& d) {
    constexpr double w = 560, h = 380, left = 64, bottom = 44, top = 16, right = 16;
    // The axes span the front, the defaults and the recommendation (at least 0.05%): a setting
    // with gross acne would squash the interesting corner; those beyond sit on the border,
    // hollow.
    double maxX = 0.05, maxY = 0.05;
    for (size_t i = 0; i < d.candidates.size(); ++i) {
        const TuneCandidate& c = d.candidates[i];
        if (!c.onFront && i != d.defaults && i != d.recommended)
            continue;
        maxX = std::max(maxX, 100 * c.metrics.acneBeyondBlur * 1.1);
        maxY = std::max(maxY, 100 * c.metrics.leakBeyondBlur * 1.1);
    }
    const Axis ax = niceAxis(maxX), ay = niceAxis(maxY); // round ticks
    maxX = ax.max;
    maxY = ay.max;
    const auto x = [&](double v) {
        return left + (w - left - right) * std::min(100 * v / maxX, 1.0);
    };
    const auto y = [&](double v) {
        return h - bottom - (h - bottom - top) * std::min(100 * v / maxY, 1.0);
    };
    std::string s = fmt::format("<svg width='{}' height='{}' role='img' aria-label='acne against "
                                "leak beyond blur'><rect x='{}' y='{}' width='{}' height='{}' "
                                "fill='none' stroke='#999'/>",
                                w, h, left, top, w - left - right, h - top - bottom);
    for (int i = 0; i <= int(std::lround(ax.max / ax.step)); ++i)
        s += fmt::format("<text x='{:.1f}' y='{}' font-size='11' text-anchor='middle'>{:.{}f}"
                         "</text>",
                         x(ax.step * i / 100), h - bottom + 16, ax.step * i, ax.decimals);
    for (int i = 0; i <= int(std::lround(ay.max / ay.step)); ++i)
        s += fmt::format("<text x='{}' y='{:.1f}' font-size='11' text-anchor='end'>{:.{}f}"
                         "</text>",
                         left - 6, y(ay.step * i / 100) + 4, ay.step * i, ay.decimals);
    s += fmt::format("<text x='{}' y='{}' font-size='12' text-anchor='middle'>acne beyond blur "
                     "(%)</text><text x='14' y='{}' font-size='12' text-anchor='middle' "
                     "transform='rotate(-90 14 {})'>leak beyond blur (%)</text>",
                     (left + w - right) / 2, h - 6, (top + h - bottom) / 2, (top + h - bottom) / 2);
    std::vector<const TuneCandidate*> front;
    for (const TuneCandidate& c : d.candidates)
        if (c.onFront)
            front.push_back(&c);
    std::sort(front.begin(), front.end(), [](const TuneCandidate* a, const TuneCandidate* b) {
        return a->metrics.acneBeyondBlur < b->metrics.acneBeyondBlur;
    });
    std::string points;
    for (const TuneCandidate* c : front)
        points += fmt::format("{:.1f},{:.1f} ", x(c->metrics.acneBeyondBlur),
                              y(c->metrics.leakBeyondBlur));
    s += "<polyline fill='none' stroke='#c33' stroke-width='1.5' points='" + points + "'/>";
    for (size_t i = 0; i < d.candidates.size(); ++i) {
        const TuneCandidate& c = d.candidates[i];
        const double cx = x(c.metrics.acneBeyondBlur), cy = y(c.metrics.leakBeyondBlur);
        const bool beyond =
            100 * c.metrics.acneBeyondBlur > maxX || 100 * c.metrics.leakBeyondBlur > maxY;
        const std::string colour = c.onFront ? "#c33" : "#68a";
        s += fmt::format("<circle cx='{:.1f}' cy='{:.1f}' r='3.5' fill='{}' stroke='{}'><title>{}: "
                         "acne {:.3f}%, leak {:.3f}%</title></circle>",
                         cx, cy, beyond ? "none" : colour, colour, escapeHtml(label(c)),
                         100 * c.metrics.acneBeyondBlur, 100 * c.metrics.leakBeyondBlur);
        if (i == d.defaults || i == d.recommended)
            s += fmt::format("<circle cx='{:.1f}' cy='{:.1f}' r='8' fill='none' stroke='{}' "
                             "stroke-width='2'/>",
                             cx, cy, i == d.recommended ? "#2a2" : "#333");
    }
    return s + "</svg>";
}

} // namespace

void markFront(std::vector<TuneCandidate>& candidates) {
    for (TuneCandidate& c : candidates) {
        c.onFront = std::none_of(candidates.begin(), candidates.end(), [&](const auto& o) {
            const ErrorMetrics &a = o.metrics, &b = c.metrics;
            return a.acneBeyondBlur <= b.acneBeyondBlur && a.leakBeyondBlur <= b.leakBeyondBlur &&
                   (a.acneBeyondBlur < b.acneBeyondBlur || a.leakBeyondBlur < b.leakBeyondBlur);
        });
    }
}

size_t recommend(const std::vector<TuneCandidate>& candidates) {
    double least = INFINITY, defaults = INFINITY;
    for (const TuneCandidate& c : candidates) {
        least = std::min(least, c.objective());
        if (c.isDefault)
            defaults = std::min(defaults, c.objective());
    }
    // Within kTuneTolerance of the least (and never above the defaults), the lower RMSE, then
    // fewer misclassified pixels away from edges, then the earlier candidate.
    const double bound = std::min(least + kTuneTolerance, std::max(defaults, least));
    size_t best = candidates.size();
    for (size_t i = 0; i < candidates.size(); ++i) {
        const TuneCandidate& c = candidates[i];
        if (c.objective() > bound)
            continue;
        const auto key = [](const TuneCandidate& t) {
            return std::tuple(t.metrics.rmse, t.metrics.misclassifiedOutsideEdges);
        };
        if (best == candidates.size() || key(c) < key(candidates[best]))
            best = i;
    }
    return best == candidates.size() ? 0 : best;
}

nlohmann::json tuneJson(const TuneData& d) {
    nlohmann::json candidates = nlohmann::json::array();
    for (const TuneCandidate& c : d.candidates)
        candidates.push_back(candidateJson(c));
    return {{"scene", d.scene},
            {"technique", d.technique},
            {"device", d.device},
            {"views", d.views},
            {"sets", d.baseSets},
            {"width", d.width},
            {"height", d.height},
            {"shadow_map_size", d.shadowMapSize},
            {"samples", d.samples},
            {"rays_per_pixel", truthRays(d.samples, d.lightSized)},
            {"truth_seconds", d.truthSeconds},
            {"objective", "acne_beyond_blur + leak_beyond_blur"},
            {"candidates", candidates},
            {"defaults", d.defaults},
            {"recommended",
             {{"index", d.recommended},
              {"set", d.candidates.at(d.recommended).setLine},
              {"metrics", candidateJson(d.candidates.at(d.recommended))}}}};
}

std::string tuneHtml(const TuneData& d) {
    const std::string& setLine = d.candidates.at(d.recommended).setLine;
    std::string html = fmt::format(
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>penumbra tune: {} {}</title>"
        "<style>body{{font-family:sans-serif;margin:24px;max-width:1100px}}table{{border-"
        "collapse:collapse}}td,th{{border:1px solid #ccc;padding:3px 8px;text-align:right}}"
        "th{{background:#eee}}td.l{{text-align:left}}tr.rec td{{background:#e6f4e6}}"
        "tr.def td{{font-weight:bold}}code{{background:#f3f3f3;padding:2px 4px}}</style></head>"
        "<body><h1>penumbra tune: {} on {}</h1><p>{} candidate settings on {} view(s), {}x{}, "
        "shadow map {}, truth {} ({:.1f} s, traced once per view), {}."
        "</p><p>Acne: truly lit pixels (ground truth 1) the technique darkens below 0.9; leak: "
        "truly shadowed pixels it lights above 0.1; both counted beyond the technique's blur "
        "band (its declared filter radius on the screen, 2 to 8 pixels from the truth's shadow "
        "edges), so that what is left is bias error, not filtering. Recommended (the lowest RMSE "
        "among the settings within 0.01% of the least acne + leak and not above the defaults'): "
        "<code>{}</code>"
        "</p>",
        escapeHtml(d.technique), escapeHtml(d.scene), escapeHtml(d.technique), escapeHtml(d.scene),
        d.candidates.size(), d.views.size(), d.width, d.height, d.shadowMapSize,
        escapeHtml(truthRaysText(d.samples, d.lightSized)), d.truthSeconds, escapeHtml(d.device),
        setLine.empty() ? "the defaults" : escapeHtml(setLine));
    html += frontChart(d);
    html += "<p>Red: the front (no other setting has both less acne and less leak). Black ring: "
            "the defaults; green ring: the recommendation. Hollow dots on the border lie beyond "
            "the axes (see the table).</p>";
    std::vector<size_t> order(d.candidates.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return d.candidates[a].objective() < d.candidates[b].objective();
    });
    html += "<table><tr><th>settings</th><th>acne beyond blur %</th><th>leak beyond blur %"
            "</th><th>acne %</th><th>leak %</th><th>misclassified away from edges %</th>"
            "<th>RMSE</th><th>GPU ms</th><th>front</th></tr>";
    for (size_t i : order) {
        const TuneCandidate& c = d.candidates[i];
        const ErrorMetrics& m = c.metrics;
        html += fmt::format(
            "<tr class='{}'><td class='l'>{}{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:.3f}</td>"
            "<td>{:.3f}</td><td>{:.3f}</td><td>{:.5f}</td><td>{:.2f}</td><td>{}</td></tr>",
            i == d.recommended ? "rec"
            : i == d.defaults  ? "def"
                               : "",
            escapeHtml(label(c)), c.isDefault ? " (defaults)" : "", 100 * m.acneBeyondBlur,
            100 * m.leakBeyondBlur, 100 * m.acne, 100 * m.leak, 100 * m.misclassifiedOutsideEdges,
            m.rmse, c.gpuMs, c.onFront ? "yes" : "");
    }
    return html + "</table></body></html>\n";
}

} // namespace penumbra
