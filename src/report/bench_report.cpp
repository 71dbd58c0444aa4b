#include "report/bench_report.h"

#include "report/report_plot.h"
#include "report/stats.h"
#include "shadows/technique.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>

namespace penumbra {
namespace {

nlohmann::json statsJson(const PassStats& s) {
    return {{"median", s.median}, {"p10", s.p10}, {"p90", s.p90}};
}

std::string escape(const std::string& text) {
    std::string out;
    for (char c : text)
        out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    return out;
}

// bench.html's virtual-pages cell: pages rendered per timed frame (the last `frames` of every
// frame's counts; the warm-ups render the view's pages), and the pool's occupancy.
std::string virtualPagesCell(const VirtualMapInfo& v, uint32_t frames) {
    const std::vector<uint32_t>& all = v.renderedPerFrame;
    std::vector<uint32_t> timed(all.end() - std::min<ptrdiff_t>(frames, ptrdiff_t(all.size())),
                                all.end());
    std::sort(timed.begin(), timed.end());
    const uint32_t median = timed.empty() ? 0 : timed[timed.size() / 2];
    const uint32_t most = timed.empty() ? 0 : timed.back();
    return fmt::format("{} per frame <small>(most {})</small>, {} of {} resident "
                       "<small>({:.1f}%)</small>",
                       median, most, v.resident, v.poolPages,
                       v.poolPages ? 100.0 * v.resident / v.poolPages : 0.0);
}

// A pass's name may break after its underscores (vsm_blur_columns), so a table of many passes
// fits a narrow window.
std::string wrappable(std::string name) {
    for (size_t at = name.find('_'); at != std::string::npos; at = name.find('_', at + 6))
        name.insert(at + 1, "<wbr>");
    return name;
}

std::string sweptLabel(const BenchRun& run) {
    std::string label;
    for (const auto& [key, value] : run.swept)
        label += (label.empty() ? "" : ", ") + key + "=" + value;
    return label.empty() ? "defaults" : label;
}

const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

// The value a run gave `key` (empty when it was not swept).
std::string sweptValue(const BenchRun& run, const std::string& key) {
    for (const auto& [k, v] : run.swept)
        if (k == key)
            return v;
    return {};
}

// One SVG chart: the median ms of every pass (and the total) against the values of `key`, over
// `runs` (one technique, the other swept keys at their first values).
std::string chart(const std::string& title, const std::string& key,
                  const std::vector<const BenchRun*>& runs) {
    constexpr double W = 580, H = 280, left = 64, right = 150, top = 30, bottom = 40;
    std::vector<double> xs;
    bool numeric = true;
    for (const BenchRun* r : runs) {
        const std::string v = sweptValue(*r, key);
        double x = 0;
        const auto [end, error] = std::from_chars(v.data(), v.data() + v.size(), x);
        numeric = numeric && error == std::errc() && end == v.data() + v.size();
        xs.push_back(x);
    }
    if (!numeric) // choices: evenly spaced in the order given
        for (size_t i = 0; i < xs.size(); ++i)
            xs[i] = static_cast<double>(i);
    const double xMin = *std::min_element(xs.begin(), xs.end());
    const double xMax = *std::max_element(xs.begin(), xs.end());
    std::map<std::string, std::vector<double>> series; // pass -> median per run
    std::vector<std::string> order;
    double yMax = 0;
    for (const BenchRun* r : runs) {
        for (const PassStats& p : r->passes)
            if (!series.count(p.pass))
                order.push_back(p.pass), series[p.pass] = {};
    }
    order.push_back("total");
    for (const BenchRun* r : runs) {
        for (const std::string& pass : order) {
            double ms = 0;
            if (pass == "total")
                ms = r->total.median;
            for (const PassStats& p : r->passes)
                if (p.pass == pass)
                    ms = p.median;
            series[pass].push_back(ms);
            yMax = std::max(yMax, ms);
        }
    }
    const Axis axis = niceAxis(yMax); // ticks at 1, 2 or 5 x 10^k
    yMax = axis.max;
    auto px = [&](double x) {
        return left + (xMax > xMin ? (x - xMin) / (xMax - xMin) : 0.5) * (W - left - right);
    };
    auto py = [&](double y) { return H - bottom - y / yMax * (H - top - bottom); };
    std::string svg = fmt::format("<svg width='{}' height='{}' viewBox='0 0 {} {}'>"
                                  "<text x='{}' y='18' font-size='13' font-weight='bold'>{}</text>"
                                  "<line x1='{}' y1='{}' x2='{}' y2='{}' stroke='#333'/>"
                                  "<line x1='{}' y1='{}' x2='{}' y2='{}' stroke='#333'/>",
                                  W, H, W, H, left, escape(title), left, top, left, H - bottom,
                                  left, H - bottom, W - right, H - bottom);
    for (int i = 0; i <= int(std::lround(axis.max / axis.step)); ++i) { // the ms axis
        const double y = axis.step * i;
        svg += fmt::format("<text x='{}' y='{}' font-size='10' text-anchor='end'>{:.{}f}</text>"
                           "<line x1='{}' y1='{}' x2='{}' y2='{}' stroke='#ddd'/>",
                           left - 4, py(y) + 3, y, axis.decimals, left, py(y), W - right, py(y));
    }
    for (size_t i = 0; i < runs.size(); ++i)
        svg += fmt::format("<text x='{}' y='{}' font-size='10' text-anchor='middle'>{}</text>",
                           px(xs[i]), H - bottom + 14, escape(sweptValue(*runs[i], key)));
    svg += fmt::format("<text x='{}' y='{}' font-size='11' text-anchor='middle'>{}</text>"
                       "<text x='12' y='{}' font-size='11' transform='rotate(-90 12 {})' "
                       "text-anchor='middle'>GPU ms (median)</text>",
                       (left + W - right) / 2, H - 6, escape(key), H / 2, H / 2);
    for (size_t s = 0; s < order.size(); ++s) {
        const std::string colour = order[s] == "total" ? "#000" : kColours[s % 10];
        std::string points;
        for (size_t i = 0; i < runs.size(); ++i)
            points += fmt::format("{:.1f},{:.1f} ", px(xs[i]), py(series[order[s]][i]));
        svg += fmt::format("<polyline fill='none' stroke='{}' stroke-width='2' points='{}'/>",
                           colour, points);
        svg += fmt::format("<text x='{}' y='{}' font-size='11' fill='{}'>{}</text>", W - right + 10,
                           top + 14 * double(s) + 10, colour, escape(order[s]));
    }
    return svg + "</svg>";
}

} // namespace

PassStats passStats(std::string pass, std::vector<double> frameMs) {
    PassStats s{.pass = std::move(pass)};
    if (frameMs.empty())
        return s;
    std::sort(frameMs.begin(), frameMs.end());
    auto at = [&](double q) {
        const double pos = q * double(frameMs.size() - 1);
        const auto i = static_cast<size_t>(std::floor(pos));
        const size_t j = std::min(i + 1, frameMs.size() - 1);
        return frameMs[i] + (pos - double(i)) * (frameMs[j] - frameMs[i]);
    };
    s.median = at(0.5);
    s.p10 = at(0.1);
    s.p90 = at(0.9);
    return s;
}

void measureRun(BenchRun& run, const RenderResult& result) {
    std::vector<double> totals;
    for (const PassTime& p : result.passes) {
        run.passes.push_back(passStats(p.pass, p.frameMs));
        totals.resize(std::max(totals.size(), p.frameMs.size()), 0.0);
        for (size_t i = 0; i < p.frameMs.size(); ++i)
            totals[i] += p.frameMs[i];
    }
    run.total = passStats("total", totals);
}

void estimateMemory(BenchRun& run, const RenderOptions& o, const RenderResult& result) {
    const shadows::TechniqueModule& module = shadows::moduleOf(o.technique);
    uint64_t views = 0, lights = 0;
    for (const LightShadow& l : result.lights) {
        views += l.views.size();
        lights += l.visibilityIndex >= 0;
    }
    run.transient = result.transientMemory;
    run.shadowMapBytes = shadows::shadowMapBytes(module, o.shadowMapSize, o.parameters) * views;
    if (result.virtualMaps) { // the pool, and a page table and its requests per frame in flight
        run.virtualMaps = result.virtualMaps;
        run.shadowMapBytes = result.virtualMaps->poolBytes + 4 * result.virtualMaps->tableBytes;
    }
    // G-buffer depth 4, normal 8, albedo 4; visibility 4 per light; colour 4; position and
    // normal for readback 32.
    run.screenBytes = uint64_t{o.width} * o.height * (16 + 4 * std::max<uint64_t>(lights, 1) + 36);
    if (result.field) {
        run.fieldBytes = result.field->bytes;
        run.fieldBuildMs = result.field->buildGpuMs;
    }
}

nlohmann::json benchJson(const BenchData& data) {
    nlohmann::json runs = nlohmann::json::array();
    for (const BenchRun& r : data.runs) {
        const TechniqueInfo& info = findTechnique(techniqueName(r.technique));
        nlohmann::json parameters = nlohmann::json::object();
        for (const ParameterInfo& p : allParameters()) {
            const std::string_view family = p.key.substr(0, p.key.find('.'));
            if (std::find(info.families.begin(), info.families.end(), family) ==
                info.families.end())
                continue;
            if (p.type == ParameterType::Choice || p.type == ParameterType::Bool)
                parameters[std::string(p.key)] = r.parameters.text(p.key);
            else
                parameters[std::string(p.key)] = r.parameters.number(p.key);
        }
        nlohmann::json swept = nlohmann::json::object();
        for (const auto& [key, value] : r.swept)
            swept[key] = value;
        if (!r.skipped.empty()) {
            runs.push_back({{"technique", techniqueName(r.technique)},
                            {"swept", swept},
                            {"parameters", parameters},
                            {"skipped", r.skipped}});
            continue;
        }
        nlohmann::json gpu = nlohmann::json::object();
        for (const PassStats& p : r.passes)
            gpu[p.pass] = statsJson(p);
        nlohmann::json run = {{"technique", techniqueName(r.technique)},
                              {"swept", swept},
                              {"parameters", parameters},
                              {"gpu_ms", gpu},
                              {"gpu_ms_total", statsJson(r.total)},
                              {"gpu_memory_bytes", r.memoryBytes()},
                              {"memory",
                               {{"shadow_maps", r.shadowMapBytes},
                                {"screen_targets", r.screenBytes},
                                {"distance_field", r.fieldBytes},
                                {"transient_separate", r.transient.separateBytes},
                                {"transient_shared", r.transient.sharedBytes}}}};
        if (r.fieldBytes > 0)
            run["distance_field_build_gpu_ms"] = r.fieldBuildMs;
        if (const auto& v = r.virtualMaps)
            run["virtual_maps"] = {
                {"pages_requested", v->requested},
                {"pages_resident", v->resident},
                {"pages_rendered_per_frame", v->renderedPerFrame},
                {"pages_dropped", v->dropped},
                {"pool_pages", v->poolPages},
                {"pool_occupancy", v->poolPages ? double(v->resident) / v->poolPages : 0.0}};
        runs.push_back(run);
    }
    return {{"device", deviceJson(data.device)},
            {"scene", data.scene},
            {"image", {{"width", data.width}, {"height", data.height}}},
            {"shadow_map_size", data.shadowMapSize},
            {"frames", data.frames},
            {"sweeps", data.sweepKeys},
            {"runs", runs}};
}

std::string benchHtml(const BenchData& data) {
    std::string html = fmt::format(
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>penumbra bench: {}</title>"
        "<style>body{{font-family:sans-serif;margin:24px}}table{{border-collapse:collapse}}"
        "td,th{{border:1px solid #ccc;padding:3px 6px;text-align:right;font-size:13px}}"
        "td small{{display:block;color:#666}}svg{{max-width:100%;height:auto}}"
        "th{{background:#eee}}td.l{{text-align:left}}svg{{margin:8px 16px 8px 0}}</style>"
        "</head><body><h1>penumbra bench: {}</h1><p>{} ({}), {}x{}, shadow map {}, "
        "median, 10th and 90th percentile of {} frames after a warm-up frame, GPU ms per "
        "pass.</p>",
        escape(data.scene), escape(data.scene), escape(data.device.name),
        escape(data.device.driverName), data.width, data.height, data.shadowMapSize, data.frames);
    for (const std::string& key : data.sweepKeys)
        for (const TechniqueInfo& t : allTechniques()) {
            std::vector<const BenchRun*> runs;
            for (const BenchRun& r : data.runs) {
                if (r.technique != t.id || sweptValue(r, key).empty() || !r.skipped.empty())
                    continue;
                bool othersFirst = true; // the other swept keys at their first value
                for (const auto& [k, v] : r.swept)
                    for (const BenchRun& first : data.runs)
                        if (first.technique == t.id && k != key && !sweptValue(first, k).empty()) {
                            othersFirst = othersFirst && sweptValue(first, k) == v;
                            break;
                        }
                if (othersFirst)
                    runs.push_back(&r);
            }
            if (runs.size() >= 2)
                html += chart(fmt::format("{}: cost against {}", t.name, key), key, runs);
        }
    html += "<table><tr><th>technique</th><th>swept</th>";
    std::vector<std::string> passes;
    for (const BenchRun& r : data.runs)
        for (const PassStats& p : r.passes)
            if (std::find(passes.begin(), passes.end(), p.pass) == passes.end())
                passes.push_back(p.pass);
    for (const std::string& p : passes)
        html += "<th>" + wrappable(escape(p)) + "</th>";
    const bool anyVirtual = std::any_of(data.runs.begin(), data.runs.end(), [](const BenchRun& r) {
        return r.virtualMaps.has_value();
    });
    html += "<th>total</th><th>memory MiB</th>";
    if (anyVirtual)
        html += "<th title='virtual.enabled: pages rendered per timed frame (median and most), "
                "and pages resident in the pool'>virtual pages</th>";
    html += "</tr>";
    for (const BenchRun& r : data.runs) {
        html += fmt::format("<tr><td class='l'>{}</td><td class='l'>{}</td>",
                            techniqueName(r.technique), escape(sweptLabel(r)));
        if (!r.skipped.empty()) { // the device cannot hold it: say why across the row
            html += fmt::format("<td class='l' colspan='{}'>skipped: {}</td></tr>",
                                passes.size() + 2 + (anyVirtual ? 1 : 0), escape(r.skipped));
            continue;
        }
        for (const std::string& name : passes) {
            auto it = std::find_if(r.passes.begin(), r.passes.end(),
                                   [&](const PassStats& p) { return p.pass == name; });
            html += it == r.passes.end()
                        ? "<td></td>"
                        : fmt::format("<td>{:.3f} <small>[{:.3f}, {:.3f}]</small></td>", it->median,
                                      it->p10, it->p90);
        }
        html += fmt::format("<td>{:.3f}</td><td>{:.1f}</td>", r.total.median,
                            double(r.memoryBytes()) / (1 << 20));
        if (anyVirtual)
            html += r.virtualMaps ? "<td>" + virtualPagesCell(*r.virtualMaps, data.frames) + "</td>"
                                  : "<td></td>";
        html += "</tr>";
    }
    return html + "</table></body></html>\n";
}

} // namespace penumbra
