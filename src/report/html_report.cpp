#include "report/html_report.h"

#include "core/base64.h"
#include "report/report_plot.h"
#include "report/report_script.h"
#include "report/timeline_plot.h"
#include "report/truth_notes.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
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

// An <img> with the PNG inlined, or a stand-in when the image was not produced; with a file
// name, a link to that full-size file beside the report.
std::string imageTag(const std::vector<uint8_t>& png, std::string_view cls, std::string_view alt,
                     std::string_view fullSizeFile = {}) {
    if (png.empty())
        return fmt::format("<div class=\"missing {}\">no image</div>", cls);
    const std::string img =
        fmt::format("<img class=\"{}\" alt=\"{}\" src=\"data:image/png;base64,{}\">", cls,
                    escapeHtml(alt), encodeBase64(png));
    if (fullSizeFile.empty())
        return img;
    return fmt::format("<a class=\"full-size\" href=\"{0}\" title=\"full size: {0}\">{1}</a>",
                       escapeHtml(fullSizeFile), img);
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
.channels { color: var(--muted); font-size: 11px; font-weight: 400; line-height: 1.25; }
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
svg.error-vs-cost, svg.over-time { width: 100%; max-width: 900px; height: auto; display: block; font-size: 12px; }
svg.over-time .line { fill: none; stroke-width: 2; } svg.over-time circle { stroke-width: 1; }
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
                   "<dt>Reference</dt><dd>{}, {:.2f} s, {} rays/s</dd>\n"
                   "<dt>Lights</dt><dd><ul>",
                   escapeHtml(d.scene), escapeHtml(d.device), escapeHtml(d.driver), d.width,
                   d.height, d.shadowMapSize, d.shadowMapSize,
                   escapeHtml(truthRaysText(d.samples, lightsSized(d))), d.referenceSeconds,
                   humanCount(d.raysPerSecond));
    for (const std::string& light : d.lights)
        fmt::format_to(out, "<li>{}</li>", escapeHtml(light));
    if (d.lights.empty())
        s += "<li>none</li>";
    s += "</ul></dd>\n</dl></section>\n";
}

// "size=7, filter=box": the parameters without their family, cut to `limit` characters.
std::string shortParameters(const std::vector<std::pair<std::string, std::string>>& parameters,
                            size_t limit) {
    std::string text;
    for (const auto& [key, value] : parameters)
        text += (text.empty() ? "" : ", ") + key.substr(key.find('.') + 1) + "=" + value;
    if (text.size() > limit)
        text = text.substr(0, limit - 1) + "\u2026";
    return text;
}

