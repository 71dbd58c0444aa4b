#pragma once
// report.html's error-against-cost plot: one point per row, the Pareto front (the rows no other
// row beats on both RMSE and GPU time), labels placed so that none overlaps another label or a
// point (a label that finds no free place is left to the legend and the point's tooltip), on a
// linear or a logarithmic cost axis.
#include "report/html_report.h"

#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct PlotPoint {
    std::string name;
    double cost = 0, rmse = 0; // GPU ms, RMSE; non-finite points are left out
};

// true for the points no other point dominates (no more cost and no more error, and less of
// one); non-finite points are never on it.
std::vector<bool> paretoFront(const std::vector<PlotPoint>& points);

// An axis-aligned box in SVG user units.
struct PlotBox {
    double x = 0, y = 0, w = 0, h = 0;
    bool intersects(const PlotBox& o) const {
        return x < o.x + o.w && o.x < x + w && y < o.y + o.h && o.y < y + h;
    }
};

// The width a label of `text` takes at the plot's 12-pixel font, rounded up for any sans-serif
// face (wider than DejaVu Sans, the widest common default).
double labelWidth(const std::string& text);

// For each point at `at` (centres), a label box of size `sizes` placed at the first of eight
// places around it that stays inside `bounds` and clear of every placed label and every point
// (radius `radius`); nullopt-like (w = 0) when none is free.
std::vector<PlotBox> placeLabels(const std::vector<PlotBox>& points, double radius,
                                 const std::vector<PlotBox>& sizes, const PlotBox& bounds);

// The plot as inline SVG (class "error-vs-cost", plus "log" on the logarithmic one).
std::string errorVsCostSvg(const std::vector<ReportRow>& rows, bool logCost);

// The legend beside the plots: every row's colour, name, cost and RMSE, the front marked.
std::string errorVsCostLegend(const std::vector<ReportRow>& rows);

double totalGpuMs(const ReportRow& row);

// Row i's colour in every plot of the report (a palette of 8, repeating).
std::string_view plotColour(size_t row);

// A "nice" axis from 0: a 1, 2 or 5 x 10^k step and a maximum, a whole number of steps, that
// covers maxValue with 5% to spare; degenerate data (none, zero, non-finite) gets 0..1.
struct Axis {
    double max = 1, step = 0.2;
    int decimals = 1; // the step's
};
Axis niceAxis(double maxValue);

} // namespace penumbra
