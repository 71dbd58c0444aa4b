#include "report/html_report.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <span>
#include <string_view>

namespace penumbra {

std::string escapeHtml(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        const char* entity = c == '&'    ? "&amp;"
                             : c == '<'  ? "&lt;"
                             : c == '>'  ? "&gt;"
                             : c == '"'  ? "&quot;"
                             : c == '\'' ? "&#39;"
                                         : nullptr;
        if (entity)
            out += entity;
        else
            out += c;
    }
    return out;
}

namespace {

std::string base64(std::span<const uint8_t> bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        uint32_t group = uint32_t{bytes[i]} << 16;
        if (n > 1)
            group |= uint32_t{bytes[i + 1]} << 8;
        if (n > 2)
            group |= bytes[i + 2];
        for (size_t k = 0; k < 4; ++k)
            out += k <= n ? kAlphabet[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// An <img> with the PNG inlined, or a stand-in when the image was not produced.
std::string imageTag(const std::vector<uint8_t>& png, std::string_view cls, std::string_view alt) {
    if (png.empty())
        return fmt::format("<div class=\"missing {}\">no image</div>", cls);
    return fmt::format("<img class=\"{}\" alt=\"{}\" src=\"data:image/png;base64,{}\">", cls,
                       escapeHtml(alt), base64(png));
}

double totalGpuMs(const ReportRow& row) {
    double total = 0;
    for (const auto& [pass, ms] : row.gpuMs)
        total += ms;
    return total;
}

// Every pass that any row timed, in the order first seen (rows list them in frame order).
std::vector<std::string> passNames(const std::vector<ReportRow>& rows) {
    std::vector<std::string> names;
    for (const ReportRow& row : rows)
        for (const auto& [pass, ms] : row.gpuMs)
            if (std::find(names.begin(), names.end(), pass) == names.end())
                names.push_back(pass);
    return names;
}

std::string percent(double fraction) {
    return fmt::format("{:.2f}%", 100 * fraction);
}

// "12.3 M" style counts for rays per second.
std::string humanCount(double value) {
    if (value >= 1e9)
        return fmt::format("{:.2f} G", value / 1e9);
    if (value >= 1e6)
        return fmt::format("{:.2f} M", value / 1e6);
    if (value >= 1e3)
        return fmt::format("{:.2f} k", value / 1e3);
    return fmt::format("{:.0f}", value);
}

// A "nice" axis from 0: a 1/2/5 x 10^k step and a maximum that covers maxValue. Degenerate data
// (no rows, all zero, non-finite) gets the unit axis rather than a division by zero.
struct Axis {
    double max = 1, step = 0.2;
    int decimals = 1;
};

Axis niceAxis(double maxValue) {
    if (!(maxValue > 0) || !std::isfinite(maxValue))
        return {};
    const double raw = maxValue * 1.05 / 5;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double norm = raw / magnitude;
    const double step = (norm <= 1 ? 1 : norm <= 2 ? 2 : norm <= 5 ? 5 : 10) * magnitude;
    const int decimals = std::max(0, -int(std::floor(std::log10(step) + 1e-9)));
    return {std::ceil(maxValue * 1.05 / step) * step, step, decimals};
}

constexpr std::string_view kPalette[] = {"#2b6cb0", "#c53030", "#2f855a", "#b7791f",
                                         "#6b46c1", "#0987a0", "#d53f8c", "#4a5568"};

// Error (RMSE) against total GPU time, one labelled point per row, as inline SVG.
std::string errorVsCostSvg(const std::vector<ReportRow>& rows) {
    constexpr double w = 760, h = 420, left = 70, right = 180, top = 20, bottom = 56;
    constexpr double plotW = w - left - right, plotH = h - top - bottom;
    double maxMs = 0, maxRmse = 0;
    for (const ReportRow& row : rows) {
        if (std::isfinite(totalGpuMs(row)))
            maxMs = std::max(maxMs, totalGpuMs(row));
        if (std::isfinite(row.metrics.rmse))
            maxRmse = std::max(maxRmse, row.metrics.rmse);
    }
    const Axis ax = niceAxis(maxMs), ay = niceAxis(maxRmse);
    auto px = [&](double ms) { return left + plotW * ms / ax.max; };
    auto py = [&](double rmse) { return top + plotH * (1 - rmse / ay.max); };
    std::string s = fmt::format("<svg class=\"error-vs-cost\" viewBox=\"0 0 {} {}\" role=\"img\" "
                                "aria-label=\"RMSE against total GPU time\">\n",
                                w, h);
    auto out = std::back_inserter(s);
    const int ticksX = int(std::lround(ax.max / ax.step)),
              ticksY = int(std::lround(ay.max / ay.step));
    for (int i = 0; i <= ticksX; ++i) {
        const double x = px(i * ax.step);
        fmt::format_to(out,
                       "<line class=\"grid\" x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\"/>"
                       "<text class=\"tick\" x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">"
                       "{4:.{5}f}</text>\n",
                       x, top, top + plotH, top + plotH + 18, i * ax.step, ax.decimals);
    }
    for (int i = 0; i <= ticksY; ++i) {
        const double y = py(i * ay.step);
        fmt::format_to(out,
                       "<line class=\"grid\" x1=\"{1}\" y1=\"{0:.1f}\" x2=\"{2}\" y2=\"{0:.1f}\"/>"
                       "<text class=\"tick\" x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">"
                       "{5:.{6}f}</text>\n",
                       y, left, left + plotW, left - 8, y + 4, i * ay.step, ay.decimals);
    }
    fmt::format_to(out,
                   "<line class=\"axis\" x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\"/>"
                   "<line class=\"axis\" x1=\"{0}\" y1=\"{3}\" x2=\"{0}\" y2=\"{1}\"/>\n",
                   left, top + plotH, left + plotW, top);
    fmt::format_to(out,
                   "<text class=\"label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">total GPU "
                   "time (ms)</text>\n<text class=\"label\" transform=\"translate(18 {}) "
                   "rotate(-90)\" text-anchor=\"middle\">RMSE</text>\n",
                   left + plotW / 2, h - 14, top + plotH / 2);
    for (size_t i = 0; i < rows.size(); ++i) {
        const double ms = totalGpuMs(rows[i]), rmse = rows[i].metrics.rmse;
        if (!std::isfinite(ms) || !std::isfinite(rmse))
            continue;
        const std::string name = escapeHtml(rows[i].name);
        fmt::format_to(out,
                       "<g class=\"point\" data-technique=\"{0}\"><circle cx=\"{1:.1f}\" "
                       "cy=\"{2:.1f}\" r=\"6\" fill=\"{3}\"><title>{0}: {4:.3f} ms, RMSE "
                       "{5:.4f}</title></circle><text x=\"{6:.1f}\" y=\"{7:.1f}\">{0}</text></g>\n",
                       name, px(ms), py(rmse), kPalette[i % std::size(kPalette)], ms, rmse,
                       px(ms) + 9, py(rmse) - 7);
    }
    s += "</svg>\n";
    return s;
}

constexpr std::string_view kStyle = R"(
:root { --ink: #1f2933; --muted: #616e7c; --line: #e4e7eb; --card: #fff; --accent: #2b6cb0; }
* { box-sizing: border-box; }
body { margin: 0; background: #f5f7fa; color: var(--ink); line-height: 1.45;
  font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
main { max-width: 1400px; margin: 0 auto; padding: 32px 24px 64px; }
h1 { font-size: 26px; margin: 0 0 4px; } h2 { font-size: 19px; margin: 36px 0 12px; }
.subtitle { color: var(--muted); margin: 0 0 20px; }
.card { background: var(--card); border: 1px solid var(--line); border-radius: 10px;
  padding: 18px 20px; box-shadow: 0 1px 2px rgba(15, 23, 42, .05); }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 6px 24px; margin: 0; }
dl.facts dt { color: var(--muted); } dl.facts dd { margin: 0; }
dl.facts ul { margin: 0; padding-left: 18px; }
.table-wrap { overflow-x: auto; padding: 0; }
table { border-collapse: collapse; width: 100%; font-variant-numeric: tabular-nums; }
th, td { padding: 8px 12px; border-bottom: 1px solid var(--line); white-space: nowrap; }
th { background: #f0f3f7; font-weight: 600; font-size: 13px; text-align: right; }
td { text-align: right; } th:nth-child(-n+2), td:nth-child(-n+2) { text-align: left; }
tbody tr:nth-child(even) { background: #fafbfc; } tbody tr:hover { background: #eef4fb; }
td.name { font-weight: 600; } td.params { color: var(--muted); white-space: normal; }
td.best { color: #22543d; font-weight: 600; } th.total, td.total { border-left: 1px solid var(--line); }
.grid-images { display: grid; gap: 20px; }
figure { margin: 0; } figcaption { margin-bottom: 10px; }
figcaption .tech { color: var(--muted); font-size: 13px; margin-left: 8px; }
.triptych { display: grid; grid-template-columns: repeat(3, 1fr); gap: 12px; align-items: start; }
.panel { display: flex; flex-direction: column; gap: 4px; font-size: 13px; color: var(--muted); }
img { width: 100%; height: auto; display: block; border-radius: 4px; background: #e4e7eb; }
figure.reference img { max-width: 460px; }
.missing { padding: 40px 0; text-align: center; color: var(--muted); background: #f0f3f7; border-radius: 4px; }
@media (max-width: 800px) { .triptych { grid-template-columns: 1fr; } }
.note { color: var(--muted); font-size: 13px; margin: 8px 0 0; }
svg.error-vs-cost { width: 100%; max-width: 900px; height: auto; display: block; font-size: 12px; }
svg .grid { stroke: #e4e7eb; } svg .axis { stroke: #52606d; stroke-width: 1.2; }
svg .tick { fill: var(--muted); } svg .label { fill: var(--ink); font-size: 13px; }
svg .point text { fill: var(--ink); font-size: 12px; } svg circle { stroke: #fff; stroke-width: 1.5; }
)";

void writeHeader(std::string& s, const ReportData& d) {
    auto out = std::back_inserter(s);
    fmt::format_to(out, "<h1>Penumbra shadow report</h1>\n<p class=\"subtitle\">{}</p>\n",
                   escapeHtml(d.scene));
    fmt::format_to(out,
                   "<section class=\"card\"><dl class=\"facts\">\n"
                   "<dt>Scene</dt><dd>{}</dd>\n<dt>Device</dt><dd>{}</dd>\n"
                   "<dt>Driver</dt><dd>{}</dd>\n<dt>Image</dt><dd>{} &times; {}</dd>\n"
                   "<dt>Shadow map</dt><dd>{} &times; {}</dd>\n"
                   "<dt>Reference</dt><dd>{} rays per pixel and light, {:.2f} s, {} rays/s</dd>\n"
                   "<dt>Lights</dt><dd><ul>",
                   escapeHtml(d.scene), escapeHtml(d.device), escapeHtml(d.driver), d.width,
                   d.height, d.shadowMapSize, d.shadowMapSize, d.samples, d.referenceSeconds,
                   humanCount(d.raysPerSecond));
    for (const std::string& light : d.lights)
        fmt::format_to(out, "<li>{}</li>", escapeHtml(light));
    if (d.lights.empty())
        s += "<li>none</li>";
    s += "</ul></dd>\n</dl></section>\n";
}

void writeTable(std::string& s, const ReportData& d) {
    auto out = std::back_inserter(s);
    const std::vector<std::string> passes = passNames(d.rows);
    s += "<h2>Error against the reference</h2>\n<section class=\"card table-wrap\"><table>\n"
         "<thead><tr><th>Technique</th><th>Parameters</th><th>RMSE</th><th>MAE</th><th>Max</th>"
         "<th>Misclassified</th><th>Misclassified outside edges</th><th>Acne</th><th>Leak</th>"
         "<th>Acne beyond blur</th><th>Leak beyond blur</th>";
    const bool shimmer = !d.cameraPath.empty();
    if (shimmer)
        fmt::format_to(out, "<th>Shimmer ({}, {} frames)</th>", escapeHtml(d.cameraPath),
                       d.pathFrames);
    for (const std::string& pass : passes)
        fmt::format_to(out, "<th>{} ms</th>", escapeHtml(pass));
    s += "<th class=\"total\">GPU total ms</th></tr></thead>\n<tbody>\n";
    // The lowest value of each error column is highlighted when there is something to compare.
    auto bestOf = [&](double ErrorMetrics::*field) {
        double best = INFINITY;
        for (const ReportRow& row : d.rows)
            best = std::min(best, row.metrics.*field);
        return d.rows.size() > 1 ? best : NAN;
    };
    auto cell = [&](const ReportRow& row, double ErrorMetrics::*field, bool asPercent) {
        const double v = row.metrics.*field;
        fmt::format_to(out, "<td{}>{}</td>", v == bestOf(field) ? " class=\"best\"" : "",
                       asPercent ? percent(v) : fmt::format("{:.4f}", v));
    };
    for (const ReportRow& row : d.rows) {
        const std::string name = escapeHtml(row.name);
        std::string params;
        for (const auto& [key, value] : row.parameters)
            params += (params.empty() ? "" : ", ") + escapeHtml(key) + "=" + escapeHtml(value);
        fmt::format_to(out,
                       "<tr class=\"technique-row\" data-technique=\"{}\"><td class=\"name\">{}"
                       "</td><td class=\"params\">{}</td>",
                       name, name, params.empty() ? "defaults" : params);
        cell(row, &ErrorMetrics::rmse, false);
        cell(row, &ErrorMetrics::mae, false);
        cell(row, &ErrorMetrics::max, false);
        cell(row, &ErrorMetrics::misclassified, true);
        cell(row, &ErrorMetrics::misclassifiedOutsideEdges, true);
        cell(row, &ErrorMetrics::acne, true);
        cell(row, &ErrorMetrics::leak, true);
        cell(row, &ErrorMetrics::acneBeyondBlur, true);
        cell(row, &ErrorMetrics::leakBeyondBlur, true);
        if (shimmer)
            fmt::format_to(out, "<td>{:.5f}</td>", row.shimmer);
        for (const std::string& pass : passes) {
            auto it = std::find_if(row.gpuMs.begin(), row.gpuMs.end(),
                                   [&](const auto& p) { return p.first == pass; });
            s += it == row.gpuMs.end() ? std::string("<td>&ndash;</td>")
                                       : fmt::format("<td>{:.3f}</td>", it->second);
        }
        fmt::format_to(out, "<td class=\"total\">{:.3f}</td></tr>\n", totalGpuMs(row));
    }
    s += "</tbody></table></section>\n<p class=\"note\">Percentages are fractions of counted "
         "pixels (facing a light, inside its frustum). Acne: fully lit in the reference but "
         "visibility &lt; 0.9; leak: fully shadowed but visibility &gt; 0.1; both, like "
         "misclassified outside edges, more than 2 pixels from the reference's shadow "
         "edges. Beyond blur: the same, more than the technique's blur radius from those "
         "edges (its declared filter reach, in texels, projected to the screen at each pixel; "
         "at least 2 and at most 8 pixels), so what remains is self-shadowing and missing "
         "shadow rather than the blur a wide kernel makes.</p>\n";
}

void writeImages(std::string& s, const ReportData& d) {
    auto out = std::back_inserter(s);
    s += "<h2>Images</h2>\n<div class=\"grid-images\">\n";
    fmt::format_to(out,
                   "<figure class=\"card reference\"><figcaption><strong>Reference visibility"
                   "</strong><span class=\"tech\">{} rays per pixel and light</span></figcaption>"
                   "{}</figure>\n",
                   d.samples,
                   imageTag(d.referenceVisibilityPng, "reference", "reference visibility"));
    for (const ReportRow& row : d.rows) {
        const std::string name = escapeHtml(row.name);
        fmt::format_to(out,
                       "<figure class=\"card technique\" data-technique=\"{0}\"><figcaption>"
                       "<strong>{0}</strong><span class=\"tech\">{1}</span></figcaption>\n"
                       "<div class=\"triptych\"><div class=\"panel\">{2}<span>Lit image</span>"
                       "</div><div class=\"panel\">{3}<span>Visibility</span></div>"
                       "<div class=\"panel\">{4}<span>Error: visibility &minus; reference</span>"
                       "</div></div></figure>\n",
                       name, escapeHtml(row.technique),
                       imageTag(row.imagePng, "lit", row.name + " lit image"),
                       imageTag(row.visibilityPng, "visibility", row.name + " visibility"),
                       imageTag(row.heatmapPng, "heatmap", row.name + " error heat map"));
    }
    s += "</div>\n<p class=\"note\">Heat maps: blue is too dark (acne side), red too bright "
         "(leak side); dimmed pixels are not counted; the checker is background.</p>\n";
}

} // namespace

std::string renderHtmlReport(const ReportData& data) {
    std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                    "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    fmt::format_to(std::back_inserter(s), "<title>Penumbra report: {}</title>\n<style>{}</style>\n",
                   escapeHtml(data.scene), kStyle);
    s += "</head>\n<body>\n<main>\n";
    writeHeader(s, data);
    writeTable(s, data);
    s += "<h2>Error against GPU cost</h2>\n<section class=\"card\">\n";
    s += errorVsCostSvg(data.rows);
    s += "</section>\n";
    writeImages(s, data);
    s += "</main>\n</body>\n</html>\n";
    return s;
}

nlohmann::json metricsJson(const ReportData& data) {
    nlohmann::json j;
    j["reference"] = {{"samples", data.samples},
                      {"seconds", data.referenceSeconds},
                      {"rays_per_second", data.raysPerSecond},
                      {"lights", data.lights},
                      {"scene", data.scene},
                      {"width", data.width},
                      {"height", data.height},
                      {"device", data.device}};
    if (!data.cameraPath.empty())
        j["camera_path"] = {{"path", data.cameraPath}, {"frames", data.pathFrames}};
    nlohmann::json techniques = nlohmann::json::object();
    for (const ReportRow& row : data.rows) {
        PENUMBRA_CHECK(!techniques.contains(row.name), "duplicate report row " + row.name);
        nlohmann::json gpu = nlohmann::json::object();
        for (const auto& [pass, ms] : row.gpuMs) {
            PENUMBRA_CHECK(pass != "total", "a GPU pass may not be named total");
            gpu[pass] = ms;
        }
        gpu["total"] = totalGpuMs(row);
        const ErrorMetrics& m = row.metrics;
        techniques[row.name] = {{"rmse", m.rmse},
                                {"mae", m.mae},
                                {"max", m.max},
                                {"misclassified", m.misclassified},
                                {"misclassified_outside_edges", m.misclassifiedOutsideEdges},
                                {"acne", m.acne},
                                {"leak", m.leak},
                                {"acne_beyond_blur", m.acneBeyondBlur},
                                {"leak_beyond_blur", m.leakBeyondBlur},
                                {"leak_near_contact", m.leakNearContact},
                                {"near_contact_pixels", m.nearContact},
                                {"pixels", m.pixels},
                                {"gpu_ms", gpu}};
        if (!data.cameraPath.empty())
            techniques[row.name]["shimmer"] = row.shimmer;
        if (!row.pathPagesRendered.empty()) {
            techniques[row.name]["path_pages_rendered"] = row.pathPagesRendered;
            techniques[row.name]["path_pages_resident"] = row.pathPagesResident;
        }
    }
    j["techniques"] = techniques;
    return j;
}

} // namespace penumbra
