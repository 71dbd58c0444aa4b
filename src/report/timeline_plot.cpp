#include "report/timeline_plot.h"

#include "report/html_report.h"
#include "report/report_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace penumbra {

std::vector<SeriesStyle> seriesStyles(const std::vector<std::string>& names) {
    // The layer that keeps a history across frames (docs/techniques.md, "Layers: temporal").
    constexpr std::string_view kTemporal = "+temporal";
    std::vector<SeriesStyle> styles(names.size());
    for (size_t i = 0; i < names.size(); ++i) {
        styles[i].colour = i;
        const std::string_view name = names[i];
        if (!name.ends_with(kTemporal))
            continue;
        const std::string_view base = name.substr(0, name.size() - kTemporal.size());
        for (size_t j = 0; j < names.size(); ++j)
            if (names[j] == base)
                styles[i] = {.colour = j, .dashed = true};
    }
    return styles;
}

std::string overTimeSvg(const std::vector<double>& times, const std::vector<TimeSeries>& series,
                        std::string_view kind, std::string_view quantity) {
    if (times.empty())
        return {};
    constexpr double w = 760, h = 320, left = 70, right = 20, top = 20, bottom = 56;
    constexpr double plotW = w - left - right, plotH = h - top - bottom;
    const double start = times.front(), span = times.back() - times.front();
    double most = 0;
    for (const TimeSeries& s : series)
        for (const double v : s.values)
            if (std::isfinite(v))
                most = std::max(most, v);
    const Axis ay = niceAxis(most);
    // Time from the first frame: a nice axis over the span, its ticks offset by the start.
    const Axis ax = niceAxis(span);
    const auto px = [&](double t) { return left + plotW * (t - start) / ax.max; };
    const auto py = [&](double v) { return top + plotH * (1 - v / ay.max); };
    std::string s = fmt::format("<svg class=\"over-time {}\" viewBox=\"0 0 {} {}\" role=\"img\" "
                                "aria-label=\"{} over time\">\n",
                                kind, w, h, escapeHtml(quantity));
    auto out = std::back_inserter(s);
    for (int i = 0; i <= int(std::lround(ax.max / ax.step)); ++i)
        fmt::format_to(out,
                       "<line class=\"grid\" x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\"/>"
                       "<text class=\"tick\" x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">"
                       "{4:.{5}f}</text>\n",
                       px(start + i * ax.step), top, top + plotH, top + plotH + 18,
                       start + i * ax.step, ax.decimals);
    for (int i = 0; i <= int(std::lround(ay.max / ay.step)); ++i)
        fmt::format_to(out,
                       "<line class=\"grid\" x1=\"{1}\" y1=\"{0:.1f}\" x2=\"{2}\" y2=\"{0:.1f}\"/>"
                       "<text class=\"tick\" x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">"
                       "{5:.{6}f}</text>\n",
                       py(i * ay.step), left, left + plotW, left - 8, py(i * ay.step) + 4,
                       i * ay.step, ay.decimals);
    fmt::format_to(out,
                   "<line class=\"axis\" x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\"/>"
                   "<line class=\"axis\" x1=\"{0}\" y1=\"{3}\" x2=\"{0}\" y2=\"{1}\"/>\n"
                   "<text class=\"label\" x=\"{4}\" y=\"{5}\" text-anchor=\"middle\">time "
                   "(s)</text>\n<text class=\"label\" transform=\"translate(18 {6}) "
                   "rotate(-90)\" text-anchor=\"middle\">{7}</text>\n",
                   left, top + plotH, left + plotW, top, left + plotW / 2, h - 14, top + plotH / 2,
                   escapeHtml(quantity));
    std::vector<std::string> names;
    for (const TimeSeries& one : series)
        names.push_back(one.name);
    const std::vector<SeriesStyle> styles = seriesStyles(names);
    for (size_t r = 0; r < series.size(); ++r) {
        const std::string name = escapeHtml(series[r].name);
        const std::string_view colour = plotColour(styles[r].colour);
        // The line, broken where a value is missing; then a point a frame for its tooltip.
        std::string path;
        bool drawing = false;
        const size_t frames = std::min(times.size(), series[r].values.size());
        for (size_t k = 0; k < frames; ++k) {
            const double v = series[r].values[k];
            if (!std::isfinite(v)) {
                drawing = false;
                continue;
            }
            path += fmt::format("{}{:.1f} {:.1f}", drawing ? " L" : (path.empty() ? "M" : " M"),
                                px(times[k]), py(v));
            drawing = true;
        }
        fmt::format_to(out, "<g class=\"series\" data-technique=\"{}\">\n", name);
        if (!path.empty())
            fmt::format_to(out, "<path class=\"line\" d=\"{}\" stroke=\"{}\"{}/>\n", path, colour,
                           styles[r].dashed ? " stroke-dasharray=\"6 4\"" : "");
        for (size_t k = 0; k < frames; ++k)
            if (std::isfinite(series[r].values[k]))
                fmt::format_to(out,
                               "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"><title>{} "
                               "at {:g} s: {:.6g}</title></circle>\n",
                               px(times[k]), py(series[r].values[k]), colour, name, times[k],
                               series[r].values[k]);
        s += "</g>\n";
    }
    s += "</svg>\n";
    return s;
}

