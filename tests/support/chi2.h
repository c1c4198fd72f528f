// Pearson chi-square goodness-of-fit tests for sampling routines (after Mitsuba 3's ChiSquareTest and pbrt's
// sampling tests). Header-only; depends on core/ and the standard library only.
//
//   auto r = kiln::test::chi2_sphere([](kiln::Rng& rng) -> std::optional<kiln::Vec3f> { ... },
//                                    [](kiln::Vec3f w) -> double { ... }, 1'000'000, 20, 40);
//   EXPECT_TRUE(r.passed) << r.message;
//
// How it decides:
//  * Observed counts are binned in theta (from +z, [0, pi]) x phi ([0, 2 pi)).
//  * Expected counts integrate the pdf over each cell in cos(theta)-phi space (where dω = dcos dphi) with an
//    adaptive quadtree (midpoint vs trapezoid rule), so pdfs with discontinuities (hemisphere or cone edges) not
//    aligned to cells are still integrated to a small fraction of each cell's Poisson noise. Peaks narrower than
//    a quarter cell can be missed entirely: choose bins to match the lobe.
//  * Failed samples (empty optional) form one extra cell whose expected count is N (1 - ∫pdf). When the pdf
//    integrates to 1, any failed sample lands in a cell that expects ~0 and the test fails.
//  * Cells expecting fewer than kMinExpected samples are pooled (smallest first) until the pool expects enough.
//  * A sample in a cell whose expected count is exactly 0 is attributed to an adjacent cell only when it lies
//    within kBoundarySlack radians of it (directions exactly on a hemisphere boundary); otherwise it counts
//    against a zero expectation and the test fails.
//  * The p-value is the chi-square survival function; pass when p >= 1 - (1 - significance)^(1/num_tests)
//    (Šidák correction for running num_tests tests in one suite).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"

namespace kiln::test {

struct Chi2Result {
  bool passed;
  double statistic;
  int dof;
  double p_value;
  std::string message;
};

namespace detail {

inline constexpr double kPiD = 3.14159265358979323846;
// Pearson's statistic is only chi-square distributed when every cell expects a handful of samples.
inline constexpr double kMinExpected = 5.0;
// Each cell's expected count is integrated to within this many standard deviations of its Poisson noise.
inline constexpr double kIntegrationTolSigmas = 0.05;
// Refinement stops at this depth, which caps the work per cell at ~2^(depth+2) quadtree nodes along an edge; an
// edge crossing a cell is then resolved to an error of at most jump * area / (4 * 2^depth) (area in cos-phi
// space), e.g. ~2 expected samples for a unit-pdf jump in a 9x9-degree cell at 1M samples.
inline constexpr int kMaxIntegrationDepth = 10;
// Lattice points per axis of the quadrature at each quadtree node.
inline constexpr int kQuadRes = 4;
// Trapezoid border nodes sit this fraction of a lattice step inside the rectangle.
inline constexpr double kBorderInset = 1.0 / 256.0;
// A direction exactly on a theta/phi cell boundary may round into the neighbouring cell.
inline constexpr double kBoundarySlack = 1e-5;
// Sampled directions must be unit length within this tolerance.
inline constexpr double kUnitLengthTol = 1e-3;

// Regularised upper incomplete gamma function Q(a, x) = Γ(a, x) / Γ(a): power series for P when x < a + 1,
// Lentz's continued fraction for Q otherwise.
inline double regularized_gamma_q(double a, double x) {
  if (!(x > 0.0)) return 1.0;
  constexpr int kMaxIter = 100000;
  constexpr double kEps = 1e-15;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double ap = a, term = 1.0 / a, sum = term;
    for (int n = 0; n < kMaxIter; ++n) {
      ap += 1.0;
      term *= x / ap;
      sum += term;
      if (std::abs(term) < std::abs(sum) * kEps) break;
    }
    return std::clamp(1.0 - sum * std::exp(log_prefactor), 0.0, 1.0);
  }
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < kMaxIter; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEps) break;
  }
  return std::clamp(std::exp(log_prefactor) * h, 0.0, 1.0);
}

// P(X >= statistic) for X ~ chi-square with dof degrees of freedom.
inline double chi2_survival(double statistic, int dof) {
  if (dof <= 0) return 1.0;
  return regularized_gamma_q(0.5 * dof, 0.5 * statistic);
}

inline double sidak_threshold(double significance, int num_tests) {
  return 1.0 - std::pow(1.0 - significance, 1.0 / std::max(1, num_tests));
}

inline Vec3f sphere_direction(double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return {float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(cos_theta)};
}

