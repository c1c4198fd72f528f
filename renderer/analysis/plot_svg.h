// A tiny log-log line plotter writing standalone SVG (for convergence plots a person opens in a browser): axes
// with decade ticks and 10^k labels, minor ticks, one polyline + markers per series with optional vertical spread
// bars, a legend, title and subtitle, and an optional dashed guide line of a given slope.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace kiln {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  std::vector<double> y_low, y_high;  // optional spread per point (same size as y, or empty)
};

struct LogLogPlot {
  std::string title, subtitle, x_label, y_label;
  std::vector<PlotSeries> series;
  std::optional<double> guide_slope;  // e.g. -1: the Monte Carlo rate, drawn through the data's log-centre
  int width = 800, height = 540;
};

// Whole decades [10^lo, 10^hi] covering [min, max] (both > 0); at least one decade wide.
struct DecadeRange {
  int lo = 0, hi = 1;
};
DecadeRange decade_range(double min, double max);

// Points with a non-positive or non-finite coordinate cannot be drawn on log axes and are skipped.
std::string loglog_svg(const LogLogPlot& plot);

}  // namespace kiln
