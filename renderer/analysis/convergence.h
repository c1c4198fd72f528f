// Error against run time for several path-tracing strategies on one scene (GitHub issue 7). Each strategy renders
// in doubling waves (renderer/render/progressive.h), several times with independent seeds, and every wave's relMSE and
// RMSE against a reference are recorded with their spread over the runs. Efficiency = 1 / (relMSE x seconds) is
// the figure of merit: for an unbiased estimator relMSE falls as 1/time, so efficiency settles to a constant and
// the strategy with the larger one needs less time for the same error.
//
// Strategy names (all Kiln path tracing with one set of transport rules, so every strategy converges to the same
// image): uniform, cosine, brdf (direction sampling only), nee (BRDF sampling + next event estimation), mis (NEE
// and BRDF sampling combined with the power heuristic); any of them with "+rr" adds Kiln's Russian roulette
// after kKilnRouletteMinDepth bounces (renderer/integrators/settings.h).
#pragma once
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "renderer/world/camera.h"
#include "renderer/integrators/integrator.h"
#include "renderer/integrators/rules.h"
#include "renderer/analysis/plot_svg.h"

namespace kiln {

// Waves below this many samples per pixel are dominated by start-up costs, not by the estimator's variance, and
// are left out of the fitted error-against-time slope.
inline constexpr uint32_t kSlopeMinSpp = 4;

struct NamedStrategy {
  std::string name;
  IntegratorSettings settings;
};

// The transport every strategy shares: Kiln's path tracer to the scene's depth (renderer/integrators/rules.h), roulette only
// where a strategy's "+rr" asks for it, no clamping.
PathSettings convergence_base_settings(const SceneDesc& scene);
// Kiln's strategy `name` (renderer/integrators/rules.h kiln_strategy) on top of base; throws kiln::Error naming `option` for an
// unknown name.
NamedStrategy make_strategy(const std::string& name, const PathSettings& base, uint32_t features,
                            const std::string& option = "--strategies");
// "uniform,cosine,nee" -> names (whitespace trimmed, empties dropped).
std::vector<std::string> split_list(const std::string& list);

struct ConvergencePoint {
  std::string strategy;
  uint32_t spp = 0;
  int runs = 0;                    // runs that reached this spp
  double seconds = 0, seconds_sd = 0;
  double rel_mse = 0, rel_mse_sd = 0, rel_mse_min = 0, rel_mse_max = 0;
  double rmse = 0, rmse_sd = 0;
  double efficiency = 0;           // 1 / (rel_mse * seconds), from the run means
};

struct ConvergenceOptions {
  uint32_t max_spp = 1u << 16;
  int runs = 3;
  double budget_seconds = 10;  // for this strategy, all runs together
  uint64_t seed = 0;           // run r renders with seed + 1 + r (the reference must use another seed)
  const std::atomic<bool>* cancel = nullptr;
};

// The first run stops by the time limit budget / runs; the others render to the same spp so every point has the
// same number of runs (a later run that is interrupted contributes fewer points).
std::vector<ConvergencePoint> measure_strategy(const World& world, const Camera& camera, const NamedStrategy& strategy,
                                               const Image& reference, const ConvergenceOptions& options);

struct StrategySummary {
  std::string strategy;
  uint32_t spp = 0;        // the last point's
  double seconds = 0, rel_mse = 0, efficiency = 0;
  double slope = 0;        // least-squares slope of log relMSE against log seconds (spp >= kSlopeMinSpp); NaN if < 2 points
};
StrategySummary summarize(const std::vector<ConvergencePoint>& points_of_one_strategy);
// Least-squares slope of log10(y) against log10(x); NaN with fewer than two usable points.
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);

// strategy,spp,runs,seconds,seconds_sd,relmse,relmse_sd,relmse_min,relmse_max,rmse,rmse_sd,efficiency
std::string convergence_csv(const std::vector<ConvergencePoint>& points);
// Strategies ranked by efficiency, best first, as a fixed-width text table.
std::string ranking_table(std::vector<StrategySummary> summaries);
// relMSE against seconds, one series per strategy (in first-appearance order), spread = min..max over runs.
LogLogPlot convergence_plot(const std::vector<ConvergencePoint>& points, const std::string& title,
                            const std::string& subtitle);

}  // namespace kiln