// Evaluates a user pdf, remembering the first invalid (negative or non-finite) value.
template <class PdfFn>
struct CheckedPdf {
  PdfFn& pdf;
  std::string error;
  double operator()(Vec3f w) {
    const double v = double(pdf(w));
    if (!std::isfinite(v) || v < 0.0) {
      if (error.empty()) {
        std::ostringstream s;
        s << "pdf returned " << v << " at direction (" << w.x << ", " << w.y << ", " << w.z << ")";
        error = s.str();
      }
      return 0.0;
    }
    return v;
  }
};

// Two estimates of the integral over [z0,z1] x [p0,p1] (cos(theta)-phi space) on interleaved lattices: the
// midpoint rule on kQuadRes^2 points and the trapezoid rule on (kQuadRes+1)^2 points whose outer rows sit
// kBorderInset inside the border. A step anywhere strictly inside the rectangle changes the two by different
// amounts (midpoint counts are integers, trapezoid counts half-integers), which nested midpoint rules can miss;
// the inset keeps a step lying exactly on the border (a hemisphere edge at a cell boundary) from refining.
struct RectEstimate {
  double midpoint, trapezoid;
};
template <class F>
RectEstimate estimate_rect(F& f, double z0, double z1, double p0, double p1) {
  const double dz = (z1 - z0) / kQuadRes, dp = (p1 - p0) / kQuadRes;
  double mid = 0.0, trap = 0.0;
  for (int i = 0; i < kQuadRes; ++i)
    for (int j = 0; j < kQuadRes; ++j) mid += f(sphere_direction(z0 + (i + 0.5) * dz, p0 + (j + 0.5) * dp));
  auto node = [](int k) { return k == 0 ? kBorderInset : (k == kQuadRes ? kQuadRes - kBorderInset : double(k)); };
  for (int i = 0; i <= kQuadRes; ++i) {
    const double wi = (i == 0 || i == kQuadRes) ? 0.5 : 1.0;
    for (int j = 0; j <= kQuadRes; ++j) {
      const double wj = (j == 0 || j == kQuadRes) ? 0.5 : 1.0;
      trap += wi * wj * f(sphere_direction(z0 + node(i) * dz, p0 + node(j) * dp));
    }
  }
  return {mid * dz * dp, trap * dz * dp};
}

// Quadtree refinement until the two estimates agree to tol. Errors that survive refinement sit along curves
// (edges), where the number of nodes doubles per level, so each child gets half its parent's tolerance.
template <class F>
double adaptive_rect(F& f, double z0, double z1, double p0, double p1, double tol, int depth) {
  const RectEstimate e = estimate_rect(f, z0, z1, p0, p1);
  if (depth <= 0 || std::abs(e.midpoint - e.trapezoid) <= tol)
    return (2.0 * e.midpoint + e.trapezoid) / 3.0;  // Simpson-like combination for smooth integrands
  const double zm = 0.5 * (z0 + z1), pm = 0.5 * (p0 + p1), t = 0.5 * tol;
  return adaptive_rect(f, z0, zm, p0, pm, t, depth - 1) + adaptive_rect(f, zm, z1, p0, pm, t, depth - 1) +
         adaptive_rect(f, z0, zm, pm, p1, t, depth - 1) + adaptive_rect(f, zm, z1, pm, p1, t, depth - 1);
}

// Integral of f over theta in [t0,t1], phi in [p0,p1], accurate to a small fraction of the Poisson noise of a
// cell that receives num_samples * integral samples.
template <class F>
double integrate_cell(F& f, double t0, double t1, double p0, double p1, double num_samples) {
  const double z0 = std::cos(t1), z1 = std::cos(t0);
  const RectEstimate rough = estimate_rect(f, z0, z1, p0, p1);
  const double expected = std::max(1.0, num_samples * std::max(rough.midpoint, rough.trapezoid));
  const double tol = kIntegrationTolSigmas * std::sqrt(expected) / num_samples;
  return adaptive_rect(f, z0, z1, p0, p1, tol, kMaxIntegrationDepth);
}

struct Cell {
  double observed;
  double expected;
  std::string label;
};

