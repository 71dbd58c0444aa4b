// The merged report (merge_report.h). The plot is compare's (report_plot.h), fed one row per
// setting with its shadow time (every pass but the G-buffer) as its cost.
#include "sweep/merge_report.h"

#include "report/html_report.h"
#include "report/report_plot.h"
#include "report/report_script.h"
#include "sweep/truth_bootstrap.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::sweep {
namespace {

constexpr std::string_view kStyle = R"(
* { box-sizing: border-box; }
:root { --ink: #1f2933; --muted: #616e7c; --line: #e4e7eb; --card: #fff; --accent: #2b6cb0; }
body { margin: 0; background: #f5f7fa; color: #1f2933;
  font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, Arial, sans-serif; }
main { max-width: 1400px; margin: 0 auto; padding: 32px 24px 64px; }
h1 { font-size: 26px; margin: 0 0 4px; } h2 { font-size: 19px; margin: 36px 0 12px; }
.card { background: #fff; border: 1px solid #e4e7eb; border-radius: 10px; padding: 18px 20px;
  margin-bottom: 16px; }
table { border-collapse: collapse; width: 100%; table-layout: fixed; font-size: 13px;
  font-variant-numeric: tabular-nums; }
th, td { padding: 6px 6px; border-bottom: 1px solid #e4e7eb; text-align: right;
  overflow-wrap: anywhere; }
th.setting { width: 22%; } table.cost th.setting { width: 30%; }
th { background: #f0f3f7; font-weight: 600; } td.l, th.l { text-align: left; }
td.front { font-weight: 600; color: #22543d; } .ci { color: #616e7c; font-size: 11px; display: block; }
.note { color: #616e7c; font-size: 13px; margin: 8px 0 0; }
svg.error-vs-cost { width: 100%; max-width: 900px; height: auto; display: block; font-size: 12px; }
svg .grid { stroke: #e4e7eb; } svg .axis { stroke: #52606d; stroke-width: 1.2; }
svg .tick { fill: #616e7c; } svg .label { fill: #1f2933; font-size: 13px; }
svg .point text { fill: #1f2933; font-size: 12px; } svg circle { stroke: #fff; stroke-width: 1.5; }
ul.legend { overflow-wrap: anywhere; }
)";

std::string figure(double v) {
    return std::isfinite(v) ? fmt::format("{:.3g}", v) : "&ndash;";
}

// "leak_beyond_blur" -> "leak beyond blur": a header that wraps between words.
std::string headerOf(std::string_view name) {
    std::string text(name);
    std::replace(text.begin(), text.end(), '_', ' ');
    return text;
}

void writeGroup(std::string& s, const GroupSummary& g) {
    auto out = std::back_inserter(s);
    fmt::format_to(out, "<h2>{}</h2>\n",
                   g.name == "corpus" ? "The corpus: every view" : escapeHtml(g.name));
    std::vector<ReportRow> rows;
    for (const SettingSummary& st : g.settings) {
        ReportRow row{.name = st.setting, .technique = st.technique};
        row.metrics.rmse = st.metrics.at("rmse").value;
        // The merged figure is already every pass but the frames: one entry of one group.
        row.gpuMs = {{.pass = "technique", .cost = CostGroup::ShadowMaps, .medianMs = st.shadowMs}};
        rows.push_back(std::move(row));
    }
    s += "<section class=\"card\"><div class=\"plots\">\n";
    s += errorVsCostSvg(rows, false);
    s += errorVsCostLegend(rows);
    s += "</div><p class=\"note\">RMSE against the technique's GPU time (every pass but the "
         "G-buffer: the shadow maps, their post passes and the per-pixel evaluation), means "
         "over the views. The dashed line is the Pareto front.</p></section>\n";
    s += "<section class=\"card\"><table class=\"merged\"><thead><tr>"
         "<th class=\"l setting\">setting</th>";
    for (const MetricField& f : kMetricFields)
        fmt::format_to(out, "<th>{}</th>", headerOf(f.name));
    s += "</tr></thead><tbody>\n";
    for (const SettingSummary& st : g.settings) {
        fmt::format_to(out, "<tr><td class=\"l{}\">{}{}</td>", st.onFront ? " front" : "",
                       escapeHtml(st.setting), st.onFront ? " &#9670;" : "");
        for (const MetricField& f : kMetricFields) {
            const Estimate& e = st.metrics.at(std::string(f.name));
            fmt::format_to(out, "<td>{} <small>#{}</small><span class=\"ci\">{} .. {}</span></td>",
                           figure(e.value), e.rank, figure(e.lo), figure(e.hi));
        }
        s += "</tr>\n";
    }
    s += "</tbody></table>\n<table class=\"cost\"><thead><tr><th class=\"l setting\">setting"
         "</th><th>views</th><th>per-pixel ms</th><th>shadow ms</th><th class=\"l\">"
         "device</th></tr></thead><tbody>\n";
    for (const SettingSummary& st : g.settings) {
        std::string devices;
        for (const std::string& d : st.devices)
            devices += (devices.empty() ? "" : "; ") + escapeHtml(d);
        fmt::format_to(out,
                       "<tr><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td>"
                       "<td class=\"l\">{}</td></tr>\n",
                       escapeHtml(st.setting), st.views, figure(st.visibilityMs),
                       figure(st.shadowMs), devices);
    }
    s += "</tbody></table></section>\n";
}

} // namespace

std::string mergeHtml(const MergeResult& m, const std::string& title) {
    std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                    "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    auto out = std::back_inserter(s);
    fmt::format_to(out,
                   "<title>Penumbra sweep: {}</title>\n<style>{}</style>\n</head>\n<body>\n"
                   "<main>\n<h1>Penumbra sweep</h1>\n",
                   escapeHtml(title), std::string(kStyle) + std::string(kReportInteractiveStyle));
    fmt::format_to(out,
                   "<section class=\"card\"><p>{}: {} task(s), {} failed. Each figure is the "
                   "mean over the views a setting ran on; under it, its 95% interval from the "
                   "ground truth's finite samples (a parametric bootstrap of each pixel's "
                   "binomial ray count, {} replicates, basic bootstrap interval) and after it (#) "
                   "its rank among the "
                   "settings, 1 the least error. &#9670; marks the Pareto front.</p></section>\n",
                   escapeHtml(title), m.tasks, m.failed.size(), kBootstrapReplicates);
    for (const GroupSummary& g : m.groups)
        writeGroup(s, g);
    if (!m.failed.empty()) {
        s += "<h2>Failed tasks</h2>\n<section class=\"card\"><ul>\n";
        for (const TaskRecord& r : m.failed)
            fmt::format_to(out, "<li><strong>{}</strong> on {}, {}{}: {}</li>\n",
                           escapeHtml(r.setting), escapeHtml(r.scene), escapeHtml(r.light),
                           r.time ? fmt::format(", at {} s", *r.time) : "", escapeHtml(r.error));
        s += "</ul></section>\n";
    }
    s += "</main>\n</body>\n</html>\n";
    return s;
}

} // namespace penumbra::sweep