// 950, 12.3k, 4.1M: a pixel count that fits under a percentage.
std::string compactCount(uint64_t n) {
    if (n < 10'000)
        return fmt::format("{}", n);
    if (n < 10'000'000)
        return fmt::format("{:.3g}k", static_cast<double>(n) / 1e3);
    return fmt::format("{:.3g}M", static_cast<double>(n) / 1e6);
}

void writeTable(std::string& s, const ReportData& d) {
    auto out = std::back_inserter(s);
    const bool shimmer = !d.cameraPath.empty();
    s += "<h2>Error against the reference</h2>\n<section class=\"card table-wrap\">"
         "<table class=\"results\">\n<thead><tr class=\"groups\"><th rowspan=\"2\" "
         "class=\"sortable\" data-type=\"text\">Technique</th><th colspan=\"5\">Error</th>";
    fmt::format_to(out, "<th colspan=\"{}\" class=\"group\">Artifacts, % of pixels</th>",
                   shimmer ? 5 : 4);
    s += "<th colspan=\"3\" class=\"group\">GPU cost, ms</th></tr>\n<tr>";
    auto header = [&](std::string_view text, std::string_view title, bool first = false) {
        fmt::format_to(out, "<th class=\"sortable{}\" title=\"{}\">{}</th>", first ? " group" : "",
                       title, text);
    };
    header("RMSE", "root-mean-square error of the visibility against the reference (beneath it, "
                   "where the truth is coloured, the first light's red, green and blue channels')");
    header("MAE", "mean absolute error");
    header("Max", "largest absolute error");
    header("Wrong", "misclassified: lit where the reference is shadowed or the reverse");
    header("Wrong <small>off edges</small>",
           "misclassified more than 2 pixels from the reference's shadow edges");
    header("Acne", "fully lit in the reference, visibility below 0.9, off edges", true);
    header("Leak", "fully shadowed in the reference, visibility above 0.1, off edges");
    header("Acne <small>beyond blur</small>", "acne beyond the technique's blur radius");
    header("Leak <small>beyond blur</small>", "leak beyond the technique's blur radius");
    if (shimmer)
        header(fmt::format("Shimmer ({})", escapeHtml(d.cameraPath)),
               fmt::format("mean frame-to-frame change along the {} path, {} frames",
                           escapeHtml(d.cameraPath), d.pathFrames));
    header("Shadow maps", "the depth pass and the technique's own passes over its maps", true);
    header("Per pixel", "visibility and composite (and the contact layer)");
    header("Total", "every pass, the G-buffer included (the cell's tooltip lists them)");
    s += "</tr></thead>\n<tbody>\n";
    // The lowest value of each error column is highlighted when there is something to compare:
    // two rows or more whose values differ (a Max of 1 on every row marks none).
    auto bestOf = [&](double ErrorMetrics::*field) {
        double best = INFINITY, worst = -INFINITY;
        for (const ReportRow& row : d.rows) {
            best = std::min(best, row.metrics.*field);
            worst = std::max(worst, row.metrics.*field);
        }
        return best < worst ? best : NAN;
    };
    auto number = [&](double v, std::string text, std::string_view cls = "",
                      std::string_view title = "") {
        fmt::format_to(out, "<td data-value=\"{}\"{}{}>{}</td>",
                       std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string("NaN"),
                       cls.empty() ? "" : fmt::format(" class=\"{}\"", cls),
                       title.empty() ? "" : fmt::format(" title=\"{}\"", title), text);
    };
    // A percentage with its pixels beneath it (numerator / denominator, both in the tooltip).
    auto cell = [&](const ReportRow& row, double ErrorMetrics::*field, bool asPercent,
                    std::string_view extra = "", std::string_view countKey = "",
                    std::string_view beneath = "") {
        const double v = row.metrics.*field;
        const bool best = v == bestOf(field);
        std::string text = asPercent ? fmt::format("{:.2f}", 100 * v) : fmt::format("{:.4f}", v);
        text += beneath;
        std::string title;
        if (!countKey.empty()) {
            const nlohmann::json c = metricCountsJson(row.metrics)[std::string(countKey)];
            const uint64_t n = c["pixels"], of = c["of"];
            // It may break after the slash: a narrow window keeps every column in view.
            text += fmt::format("<div class=\"count\">{}/<wbr>{}</div>", compactCount(n),
                                compactCount(of));
            title = fmt::format("{} of {} pixels", n, of);
        }
        number(v, text, best ? fmt::format("best{}", extra) : std::string(extra), title);
    };
    for (const ReportRow& row : d.rows) {
        const std::string name = escapeHtml(row.name);
        std::string full;
        for (const auto& [key, value] : row.parameters)
            full += (full.empty() ? "" : ", ") + key + "=" + value;
        fmt::format_to(out,
                       "<tr class=\"technique-row\" data-technique=\"{}\"><td class=\"name\" "
                       "data-value=\"{}\"><strong>{}</strong><div class=\"params\" "
                       "title=\"{}\">{}</div></td>",
                       name, name, name, full.empty() ? "defaults" : escapeHtml(full),
                       full.empty() ? "defaults" : escapeHtml(shortParameters(row.parameters, 34)));
        // A coloured truth's error per channel, stacked under the RMSE: no column of its own, so
        // the table still fits a 1000-pixel window.
        const std::string channels =
            row.rmsePerChannel.size() == 3
                ? fmt::format("<div class=\"channels\" title=\"red, green, blue\">{:.3f}<br>{:.3f}"
                              "<br>{:.3f}</div>",
                              row.rmsePerChannel[0], row.rmsePerChannel[1], row.rmsePerChannel[2])
                : std::string();
        cell(row, &ErrorMetrics::rmse, false, "", "", channels);
        cell(row, &ErrorMetrics::mae, false);
        cell(row, &ErrorMetrics::max, false);
        cell(row, &ErrorMetrics::misclassified, true, "", "misclassified");
        cell(row, &ErrorMetrics::misclassifiedOutsideEdges, true, "",
             "misclassified_outside_edges");
        cell(row, &ErrorMetrics::acne, true, " first", "acne");
        cell(row, &ErrorMetrics::leak, true, "", "leak");
        cell(row, &ErrorMetrics::acneBeyondBlur, true, "", "acne_beyond_blur");
        cell(row, &ErrorMetrics::leakBeyondBlur, true, "", "leak_beyond_blur");
        if (shimmer)
            number(row.shimmer, fmt::format("{:.5f}", row.shimmer));
        double maps = 0, perPixel = 0;
        std::string passes;
        for (const PassTime& p : row.gpuMs) { // the G-buffer's in the total only
            if (p.cost == CostGroup::ShadowMaps)
                maps += p.medianMs;
            else if (p.cost == CostGroup::PerPixel)
                perPixel += p.medianMs;
            passes += fmt::format("{}{} {:.3f}", passes.empty() ? "" : ", ", p.pass, p.medianMs);
        }
        number(maps, fmt::format("{:.3f}", maps), "first");
        number(perPixel, fmt::format("{:.3f}", perPixel));
        number(totalGpuMs(row), fmt::format("{:.3f}", totalGpuMs(row)), "", escapeHtml(passes));
        s += "</tr>\n";
    }
    s += "</tbody></table></section>\n";
    if (const std::string note = hardTruthNote(d); !note.empty())
        fmt::format_to(out, "<p class=\"note hard-truth\"><strong>{}</strong></p>\n",
                       escapeHtml(note));
    if (!d.rows.empty() && !fewPixelsNote(d.rows.front().metrics).empty())
        fmt::format_to(out, "<p class=\"note few-pixels\"><strong>{}</strong></p>\n",
                       fewPixelsNote(d.rows.front().metrics));
    s += "<p class=\"note\">Click a column's header to sort by it. "
         "Percentages are of counted pixels (facing a light, inside its frustum). Acne: fully "
         "lit in the reference but visibility &lt; 0.9; leak: fully shadowed but visibility &gt; "
         "0.1; both, like wrong (misclassified) off edges, more than 2 pixels from the "
         "reference's shadow edges. Beyond blur: the errors among the same pixels that also lie "
         "more than the technique's blur radius from those edges (its declared filter reach, in "
         "texels, projected to the screen at each pixel; at least 2 and at most 8 pixels), so "
         "what remains is self-shadowing and missing shadow rather than the blur a wide kernel "
         "makes; of the same pixels, it never exceeds the plain figure. Under each percentage: "
         "its pixels, of how many. Every pass's time is in the total's tooltip and in "
         "metrics.json.</p>\n";
}

void writeImages(std::string& s, const ReportData& d) {
    auto out = std::back_inserter(s);
    s += "<h2>Images</h2>\n<div class=\"grid-images\">\n";
    fmt::format_to(out,
                   "<figure class=\"card reference\"><figcaption><strong>Reference visibility"
                   "</strong><span class=\"tech\">{}</span></figcaption>"
                   "{}</figure>\n",
                   escapeHtml(truthRaysText(d.samples, lightsSized(d))),
                   imageTag(d.referenceVisibilityPng, "reference", "reference visibility"));
    for (const ReportRow& row : d.rows) {
        const std::string name = escapeHtml(row.name);
        fmt::format_to(
            out,
            "<figure class=\"card technique\" data-technique=\"{0}\"><figcaption>"
            "<strong>{0}</strong><span class=\"tech\">{1}</span></figcaption>\n"
            "<div class=\"triptych\"><div class=\"panel\">{2}<span>Lit image</span>"
            "</div><div class=\"panel\">{3}<span>Visibility</span></div>"
            "<div class=\"panel\">{4}<span>Error: visibility &minus; reference</span>"
            "</div></div></figure>\n",
            name, escapeHtml(row.technique),
            imageTag(row.imagePng, "lit", row.name + " lit image", row.imageFile),
            imageTag(row.visibilityPng, "visibility", row.name + " visibility"),
            imageTag(row.heatmapPng, "heatmap", row.name + " error heat map", row.heatmapFile));
    }
    s += "</div>\n<p class=\"note\">Heat maps: blue is too dark (acne side), red too bright "
         "(leak side); dimmed pixels are not counted; the checker is background.";
    if (d.pageScale > 1)
        fmt::format_to(out,
                       " Images are shown at 1/{0} of the rendered size ({1} &times; {2}), each "
                       "pixel the mean of {0} &times; {0} in linear light; click a lit image or a "
                       "heat map for its full-size file, which sits beside this report.",
                       d.pageScale, d.width, d.height);
    s += "</p>\n";
}

// The rows that did not run, each with why (the device could not hold it).
void writeSkipped(std::string& s, const std::vector<const ReportRow*>& skipped) {
    if (skipped.empty())
        return;
    s += "<h2>Skipped rows</h2>\n<section class=\"card skipped\"><ul>\n";
    for (const ReportRow* row : skipped)
        fmt::format_to(std::back_inserter(s), "<li><strong>{}</strong>: {}</li>\n",
                       escapeHtml(row->name), escapeHtml(row->skipped));
    s += "</ul><p class=\"note\">The device cannot hold these rows at these settings; the "
         "others ran as usual.</p></section>\n";
}

std::string renderRanRows(const ReportData& data, const std::vector<const ReportRow*>& skipped) {
    std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                    "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    fmt::format_to(std::back_inserter(s),
                   "<title>Penumbra report: {}</title>\n<style>{}{}</style>\n",
                   escapeHtml(data.scene), kStyle, kReportInteractiveStyle);
    fmt::format_to(std::back_inserter(s), "</head>\n<body>\n<main data-page-scale=\"{}\">\n",
                   data.pageScale);
    writeHeader(s, data);
    writeTable(s, data);
    writeSkipped(s, skipped);
    s += "<h2>Error against GPU cost</h2>\n<section class=\"card\">\n"
         "<input type=\"radio\" name=\"cost-axis\" id=\"cost-linear\" checked>"
         "<label for=\"cost-linear\">linear cost</label> "
         "<input type=\"radio\" name=\"cost-axis\" id=\"cost-log\">"
         "<label for=\"cost-log\">logarithmic cost</label>\n<div class=\"plots\">\n";
    s += errorVsCostSvg(data.rows, false);
    s += errorVsCostSvg(data.rows, true);
    s += errorVsCostLegend(data.rows);
    s += "</div>\n<p class=\"note\">The dashed line is the Pareto front: the rows no other row "
         "beats on both error and cost (ringed, bold in the legend). A label that would overlap "
         "another is left out: the legend and each point's tooltip name it.</p>\n</section>\n";
    s += overTimeSection(data);
    s += kComparerHtml;
    writeImages(s, data);
    s += "</main>\n<script>";
    s += kReportScript;
    s += "</script>\n</body>\n</html>\n";
    return s;
}

} // namespace

