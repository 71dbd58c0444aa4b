#pragma once
// report.html's plots over time (`compare --timeline`): one line per row of a quantity measured
// each frame (RMSE, GPU time) against the frame's time, with a point per frame whose tooltip
// gives its value, on a "nice" axis from 0 (report_plot.h).
#include "report/html_report.h"

#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct TimeSeries {
    std::string name;           // the row's
    std::vector<double> values; // one per time; non-finite values break the line
};

// The plot as inline SVG of class "over-time" and `kind` (e.g. "rmse"), the y axis labelled
// `quantity`; series i in the palette's colour i, as the error-against-cost plot colours row i,
// but a row `<row>+temporal` beside its `<row>`: in that row's colour, dashed, so that each
// temporal row reads against its one-frame version. Empty when there are no times.
std::string overTimeSvg(const std::vector<double>& times, const std::vector<TimeSeries>& series,
                        std::string_view kind, std::string_view quantity);

// The palette index series i is drawn in (overTimeSvg), and whether it is dashed.
struct SeriesStyle {
    size_t colour = 0;
    bool dashed = false;
};
std::vector<SeriesStyle> seriesStyles(const std::vector<std::string>& names);

// report.html's "Over time" section: RMSE and GPU time over the timeline for every row that
// ran, and a legend with each row's mean and largest RMSE, flicker and mean GPU time. Empty
// without a timeline.
std::string overTimeSection(const ReportData& data);

} // namespace penumbra
