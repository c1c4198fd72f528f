#include "renderer/analysis/convergence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "core/error.h"
#include "renderer/analysis/error_curve.h"

namespace kiln {
namespace {


struct Moments {
  double sum = 0, sum2 = 0, lo = std::numeric_limits<double>::infinity(), hi = 0;
  int n = 0;
  void add(double v) {
    sum += v;
    sum2 += v * v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    ++n;
  }
  double mean() const { return n ? sum / n : 0.0; }
  // Sample standard deviation (n - 1); 0 for a single run.
  double sd() const { return n > 1 ? std::sqrt(std::max(0.0, (sum2 - sum * sum / n) / (n - 1))) : 0.0; }
};

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

}  // namespace

PathSettings convergence_base_settings(const SceneDesc& scene) {
  PathSettings s = kiln_path_defaults(scene);
  s.max_depth = std::max(0, s.max_depth);
  s.russian_roulette = false;
  s.rr_min_depth = kKilnRouletteMinDepth;
  return s;
}

NamedStrategy make_strategy(const std::string& name, const PathSettings& base, uint32_t features,
                            const std::string& option) {
  IntegratorSettings s = kiln_strategy(name, base, option);
  s.features = features;
  return {name, s};
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = trim(list.substr(start, comma - start));
    if (!item.empty()) out.push_back(item);
    start = comma + 1;
  }
  return out;
}

std::vector<ConvergencePoint> measure_strategy(const World& world, const Camera& camera, const NamedStrategy& strategy,
                                               const Image& reference, const ConvergenceOptions& options) {
  const int runs = std::max(1, options.runs);
  std::map<uint32_t, std::array<Moments, 3>> by_spp;  // seconds, relMSE, RMSE
  uint32_t spp_target = options.max_spp;
  for (int r = 0; r < runs; ++r) {
    if (options.cancel && options.cancel->load()) break;
    RenderOptions ro;
    ro.seed = options.seed + 1 + uint64_t(r);
    ro.cancel = options.cancel;
    ProgressiveOptions po;
    if (r == 0) po.time_limit_seconds = options.budget_seconds / runs;
    Film film(camera.width(), camera.height());
    const ErrorCurve curve =
        render_error_curve(world, camera, strategy.settings, ro, spp_target, reference, po, film);
    for (const MeasuredWave& w : curve.waves) {
      if (w.wave.cancelled) continue;
      auto& m = by_spp[w.wave.spp];
      m[0].add(w.wave.seconds);
      m[1].add(w.error.rel_mse);
      m[2].add(w.error.rmse);
    }
    if (r == 0) spp_target = std::max(1u, curve.render.spp);
  }
  std::vector<ConvergencePoint> out;
  for (const auto& [spp, m] : by_spp) {
    ConvergencePoint p;
    p.strategy = strategy.name;
    p.spp = spp;
    p.runs = m[1].n;
    p.seconds = m[0].mean();
    p.seconds_sd = m[0].sd();
    p.rel_mse = m[1].mean();
    p.rel_mse_sd = m[1].sd();
    p.rel_mse_min = m[1].lo;
    p.rel_mse_max = m[1].hi;
    p.rmse = m[2].mean();
    p.rmse_sd = m[2].sd();
    p.efficiency = p.rel_mse > 0 && p.seconds > 0 ? 1.0 / (p.rel_mse * p.seconds) : 0.0;
    out.push_back(p);
  }
  return out;
}

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (!(x[i] > 0 && y[i] > 0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
    const double lx = std::log10(x[i]), ly = std::log10(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  const double den = n * sxx - sx * sx;
  if (n < 2 || !(std::abs(den) > 1e-12)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / den;
}

StrategySummary summarize(const std::vector<ConvergencePoint>& points) {
  StrategySummary s;
  if (points.empty()) return s;
  const ConvergencePoint& last = points.back();
  s.strategy = last.strategy;
  s.spp = last.spp;
  s.seconds = last.seconds;
  s.rel_mse = last.rel_mse;
  s.efficiency = last.efficiency;
  std::vector<double> x, y;
  for (const ConvergencePoint& p : points)
    if (p.spp >= kSlopeMinSpp) {
      x.push_back(p.seconds);
      y.push_back(p.rel_mse);
    }
  s.slope = loglog_slope(x, y);
  return s;
}

std::string convergence_csv(const std::vector<ConvergencePoint>& points) {
  std::string s = "strategy,spp,runs,seconds,seconds_sd,relmse,relmse_sd,relmse_min,relmse_max,rmse,rmse_sd,efficiency\n";
  char buf[512];
  for (const ConvergencePoint& p : points) {
    std::snprintf(buf, sizeof buf, "%s,%u,%d,%.6g,%.3g,%.6g,%.3g,%.6g,%.6g,%.6g,%.3g,%.6g\n", p.strategy.c_str(), p.spp,
                  p.runs, p.seconds, p.seconds_sd, p.rel_mse, p.rel_mse_sd, p.rel_mse_min, p.rel_mse_max, p.rmse,
                  p.rmse_sd, p.efficiency);
    s += buf;
  }
  return s;
}

std::string ranking_table(std::vector<StrategySummary> summaries) {
  std::stable_sort(summaries.begin(), summaries.end(),
                   [](const StrategySummary& a, const StrategySummary& b) { return a.efficiency > b.efficiency; });
  const double best = summaries.empty() ? 0.0 : summaries.front().efficiency;
  std::string s = "rank  strategy      spp   seconds     relMSE  efficiency  vs best  slope\n";
  char buf[256];
  for (size_t i = 0; i < summaries.size(); ++i) {
    const StrategySummary& m = summaries[i];
    char slope[16] = "  n/a";
    if (std::isfinite(m.slope)) std::snprintf(slope, sizeof slope, "%5.2f", m.slope);
    std::snprintf(buf, sizeof buf, "%4zu  %-10s %6u  %8.3f  %9.3e  %10.4g  %6.2fx  %s\n", i + 1, m.strategy.c_str(), m.spp,
                  m.seconds, m.rel_mse, m.efficiency, best > 0 ? m.efficiency / best : 0.0, slope);
    s += buf;
  }
  return s;
}

LogLogPlot convergence_plot(const std::vector<ConvergencePoint>& points, const std::string& title,
                            const std::string& subtitle) {
  LogLogPlot plot;
  plot.title = title;
  plot.subtitle = subtitle;
  plot.x_label = "render time (seconds)";
  plot.y_label = "relMSE against the reference";
  plot.guide_slope = -1.0;
  for (const ConvergencePoint& p : points) {
    auto it = std::find_if(plot.series.begin(), plot.series.end(), [&](const PlotSeries& s) { return s.name == p.strategy; });
    if (it == plot.series.end()) {
      plot.series.push_back(PlotSeries{p.strategy, {}, {}, {}, {}});
      it = plot.series.end() - 1;
    }
    it->x.push_back(p.seconds);
    it->y.push_back(p.rel_mse);
    it->y_low.push_back(p.rel_mse_min);
    it->y_high.push_back(p.rel_mse_max);
  }
  return plot;
}

}  // namespace kiln
