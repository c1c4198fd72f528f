#include "renderer/analysis/plot_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace kiln {
namespace {

// Page layout in SVG user units (pixels).
constexpr double kMarginLeft = 84, kMarginRight = 190, kMarginTop = 64, kMarginBottom = 64;
constexpr double kTickMajor = 7, kTickMinor = 4;
constexpr double kMarkerRadius = 3.5;
constexpr double kLegendRow = 20;
// Tableau 10: distinguishable for the common forms of colour blindness, and in grey-scale print with the markers.
constexpr const char* kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
constexpr int kMarkerShapes = 5;

std::string esc(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

bool drawable(double x, double y) { return std::isfinite(x) && std::isfinite(y) && x > 0 && y > 0; }

struct Axes {
  DecadeRange xr, yr;
  double x0, x1, y0, y1;  // plot area in page units (y0 top)
  double px(double x) const { return x0 + (std::log10(x) - xr.lo) / double(xr.hi - xr.lo) * (x1 - x0); }
  double py(double y) const { return y1 - (std::log10(y) - yr.lo) / double(yr.hi - yr.lo) * (y1 - y0); }
};

std::string marker(int shape, double x, double y, const char* colour) {
  const double r = kMarkerRadius;
  switch (shape % kMarkerShapes) {
    case 0:
      return fmt("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"", x, y, r) + " fill=\"" + colour + "\"/>";
    case 1:
      return fmt("<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"", x - r, y - r, 2 * r, 2 * r) +
             " fill=\"" + colour + "\"/>";
    case 2:
      return fmt("<polygon points=\"%.2f,%.2f ", x, y - 1.2 * r) + fmt("%.2f,%.2f ", x + 1.1 * r, y + 0.8 * r) +
             fmt("%.2f,%.2f\"", x - 1.1 * r, y + 0.8 * r) + " fill=\"" + colour + "\"/>";
    case 3:
      return fmt("<polygon points=\"%.2f,%.2f ", x, y - 1.3 * r) + fmt("%.2f,%.2f ", x + 1.3 * r, y) +
             fmt("%.2f,%.2f ", x, y + 1.3 * r) + fmt("%.2f,%.2f\"", x - 1.3 * r, y) + " fill=\"" + colour + "\"/>";
    default:
      return fmt("<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\"", x, y, r) + " fill=\"white\" stroke=\"" + colour +
             "\" stroke-width=\"1.5\"/>";
  }
}

// "10^k" with a raised exponent.
std::string decade_label(int k) {
  return "10<tspan dy=\"-6\" font-size=\"9\">" + std::to_string(k) + "</tspan>";
}

}  // namespace

DecadeRange decade_range(double min, double max) {
  DecadeRange r;
  r.lo = int(std::floor(std::log10(min)));
  r.hi = int(std::ceil(std::log10(max)));
  if (r.hi <= r.lo) r.hi = r.lo + 1;
  return r;
}

std::string loglog_svg(const LogLogPlot& plot) {
  double xmin = std::numeric_limits<double>::infinity(), xmax = 0, ymin = xmin, ymax = 0;
  for (const PlotSeries& s : plot.series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!drawable(s.x[i], s.y[i])) continue;
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
      if (s.y_low.size() == s.y.size() && drawable(1, s.y_low[i])) ymin = std::min(ymin, s.y_low[i]);
      if (s.y_high.size() == s.y.size() && drawable(1, s.y_high[i])) ymax = std::max(ymax, s.y_high[i]);
    }
  if (!(xmax > 0)) xmin = 1, xmax = 10, ymin = 1, ymax = 10;  // nothing to draw: empty axes

  const double W = plot.width, H = plot.height;
  Axes ax{decade_range(xmin, xmax), decade_range(ymin, ymax), kMarginLeft, W - kMarginRight, kMarginTop,
          H - kMarginBottom};
  std::string s;
  s += fmt("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" ", W, H,
           W, H) +
       "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"12\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += fmt("<text x=\"%.2f\" y=\"26\" font-size=\"16\" font-weight=\"bold\" text-anchor=\"middle\">", (ax.x0 + ax.x1) / 2) +
       esc(plot.title) + "</text>\n";
  if (!plot.subtitle.empty())
    s += fmt("<text x=\"%.2f\" y=\"44\" font-size=\"11\" fill=\"#555\" text-anchor=\"middle\">", (ax.x0 + ax.x1) / 2) +
         esc(plot.subtitle) + "</text>\n";
  s += "<defs><clipPath id=\"plot-area\">" +
       fmt("<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/>", ax.x0, ax.y0, ax.x1 - ax.x0, ax.y1 - ax.y0) +
       "</clipPath></defs>\n";

  // Grid and ticks: a line and label per decade, short ticks at 2..9 x 10^k.
  s += "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (int k = ax.xr.lo; k <= ax.xr.hi; ++k)
    s += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", ax.px(std::pow(10.0, k)), ax.y0,
             ax.px(std::pow(10.0, k)), ax.y1);
  for (int k = ax.yr.lo; k <= ax.yr.hi; ++k)
    s += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", ax.x0, ax.py(std::pow(10.0, k)), ax.x1,
             ax.py(std::pow(10.0, k)));
  s += "</g>\n<g stroke=\"black\" stroke-width=\"1\">\n";
  s += fmt("<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"none\"/>\n", ax.x0, ax.y0, ax.x1 - ax.x0,
           ax.y1 - ax.y0);
  for (int k = ax.xr.lo; k <= ax.xr.hi; ++k)
    for (int m = 1; m <= (k < ax.xr.hi ? 9 : 1); ++m) {
      const double x = ax.px(m * std::pow(10.0, k));
      s += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", x, ax.y1, x, ax.y1 - (m == 1 ? kTickMajor : kTickMinor));
    }
  for (int k = ax.yr.lo; k <= ax.yr.hi; ++k)
    for (int m = 1; m <= (k < ax.yr.hi ? 9 : 1); ++m) {
      const double y = ax.py(m * std::pow(10.0, k));
      s += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", ax.x0, y, ax.x0 + (m == 1 ? kTickMajor : kTickMinor), y);
    }
  s += "</g>\n<g class=\"tick-labels\">\n";
  for (int k = ax.xr.lo; k <= ax.xr.hi; ++k)
    s += fmt("<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">", ax.px(std::pow(10.0, k)), ax.y1 + 20) +
         decade_label(k) + "</text>\n";
  for (int k = ax.yr.lo; k <= ax.yr.hi; ++k)
    s += fmt("<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">", ax.x0 - 8, ax.py(std::pow(10.0, k)) + 4) +
         decade_label(k) + "</text>\n";
  s += "</g>\n";
  s += fmt("<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">", (ax.x0 + ax.x1) / 2, H - 18) + esc(plot.x_label) +
       "</text>\n";
  s += fmt("<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\" transform=\"rotate(-90 %.2f %.2f)\">", 22,
           (ax.y0 + ax.y1) / 2, 22, (ax.y0 + ax.y1) / 2) +
       esc(plot.y_label) + "</text>\n";

  s += "<g clip-path=\"url(#plot-area)\">\n";
  if (plot.guide_slope && xmax > 0) {
    // Through the log-centre of the data, across the whole x range.
    const double cx = 0.5 * (std::log10(xmin) + std::log10(xmax)), cy = 0.5 * (std::log10(ymin) + std::log10(ymax));
    const double xa = std::pow(10.0, ax.xr.lo), xb = std::pow(10.0, ax.xr.hi);
    const double ya = std::pow(10.0, cy + *plot.guide_slope * (ax.xr.lo - cx));
    const double yb = std::pow(10.0, cy + *plot.guide_slope * (ax.xr.hi - cx));
    s += fmt("<line class=\"guide\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" ", ax.px(xa), ax.py(ya), ax.px(xb),
             ax.py(yb)) +
         "stroke=\"#999\" stroke-width=\"1\" stroke-dasharray=\"6 4\"/>\n";
  }
  for (size_t si = 0; si < plot.series.size(); ++si) {
    const PlotSeries& ps = plot.series[si];
    const char* colour = kPalette[si % std::size(kPalette)];
    std::string pts, marks, bars;
    const bool spread = ps.y_low.size() == ps.y.size() && ps.y_high.size() == ps.y.size();
    for (size_t i = 0; i < std::min(ps.x.size(), ps.y.size()); ++i) {
      if (!drawable(ps.x[i], ps.y[i])) continue;
      const double x = ax.px(ps.x[i]), y = ax.py(ps.y[i]);
      pts += fmt("%.2f,%.2f ", x, y);
      marks += marker(int(si), x, y, colour) + "\n";
      if (spread && drawable(1, ps.y_low[i]) && drawable(1, ps.y_high[i])) {
        const double ylo = ax.py(ps.y_low[i]), yhi = ax.py(ps.y_high[i]);
        bars += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>", x, ylo, x, yhi);
        bars += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>", x - 3, ylo, x + 3, ylo);
        bars += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", x - 3, yhi, x + 3, yhi);
      }
    }
    s += "<g class=\"series\" data-name=\"" + esc(ps.name) + "\">\n";
    if (!bars.empty()) s += std::string("<g stroke=\"") + colour + "\" stroke-width=\"1\">\n" + bars + "</g>\n";
    if (!pts.empty())
      s += "<polyline fill=\"none\" stroke=\"" + std::string(colour) + "\" stroke-width=\"2\" points=\"" + pts +
           "\"/>\n";
    s += marks + "</g>\n";
  }
  s += "</g>\n";

  // Legend, right of the plot area.
  const double lx = ax.x1 + 18;
  double ly = ax.y0 + 8;
  const double lh = kLegendRow * double(plot.series.size() + (plot.guide_slope ? 1 : 0)) + 8;
  s += fmt("<g class=\"legend\"><rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" ", lx - 8, ly - 8,
           kMarginRight - 28, lh) +
       "fill=\"white\" stroke=\"#bbb\"/>\n";
  for (size_t si = 0; si < plot.series.size(); ++si) {
    const char* colour = kPalette[si % std::size(kPalette)];
    const double y = ly + 6;
    s += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" ", lx, y, lx + 28, y) + "stroke=\"" + colour +
         "\" stroke-width=\"2\"/>" + marker(int(si), lx + 14, y, colour);
    s += fmt("<text x=\"%.2f\" y=\"%.2f\">", lx + 36, y + 4) + esc(plot.series[si].name) + "</text>\n";
    ly += kLegendRow;
  }
  if (plot.guide_slope) {
    const double y = ly + 6;
    s += fmt("<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" ", lx, y, lx + 28, y) +
         "stroke=\"#999\" stroke-dasharray=\"6 4\"/>";
    s += fmt("<text x=\"%.2f\" y=\"%.2f\">slope %g</text>\n", lx + 36, y + 4, *plot.guide_slope);
  }
  s += "</g>\n</svg>\n";
  return s;
}

}  // namespace kiln
