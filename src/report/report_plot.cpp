#include "report/report_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>

namespace penumbra {
namespace {

// A logarithmic axis over whole decades around [lo, hi] (both > 0), ticks at 1, 2, 5 x 10^k.
struct LogAxis {
    double lo = 0.1, hi = 10;
    std::vector<double> ticks;
};

LogAxis logAxis(double lo, double hi) {
    if (!(lo > 0) || !std::isfinite(lo) || !(hi > 0) || !std::isfinite(hi))
        lo = 1, hi = 1;
    LogAxis a{std::pow(10.0, std::floor(std::log10(lo))),
              std::pow(10.0, std::ceil(std::log10(hi)))};
    if (a.hi <= a.lo)
        a.hi = a.lo * 10;
    for (double decade = a.lo; decade < a.hi * 1.001; decade *= 10)
        for (double m : {1.0, 2.0, 5.0})
            if (m * decade <= a.hi * 1.001)
                a.ticks.push_back(m * decade);
    return a;
}

std::string tickText(double v) {
    // As few digits as the value needs: 0.02, 0.5, 20, 100.
    const int decimals = v >= 1 ? 0 : std::max(0, -int(std::floor(std::log10(v) + 1e-9)));
    return fmt::format("{:.{}f}", v, decimals);
}

constexpr std::string_view kPalette[] = {"#2b6cb0", "#c53030", "#2f855a", "#b7791f",
                                         "#6b46c1", "#0987a0", "#d53f8c", "#4a5568"};

constexpr double kLabelHeight = 15; // a 12-pixel font's line box, and a pixel of air
constexpr double kPointRadius = 6;

} // namespace

std::string_view plotColour(size_t row) {
    return kPalette[row % std::size(kPalette)];
}

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

double totalGpuMs(const ReportRow& row) {
    double total = 0;
    for (const PassTime& p : row.gpuMs)
        total += p.medianMs;
    return total;
}

namespace {
// Each row's point: its total GPU time and RMSE.
std::vector<PlotPoint> pointsOf(const std::vector<ReportRow>& rows) {
    std::vector<PlotPoint> points;
    for (const ReportRow& row : rows)
        points.push_back({row.name, totalGpuMs(row), row.metrics.rmse});
    return points;
}
} // namespace

std::vector<bool> paretoFront(const std::vector<PlotPoint>& points) {
    std::vector<bool> front(points.size(), false);
    auto finite = [](const PlotPoint& p) { return std::isfinite(p.cost) && std::isfinite(p.rmse); };
    for (size_t i = 0; i < points.size(); ++i) {
        if (!finite(points[i]))
            continue;
        bool dominated = false;
        for (size_t j = 0; j < points.size() && !dominated; ++j)
            dominated = j != i && finite(points[j]) && points[j].cost <= points[i].cost &&
                        points[j].rmse <= points[i].rmse &&
                        (points[j].cost < points[i].cost || points[j].rmse < points[i].rmse);
        front[i] = !dominated;
    }
    return front;
}

double labelWidth(const std::string& text) {
    // DejaVu Sans's advances at 12 px, the widest common default face, rounded up: 'm' 0.974 em,
    // 'M' 0.863, 'W' 0.989, 'w' 0.818, other capitals at most 0.77, digits, brackets and the
    // other lower case at most 0.65. The text starts 2 units into its box: 4 units of slack.
    double width = 4.0;
    for (const char c : text)
        width += c == 'm' || c == 'M' || c == 'W' ? 12.0
                 : c == 'w'                       ? 10.0
                 : c >= 'A' && c <= 'Z'           ? 9.3
                                                  : 7.8;
    return width;
}

std::vector<PlotBox> placeLabels(const std::vector<PlotBox>& points, double radius,
                                 const std::vector<PlotBox>& sizes, const PlotBox& bounds) {
    std::vector<PlotBox> placed(points.size());
    std::vector<PlotBox> taken;
    for (const PlotBox& p : points) // the points' own discs, as boxes
        taken.push_back({p.x - radius, p.y - radius, 2 * radius, 2 * radius});
    for (size_t i = 0; i < points.size(); ++i) {
        const double x = points[i].x, y = points[i].y, w = sizes[i].w, h = sizes[i].h;
        const double gap = radius + 2;
        const PlotBox candidates[] = {
            {x + gap, y - h / 2, w, h},           {x - gap - w, y - h / 2, w, h},
            {x - w / 2, y - gap - h, w, h},       {x - w / 2, y + gap, w, h},
            {x + gap, y - gap - h + 2, w, h},     {x + gap, y + gap - 2, w, h},
            {x - gap - w, y - gap - h + 2, w, h}, {x - gap - w, y + gap - 2, w, h}};
        for (const PlotBox& c : candidates) {
            const bool inside = c.x >= bounds.x && c.y >= bounds.y &&
                                c.x + c.w <= bounds.x + bounds.w &&
                                c.y + c.h <= bounds.y + bounds.h;
            if (!inside || std::any_of(taken.begin(), taken.end(),
                                       [&](const PlotBox& t) { return t.intersects(c); }))
                continue;
            placed[i] = c;
            taken.push_back(c);
            break;
        }
    }
    return placed;
}

std::string errorVsCostSvg(const std::vector<ReportRow>& rows, bool logCost) {
    constexpr double w = 760, h = 420, left = 70, right = 20, top = 20, bottom = 56;
    constexpr double plotW = w - left - right, plotH = h - top - bottom;
    const std::vector<PlotPoint> points = pointsOf(rows);
    double maxMs = 0, minMs = INFINITY, maxRmse = 0;
    for (const PlotPoint& p : points) {
        if (std::isfinite(p.cost)) {
            maxMs = std::max(maxMs, p.cost);
            if (p.cost > 0)
                minMs = std::min(minMs, p.cost);
        }
        if (std::isfinite(p.rmse))
            maxRmse = std::max(maxRmse, p.rmse);
    }
    const Axis ax = niceAxis(maxMs), ay = niceAxis(maxRmse);
    const LogAxis lx = logAxis(minMs, maxMs);
    auto px = [&](double ms) {
        if (!logCost)
            return left + plotW * ms / ax.max;
        const double t = (std::log10(std::max(ms, lx.lo)) - std::log10(lx.lo)) /
                         (std::log10(lx.hi) - std::log10(lx.lo));
        return left + plotW * t;
    };
    auto py = [&](double rmse) { return top + plotH * (1 - rmse / ay.max); };
    std::string s = fmt::format("<svg class=\"error-vs-cost{}\" viewBox=\"0 0 {} {}\" "
                                "role=\"img\" aria-label=\"RMSE against total GPU time{}\">\n",
                                logCost ? " log" : "", w, h, logCost ? ", logarithmic" : "");
    auto out = std::back_inserter(s);
    std::vector<std::pair<double, std::string>> xTicks;
    if (logCost)
        for (double t : lx.ticks)
            xTicks.push_back({t, tickText(t)});
    else
        for (int i = 0; i <= int(std::lround(ax.max / ax.step)); ++i)
            xTicks.push_back({i * ax.step, fmt::format("{:.{}f}", i * ax.step, ax.decimals)});
    for (const auto& [value, text] : xTicks)
        fmt::format_to(out,
                       "<line class=\"grid\" x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\"/>"
                       "<text class=\"tick\" x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">"
                       "{4}</text>\n",
                       px(value), top, top + plotH, top + plotH + 18, text);
    for (int i = 0; i <= int(std::lround(ay.max / ay.step)); ++i) {
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
                   "time (ms{})</text>\n<text class=\"label\" transform=\"translate(18 {}) "
                   "rotate(-90)\" text-anchor=\"middle\">RMSE</text>\n",
                   left + plotW / 2, h - 14, logCost ? ", logarithmic" : "", top + plotH / 2);

    // The front: a staircase through its points from the cheapest to the most accurate.
    const std::vector<bool> front = paretoFront(points);
    std::vector<size_t> order;
    for (size_t i = 0; i < points.size(); ++i)
        if (front[i])
            order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return points[a].cost < points[b].cost; });
    if (order.size() >= 2) {
        std::string path =
            fmt::format("M{:.1f} {:.1f}", px(points[order[0]].cost), py(points[order[0]].rmse));
        for (size_t k = 1; k < order.size(); ++k)
            path += fmt::format(" H{:.1f} V{:.1f}", px(points[order[k]].cost),
                                py(points[order[k]].rmse));
        fmt::format_to(out, "<path class=\"front\" d=\"{}\"/>\n", path);
    }

    // Labels: the front's name first (beside its cheapest point), then each point's.
    std::vector<PlotBox> anchors, sizes;
    std::vector<std::string> texts;
    std::vector<size_t> rowOf;
    if (!order.empty()) {
        anchors.push_back({px(points[order[0]].cost), py(points[order[0]].rmse)});
        texts.push_back("Pareto front");
        rowOf.push_back(SIZE_MAX);
    }
    for (size_t i = 0; i < points.size(); ++i)
        if (std::isfinite(points[i].cost) && std::isfinite(points[i].rmse)) {
            anchors.push_back({px(points[i].cost), py(points[i].rmse)});
            texts.push_back(points[i].name);
            rowOf.push_back(i);
        }
    for (const std::string& t : texts)
        sizes.push_back({0, 0, labelWidth(t), kLabelHeight});
    const std::vector<PlotBox> labels =
        placeLabels(anchors, kPointRadius, sizes, {left, top, plotW + right, plotH});
    for (size_t k = 0; k < anchors.size(); ++k) {
        const size_t i = rowOf[k];
        if (i != SIZE_MAX) {
            const std::string name = escapeHtml(points[i].name);
            fmt::format_to(out,
                           "<g class=\"point{}\" data-technique=\"{}\"><circle cx=\"{:.1f}\" "
                           "cy=\"{:.1f}\" r=\"{}\" fill=\"{}\"><title>{}: {:.3f} ms, RMSE "
                           "{:.4f}{}</title></circle></g>\n",
                           front[i] ? " on-front" : "", name, anchors[k].x, anchors[k].y,
                           kPointRadius, plotColour(i), name, points[i].cost, points[i].rmse,
                           front[i] ? " (on the Pareto front)" : "");
        }
    }
    // After the points, so that no disc covers a label.
    for (size_t k = 0; k < anchors.size(); ++k) {
        if (labels[k].w == 0)
            continue;
        fmt::format_to(out, "<text class=\"{}\" x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n",
                       rowOf[k] == SIZE_MAX ? "plot-label front-label" : "plot-label",
                       labels[k].x + 2, labels[k].y + kLabelHeight - 3.5, escapeHtml(texts[k]));
    }
    s += "</svg>\n";
    return s;
}

std::string errorVsCostLegend(const std::vector<ReportRow>& rows) {
    const std::vector<PlotPoint> points = pointsOf(rows);
    const std::vector<bool> front = paretoFront(points);
    std::string s = "<ul class=\"legend\">\n";
    for (size_t i = 0; i < rows.size(); ++i)
        s += fmt::format("<li{}><span class=\"dot\" style=\"background:{}\"></span>{} "
                         "<small>{:.3f} ms, {:.4f}</small></li>\n",
                         front[i] ? " class=\"on-front\"" : "", plotColour(i),
                         escapeHtml(rows[i].name), points[i].cost, points[i].rmse);
    return s + "</ul>\n";
}

} // namespace penumbra