std::string overTimeSection(const ReportData& data) {
    if (data.timelineTimes.empty())
        return {};
    std::vector<TimeSeries> rmse, movingRmse, gpuMs;
    for (const ReportRow& row : data.rows) {
        rmse.push_back({row.name, row.rmseOverTime});
        movingRmse.push_back({row.name, row.movingRmseOverTime});
        gpuMs.push_back({row.name, row.movingGpuMsOverTime});
    }
    const auto meanAndMost = [](const std::vector<double>& v) {
        double sum = 0, most = 0;
        for (const double x : v)
            sum += x, most = std::max(most, x);
        return std::pair(v.empty() ? 0.0 : sum / double(v.size()), most);
    };
    std::string s = fmt::format("<h2>Over time</h2>\n<section class=\"card\">\n<p class=\"note\">"
                                "{} frames from {:g} to {:g} s, each posed, rendered and traced "
                                "(timeline.json and timeline.csv hold the numbers).</p>\n",
                                data.timelineTimes.size(), data.timelineTimes.front(),
                                data.timelineTimes.back());
    s += overTimeSvg(data.timelineTimes, rmse, "rmse", "RMSE at rest");
    s += overTimeSvg(data.timelineTimes, movingRmse, "rmse-moving", "RMSE in motion");
    s += overTimeSvg(data.timelineTimes, gpuMs, "gpu-ms", "total GPU time in motion (ms)");
    s += "<ul class=\"legend\">\n";
    std::vector<std::string> names;
    for (const ReportRow& row : data.rows)
        names.push_back(row.name);
    const std::vector<SeriesStyle> styles = seriesStyles(names);
    for (size_t r = 0; r < data.rows.size(); ++r) {
        const ReportRow& row = data.rows[r];
        const auto [meanRmse, mostRmse] = meanAndMost(row.rmseOverTime);
        const double meanMs = meanAndMost(row.gpuMsOverTime).first;
        const double movingMs = meanAndMost(row.movingGpuMsOverTime).first;
        fmt::format_to(
            std::back_inserter(s),
            "<li><span class=\"dot{}\" style=\"background:{}\"></span>{} <small>RMSE "
            "{:.4f} mean, {:.4f} max; flicker {:.6f}; as played {:.6f}; pop-in {:.4f}, lag {} "
            "frames; "
            "{:.3f} ms a frame at rest, {:.3f} in motion</small></li>\n",
            styles[r].dashed ? " dashed" : "", plotColour(styles[r].colour), escapeHtml(row.name),
            meanRmse, mostRmse, row.flicker, row.movingFlicker, row.popIn, row.lagFrames, meanMs,
            movingMs);
    }
    s += "</ul>\n<p class=\"note\">At rest: each pose rendered from scratch after warm-up (the "
         "technique's steady state). In motion: each pose drawn as the next frame of one renderer, "
         "with what it kept from the frame before. Flicker is the mean change of the error from "
         "frame to frame where the truth held still, at rest and as played (in motion: what a "
         "history or cached pages show from frame to frame); pop-in the worst excess of the error "
         "in "
         "motion over the one at rest; lag the longest run of frames more than 10% worse in "
         "motion (docs/cli.md). A dashed line is a row with the temporal layer, in the colour of "
         "the "
         "same row without it.</p>\n</section>\n";
    return s;
}

} // namespace penumbra