// Pearson's test over cells with Mitsuba-style pooling of small expectations.
inline Chi2Result pearson(std::vector<Cell> cells, double significance, int num_tests, const std::string& header) {
  std::ostringstream msg;
  msg << header;
  const double threshold = sidak_threshold(significance, num_tests);
  // Samples where the model says none can occur: the sampler is wrong regardless of statistics.
  for (const Cell& c : cells)
    if (c.expected <= 0.0 && c.observed > 0.0) {
      msg << "\n  " << c.observed << " samples fell in " << c.label << " whose expected count is 0";
      return {false, std::numeric_limits<double>::infinity(), 0, 0.0, msg.str()};
    }
  std::vector<size_t> order(cells.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cells[a].expected < cells[b].expected; });

  double stat = 0.0, pooled_obs = 0.0, pooled_exp = 0.0;
  int dof = 0, pooled_in = 0;
  std::vector<std::pair<double, size_t>> contrib;  // (term, cell) for the message
  for (size_t idx : order) {
    const Cell& c = cells[idx];
    if (c.expected <= 0.0) continue;  // observed is 0 too (checked above)
    if (c.expected < kMinExpected || (pooled_in > 0 && pooled_exp < kMinExpected)) {
      pooled_obs += c.observed;
      pooled_exp += c.expected;
      ++pooled_in;
      continue;
    }
    const double term = (c.observed - c.expected) * (c.observed - c.expected) / c.expected;
    stat += term;
    contrib.push_back({term, idx});
    ++dof;
  }
  if (pooled_in > 0) {
    const double term = (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    stat += term;
    ++dof;
    if (term > 0.0) contrib.push_back({term, cells.size()});
  }
  --dof;  // the total count is fixed
  if (dof < 1) {
    msg << "\n  not enough cells with expected count >= " << kMinExpected << " (dof = " << dof
        << "); use more samples or fewer bins";
    return {false, stat, dof, 0.0, msg.str()};
  }
  const double p = chi2_survival(stat, dof);
  const bool passed = p >= threshold;
  msg << "\n  chi2 = " << stat << ", dof = " << dof << ", p-value = " << p << (passed ? " >= " : " < ")
      << "threshold " << threshold << " -> " << (passed ? "pass" : "FAIL");
  if (pooled_in > 0) msg << "\n  pooled " << pooled_in << " cells: observed " << pooled_obs << ", expected " << pooled_exp;
  std::sort(contrib.begin(), contrib.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  constexpr size_t kWorstCellsShown = 5;
  for (size_t i = 0; i < std::min(kWorstCellsShown, contrib.size()); ++i) {
    if (contrib[i].second == cells.size()) {
      msg << "\n  worst: pooled cells, term " << contrib[i].first;
      continue;
    }
    const Cell& c = cells[contrib[i].second];
    msg << "\n  worst: " << c.label << ": observed " << c.observed << ", expected " << c.expected << ", term "
        << contrib[i].first;
  }
  return {passed, stat, dof, p, msg.str()};
}

}  // namespace detail

// Integral of f(direction) over the unit sphere by the midpoint rule on a cos(theta)-phi grid (dω = dcos dphi).
template <class Fn>
double integrate_sphere(Fn&& f, int theta_res = 512, int phi_res = 1024) {
  const double dz = 2.0 / theta_res, dp = 2.0 * detail::kPiD / phi_res;
  double sum = 0.0;
  for (int i = 0; i < theta_res; ++i) {
    const double z = -1.0 + (i + 0.5) * dz;
    for (int j = 0; j < phi_res; ++j) sum += double(f(detail::sphere_direction(z, (j + 0.5) * dp)));
  }
  return sum * dz * dp;
}

// Observed counts vs expected probabilities. Probability not covered by expected_prob (1 - Σp) is one more cell
// that observed nothing, so under-normalised probabilities fail; any count in a zero-probability entry fails.
inline Chi2Result chi2_discrete(std::span<const uint64_t> observed, std::span<const double> expected_prob,
                                double significance = 0.01, int num_tests = 1) {
  if (observed.size() != expected_prob.size()) {
    return {false, 0.0, 0, 0.0,
            "chi2_discrete: " + std::to_string(observed.size()) + " observed counts but " +
                std::to_string(expected_prob.size()) + " expected probabilities"};
  }
  double n = 0.0, prob_sum = 0.0;
  for (uint64_t o : observed) n += double(o);
  std::vector<detail::Cell> cells;
  cells.reserve(observed.size() + 1);
  for (size_t i = 0; i < observed.size(); ++i) {
    const double p = expected_prob[i];
    if (!std::isfinite(p) || p < 0.0)
      return {false, 0.0, 0, 0.0, "chi2_discrete: expected probability " + std::to_string(i) + " is invalid"};
    prob_sum += p;
    cells.push_back({double(observed[i]), n * p, "entry " + std::to_string(i)});
  }
  cells.push_back({0.0, n * std::max(0.0, 1.0 - prob_sum), "probability missing from the model"});
  std::ostringstream header;
  header << "chi2_discrete: " << observed.size() << " entries, " << n << " samples, sum of probabilities "
         << prob_sum;
  return detail::pearson(std::move(cells), significance, num_tests, header.str());
}

