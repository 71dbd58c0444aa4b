// report.html's plots over time (src/report/timeline_plot.h): each row a line through its frames,
// x proportional to the time and y to the value from a zero at the plot's foot, broken where a
// value is missing; the section shows only with a timeline.
#include "report/html_report.h"
#include "report/report_plot.h"
#include "report/timeline_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

using namespace penumbra;

namespace {

struct Point {
    double x = 0, y = 0;
};

// The points of the series `name` in `svg`: its circles' centres, in order.
std::vector<Point> pointsOf(const std::string& svg, const std::string& name) {
    const size_t start = svg.find("<g class=\"series\" data-technique=\"" + name + "\">");
    EXPECT_NE(start, std::string::npos) << name;
    const std::string group = svg.substr(start, svg.find("</g>", start) - start);
    std::vector<Point> points;
    const std::regex circle(R"re(<circle cx="([0-9.]+)" cy="([0-9.]+)")re");
    for (auto it = std::sregex_iterator(group.begin(), group.end(), circle);
         it != std::sregex_iterator(); ++it)
        points.push_back({std::stod((*it)[1]), std::stod((*it)[2])});
    return points;
}

std::string pathOf(const std::string& svg, const std::string& name) {
    const size_t start = svg.find("<g class=\"series\" data-technique=\"" + name + "\">");
    const std::string group = svg.substr(start, svg.find("</g>", start) - start);
    std::smatch m;
    return std::regex_search(group, m, std::regex(R"re(<path class="line" d="([^"]*)")re"))
               ? m[1].str()
               : "";
}

} // namespace

TEST(ReportPlot, OverTimeEachRowIsALineThroughItsFramesInProportion) {
    EXPECT_EQ(overTimeSvg({}, {{"a", {}}}, "rmse", "RMSE"), "");
    const std::vector<double> times = {2.0, 2.5, 3.0, 4.0};
    const std::string svg = overTimeSvg(
        times, {{"a<b", {0.1, 0.2, 0.05, 0.4}}, {"c", {0.3, NAN, 0.1, 0.2}}}, "rmse", "RMSE");
    EXPECT_NE(svg.find("<svg class=\"over-time rmse\""), std::string::npos);
    const std::vector<Point> a = pointsOf(svg, "a&lt;b");
    ASSERT_EQ(a.size(), 4u);
    // x: from the first frame at the plot's left edge, in proportion to the time.
    EXPECT_NEAR(a[0].x, 70.0, 0.051);
    for (size_t k = 1; k < times.size(); ++k)
        EXPECT_NEAR((a[k].x - a[0].x) / (times[k] - times[0]), (a[3].x - a[0].x) / 2.0, 0.1) << k;
    EXPECT_GT(a[3].x, a[2].x);
    // y: the foot of the plot is 0, and the height above it is in proportion to the value.
    const double foot = 20 + (320 - 20 - 56);
    const std::vector<double> values = {0.1, 0.2, 0.05, 0.4};
    for (size_t k = 0; k < values.size(); ++k)
        EXPECT_NEAR((foot - a[k].y) / values[k], (foot - a[3].y) / 0.4, 2.0) << k;
    EXPECT_LT(a[3].y, a[1].y) << "more error is higher";
    // A missing value breaks the line and has no point.
    const std::vector<Point> c = pointsOf(svg, "c");
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(pathOf(svg, "c").find(" L"), pathOf(svg, "c").rfind(" L")) << pathOf(svg, "c");
    EXPECT_EQ(pathOf(svg, "c").rfind("M"), pathOf(svg, "c").find(" M") + 1) << pathOf(svg, "c");
    EXPECT_EQ(pathOf(svg, "a&lt;b").find(" M"), std::string::npos);
    // Row i's colour is the error-against-cost plot's, and each point says its value.
    EXPECT_NE(svg.find("stroke=\"" + std::string(plotColour(1)) + "\""), std::string::npos);
    EXPECT_NE(svg.find("<title>a&lt;b at 2.5 s: 0.2</title>"), std::string::npos);
    EXPECT_EQ(svg.find("a<b"), std::string::npos);
}

TEST(ReportPlot, TheOverTimeSectionShowsOnlyWithATimeline) {
    ReportData data{.scene = "builtin:pendulum"};
    ReportRow row{.name = "hard"};
    row.rmseOverTime = {0.1, 0.2, 0.05};
    row.gpuMsOverTime = {1.0, 2.0, 3.0};
    row.movingRmseOverTime = {0.1, 0.4, 0.05};
    row.movingGpuMsOverTime = {1.0, 5.0, 3.0};
    row.flicker = 0.001;
    row.movingFlicker = 0.003;
    row.popIn = 0.2;
    row.lagFrames = 1;
    data.rows = {row};
    EXPECT_EQ(overTimeSection(data), "");
    EXPECT_EQ(renderHtmlReport(data).find("Over time"), std::string::npos);
    data.timelineTimes = {0.0, 0.5, 1.0};
    const std::string section = overTimeSection(data);
    EXPECT_NE(section.find("<h2>Over time</h2>"), std::string::npos);
    EXPECT_NE(section.find("3 frames from 0 to 1 s"), std::string::npos);
    EXPECT_NE(section.find("class=\"over-time rmse\""), std::string::npos);
    EXPECT_NE(section.find("class=\"over-time gpu-ms\""), std::string::npos);
    EXPECT_NE(section.find("class=\"over-time rmse-moving\""), std::string::npos);
    // The RMSE plots: at rest, then in motion; the GPU time plotted is the one in motion.
    EXPECT_NE(section.find("hard at 0.5 s: 0.2</title>"), std::string::npos);
    EXPECT_NE(section.find("hard at 0.5 s: 0.4</title>"), std::string::npos);
    EXPECT_LT(section.find("hard at 0.5 s: 0.2</title>"),
              section.find("hard at 0.5 s: 0.4</title>"));
    EXPECT_NE(section.find("hard at 0.5 s: 5</title>"), std::string::npos);
    EXPECT_EQ(section.find("hard at 0.5 s: 2</title>"), std::string::npos);
    EXPECT_NE(section.find("RMSE 0.1167 mean, 0.2000 max; flicker 0.001000; as played 0.003000; "
                           "pop-in 0.2000, lag 1 frames; 2.000 ms a frame at rest, 3.000 in "
                           "motion"),
              std::string::npos)
        << section;
    EXPECT_NE(renderHtmlReport(data).find(section), std::string::npos);
}

// A temporal row is drawn beside its one-frame version: in that row's colour, dashed; a temporal
// row without its one-frame version, and every other row, in its own colour, solid.
TEST(ReportPlot, ATemporalRowIsDashedInItsOneFrameRowsColour) {
    const std::vector<SeriesStyle> styles =
        seriesStyles({"pcss", "smrt+temporal", "smrt", "pcss+temporal", "hard+temporal", "smrt+"});
    ASSERT_EQ(styles.size(), 6u);
    const std::vector<std::pair<size_t, bool>> want = {{0, false}, {2, true},  {2, false},
                                                       {0, true},  {4, false}, {5, false}};
    for (size_t i = 0; i < want.size(); ++i) {
        EXPECT_EQ(styles[i].colour, want[i].first) << i;
        EXPECT_EQ(styles[i].dashed, want[i].second) << i;
    }
    const std::string svg = overTimeSvg(
        {0.0, 1.0}, {{"smrt", {0.1, 0.2}}, {"smrt+temporal", {0.05, 0.3}}}, "rmse", "RMSE");
    const std::string colour(plotColour(0));
    EXPECT_NE(svg.find("stroke=\"" + colour + "\" stroke-dasharray=\"6 4\"/>"), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"" + colour + "\"/>"), std::string::npos);
    EXPECT_EQ(svg.find(plotColour(1)), std::string::npos);
}