std::string renderHtmlReport(const ReportData& all) {
    // The table, the plot, the comparer and the images show the rows that ran.
    ReportData data = all;
    data.rows.clear();
    std::vector<const ReportRow*> skipped;
    for (const ReportRow& row : all.rows)
        if (row.skipped.empty())
            data.rows.push_back(row);
        else
            skipped.push_back(&row);
    return renderRanRows(data, skipped);
}

nlohmann::json metricsJson(const ReportData& data) {
    nlohmann::json j;
    j["reference"] = {{"samples", data.samples},
                      {"rays_per_pixel", truthRays(data.samples, lightsSized(data))},
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
        if (!row.skipped.empty()) {
            techniques[row.name] = {{"skipped", row.skipped}};
            continue;
        }
        techniques[row.name] = metricsRowJson(row);
        if (!data.cameraPath.empty())
            techniques[row.name]["shimmer"] = row.shimmer;
        if (!row.pathPagesRendered.empty()) {
            techniques[row.name]["path_pages_rendered"] = row.pathPagesRendered;
            techniques[row.name]["path_pages_resident"] = row.pathPagesResident;
        }
    }
    j["techniques"] = techniques;
    j["notes"] = nlohmann::json::array();
    if (const std::string note = hardTruthNote(data); !note.empty())
        j["notes"].push_back(note);
    for (const ReportRow& row : data.rows)
        if (row.skipped.empty()) { // the truth, and so the counts, are the same for every row
            if (!fewPixelsNote(row.metrics).empty())
                j["notes"].push_back(fewPixelsNote(row.metrics));
            break;
        }
    return j;
}