// Directions on the unit sphere: sample(Rng&) -> std::optional<Vec3f> (or Vec3f); an empty optional is a failed
// sample. pdf(Vec3f) -> double is the solid-angle density of sample()'s output.
template <class SampleFn, class PdfFn>
Chi2Result chi2_sphere(SampleFn&& sample, PdfFn&& pdf, uint64_t num_samples, int theta_bins, int phi_bins,
                       double significance = 0.01, int num_tests = 1, uint64_t seed = 1) {
  using detail::kPiD;
  if (theta_bins < 1 || phi_bins < 1) return {false, 0.0, 0, 0.0, "chi2_sphere: bin counts must be positive"};
  const double dt = kPiD / theta_bins, dp = 2.0 * kPiD / phi_bins;
  const size_t n_cells = size_t(theta_bins) * size_t(phi_bins);

  // Expected probability per cell.
  detail::CheckedPdf<std::remove_reference_t<PdfFn>> checked{pdf, {}};
  std::vector<double> prob(n_cells);
  double integral = 0.0;
  for (int i = 0; i < theta_bins; ++i)
    for (int j = 0; j < phi_bins; ++j) {
      prob[size_t(i) * phi_bins + j] =
          detail::integrate_cell(checked, i * dt, (i + 1) * dt, j * dp, (j + 1) * dp, double(num_samples));
      integral += prob[size_t(i) * phi_bins + j];
    }
  if (!checked.error.empty()) return {false, 0.0, 0, 0.0, "chi2_sphere: " + checked.error};

  // Observed counts.
  std::vector<double> obs(n_cells, 0.0);
  uint64_t failed = 0, invalid = 0;
  Vec3f first_invalid{};
  Rng rng(seed, 0x6368693273ull);  // "chi2s"
  auto cell_of = [&](double theta, double phi) {
    const int ti = std::clamp(int(theta / dt), 0, theta_bins - 1);
    const int pj = ((int(std::floor(phi / dp)) % phi_bins) + phi_bins) % phi_bins;
    return size_t(ti) * phi_bins + pj;
  };
  for (uint64_t k = 0; k < num_samples; ++k) {
    const std::optional<Vec3f> w = sample(rng);  // a plain Vec3f return converts to an engaged optional
    if (!w) {
      ++failed;
      continue;
    }
    const double x = w->x, y = w->y, z = w->z;
    const double len = std::sqrt(x * x + y * y + z * z);
    if (!std::isfinite(len) || std::abs(len - 1.0) > detail::kUnitLengthTol) {
      if (invalid++ == 0) first_invalid = *w;
      continue;
    }
    const double theta = std::acos(std::clamp(z / len, -1.0, 1.0));
    double phi = std::atan2(y, x);
    if (phi < 0.0) phi += 2.0 * kPiD;
    size_t c = cell_of(theta, phi);
    if (prob[c] <= 0.0) {
      constexpr double s = detail::kBoundarySlack;
      for (auto [a, b] : {std::pair{theta - s, phi}, std::pair{theta + s, phi}, std::pair{theta, phi - s},
                          std::pair{theta, phi + s}}) {
        if (prob[cell_of(a, b)] > 0.0) {
          c = cell_of(a, b);
          break;
        }
      }
    }
    obs[c] += 1.0;
  }
  if (invalid > 0) {
    std::ostringstream s;
    s << "chi2_sphere: " << invalid << " of " << num_samples << " samples were not finite unit vectors (first: ("
      << first_invalid.x << ", " << first_invalid.y << ", " << first_invalid.z << "))";
    return {false, 0.0, 0, 0.0, s.str()};
  }

  const double n = double(num_samples);
  std::vector<detail::Cell> cells;
  cells.reserve(n_cells + 1);
  for (int i = 0; i < theta_bins; ++i)
    for (int j = 0; j < phi_bins; ++j) {
      const size_t c = size_t(i) * phi_bins + j;
      std::ostringstream label;
      label << "cell theta[" << i << "] = [" << i * dt * 180.0 / kPiD << ", " << (i + 1) * dt * 180.0 / kPiD
            << "] deg, phi[" << j << "] = [" << j * dp * 180.0 / kPiD << ", " << (j + 1) * dp * 180.0 / kPiD
            << "] deg";
      cells.push_back({obs[c], n * prob[c], label.str()});
    }
  cells.push_back({double(failed), n * std::max(0.0, 1.0 - integral), "failed samples"});
  std::ostringstream header;
  header << "chi2_sphere: " << num_samples << " samples, " << theta_bins << "x" << phi_bins << " bins, "
         << failed << " failed samples, pdf integrates to " << integral;
  if (integral > 1.0 + 1e-3) header << " (> 1: the pdf is too large somewhere)";
  return detail::pearson(std::move(cells), significance, num_tests, header.str());
}

}  // namespace kiln::test