nlohmann::json gpuMsByCost(const std::vector<PassTime>& passes) {
    std::array<double, 3> sums{}; // CostGroup's order
    for (const PassTime& p : passes)
        sums[static_cast<size_t>(p.cost)] += p.medianMs;
    nlohmann::json j = nlohmann::json::object();
    for (CostGroup g : {CostGroup::ShadowMaps, CostGroup::PerPixel, CostGroup::Frame})
        j[std::string(costGroupName(g))] = sums[static_cast<size_t>(g)];
    return j;
}

nlohmann::json metricsRowJson(const ReportRow& row) {
    nlohmann::json gpu = nlohmann::json::object();
    for (const PassTime& p : row.gpuMs) {
        PENUMBRA_CHECK(p.pass != "total", "a GPU pass may not be named total");
        gpu[p.pass] = p.medianMs;
    }
    gpu["total"] = totalGpuMs(row);
    const ErrorMetrics& m = row.metrics;
    nlohmann::json j = {{"rmse", m.rmse},
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
                        {"counts", metricCountsJson(m)},
                        {"gpu_ms", gpu},
                        {"gpu_ms_by_cost", gpuMsByCost(row.gpuMs)}};
    if (!row.rmsePerChannel.empty())
        j["rmse_per_channel"] = row.rmsePerChannel;
    return j;
}

nlohmann::json metricCountsJson(const ErrorMetrics& m) {
    const auto of = [](uint64_t pixels, uint64_t total) {
        return nlohmann::json{{"pixels", pixels}, {"of", total}};
    };
    return {{"misclassified", of(m.misclassifiedPixels, m.pixels)},
            {"misclassified_outside_edges",
             of(m.misclassifiedOutsideEdgesPixels, m.pixelsOutsideEdges)},
            {"acne", of(m.acnePixels, m.truthLit)},
            {"leak", of(m.leakPixels, m.truthShadowed)},
            {"acne_beyond_blur", of(m.acneBeyondBlurPixels, m.truthLit)},
            {"leak_beyond_blur", of(m.leakBeyondBlurPixels, m.truthShadowed)},
            {"leak_near_contact", of(m.leakNearContactPixels, m.nearContact)}};
}

std::string fewPixelsNote(const ErrorMetrics& m) {
    std::string few;
    if (m.truthLit < kFewJudgedPixels)
        few += fmt::format("{} fully lit", m.truthLit);
    if (m.truthShadowed < kFewJudgedPixels)
        few += fmt::format("{}{} fully shadowed", few.empty() ? "" : " and ", m.truthShadowed);
    if (few.empty())
        return "";
    return fmt::format("This view has only {} pixels away from shadow edges (fewer than {}): "
                       "acne and leak rest on too few pixels to rank techniques by them.",
                       few, kFewJudgedPixels);
}

} // namespace penumbra
