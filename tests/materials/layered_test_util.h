// Checks shared by the tests of the layered BxDFs (CoatedDiffuse, CoatedConductor), whose sampling density has no
// closed form:
//  * sample() and eval() estimate the same BSDF: per direction cell, E[path weight of samples in the cell] =
//    ∫_cell f cos. A two-sample chi-square compares the sampled weights with eval() integrated over each cell at
//    random points, each side with its own estimated variance (sample_eval_agreement).
//  * albedo by both routes (sampled_albedo, evaluated_albedo), reciprocity of E[f] (independent estimates drawn by
//    perturbing the directions by ulps: expect_reciprocal), and that samples report pdf(wo, wi)
//    (expect_samples_report_pdf).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "brdf_test_util.h"
#include "core/sampling.h"
#include "support/chi2.h"

namespace kiln::test {

inline constexpr double kLayeredPi = 3.14159265358979323846;

// Next representable direction: the same direction for the BSDF, an independent estimate for the hash.
inline Vec3f jitter(Vec3f w, int k) {
  Vec3f v = w;
  for (int i = 0; i < k; ++i) v.x = std::nextafter(v.x, 2.0f);
  return v;
}

struct MeanEstimate {
  double mean = 0, stderr_ = 0;
};
template <class F>
MeanEstimate mean_of(int n, F&& f) {
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = f(i);
    s += v;
    s2 += v * v;
  }
  const double m = s / n;
  return {m, std::sqrt(std::max(0.0, s2 / n - m * m) / n)};
}

// Directional albedo through sample(): specular and non-specular samples alike (f |cos| / pdf is the path weight).
inline MeanEstimate sampled_albedo(const Material& m, Vec3f wo, int n, uint64_t seed) {
  Rng rng(seed, 5);
  return mean_of(n, [&](int) {
    const float uc = rng.next_float();
    const auto s = m.sample(wo, uc, rng.next_2d());
    return s ? double(s->f.average()) * std::abs(s->wi.z) / s->pdf : 0.0;
  });
}

// Directional albedo through eval(): cosine-weighted directions, f cos / (cos / pi) = pi f. Excludes delta lobes.
inline MeanEstimate evaluated_albedo(const Material& m, Vec3f wo, int n, uint64_t seed) {
  Rng rng(seed, 6);
  const float flip = wo.z < 0 ? -1.0f : 1.0f;
  return mean_of(n, [&](int) {
    Vec3f wi = sample_cosine_hemisphere(rng.next_2d());
    wi.z *= flip;
    return wi.z != 0 ? kLayeredPi * double(m.eval(wo, wi).average()) : 0.0;
  });
}

// Albedo <= 1 within `sigmas` standard errors, through sample() and through eval(), from normal incidence down to
// grazing; `seed` advances by one per estimate.
inline void expect_albedo_at_most_one(const Material& m, const std::string& name, double sigmas, uint64_t& seed) {
  for (float c : {1.0f, 0.6f, 0.2f, 0.02f}) {
    const MeanEstimate s = sampled_albedo(m, direction_at(c), 40000, ++seed);
    EXPECT_LE(s.mean, 1.0 + sigmas * s.stderr_) << name << " sample, cos " << c;
    const MeanEstimate e = evaluated_albedo(m, direction_at(c), 20000, ++seed);
    EXPECT_LE(e.mean, 1.0 + sigmas * e.stderr_) << name << " eval, cos " << c;
  }
}

// One direction cell (or a pool of cells) of the two-sample comparison.
struct CellTally {
  double count = 0, sum = 0, sum2 = 0;      // sampled path weights landing in the cell
  double evaluated = 0, evaluated_var = 0;  // ∫_cell f cos from eval() at random points, and its variance
  void add(const CellTally& o) {
    count += o.count;
    sum += o.sum;
    sum2 += o.sum2;
    evaluated += o.evaluated;
    evaluated_var += o.evaluated_var;
  }
};

struct AgreementResult {
  double statistic = 0, p_value = 1;
  int dof = 0;
  std::string worst;  // the pool contributing most to the statistic
};

// The two-sample chi-square of sample() against eval() over the upper hemisphere (wo.z > 0), non-specular samples.
// evals_per_cell: eval() calls averaged per cell. Each call is one random walk, and behind a rough coat over a
// smooth base a walk's value is a narrow spike (the coat's lobe around the mirrored entry direction): the per-cell
// means then need more calls before their sample variance, which the statistic relies on, is trustworthy.
inline AgreementResult sample_eval_agreement(const Material& m, Vec3f wo, uint64_t seed, int evals_per_cell = 120) {
  constexpr int kCosBins = 8, kPhiBins = 12, kSamples = 100000;
  // The normal approximation of a cell's weighted sum needs a few dozen samples: cells are pooled (in order of
  // their evaluated integral, smallest first) until the pool holds this many.
  constexpr double kMinSamplesPerPool = 50;
  auto cell_of = [&](Vec3f w) {
    const int ci = std::clamp(int(w.z * kCosBins), 0, kCosBins - 1);
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += 2 * kLayeredPi;
    const int pj = std::clamp(int(phi / (2 * kLayeredPi) * kPhiBins), 0, kPhiBins - 1);
    return ci * kPhiBins + pj;
  };
  const int n_cells = kCosBins * kPhiBins;
  std::vector<CellTally> cells(n_cells);
  Rng rng(seed, 1);
  int below = 0;  // samples on the wrong side: each one fails the comparison outright
  for (int i = 0; i < kSamples; ++i) {
    const float uc = rng.next_float();
    const auto s = m.sample(wo, uc, rng.next_2d());
    if (!s || s->is_specular()) continue;
    if (!(s->wi.z > 0.0f)) {
      ++below;
      continue;
    }
    const double w = double(s->f.average()) * s->wi.z / s->pdf;
    CellTally& t = cells[size_t(cell_of(s->wi))];
    t.count += 1;
    t.sum += w;
    t.sum2 += w * w;
  }
  const double cell_area = (1.0 / kCosBins) * (2 * kLayeredPi / kPhiBins);  // in cos(theta)-phi, dw = dcos dphi
  for (int k = 0; k < n_cells; ++k) {
    const int ci = k / kPhiBins, pj = k % kPhiBins;
    const MeanEstimate b = mean_of(evals_per_cell, [&](int) {
      const double z = (ci + rng.next_float()) / kCosBins;
      const double phi = (pj + rng.next_float()) * 2 * kLayeredPi / kPhiBins;
      const double sz = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3f wi(float(sz * std::cos(phi)), float(sz * std::sin(phi)), float(z));
      return cell_area * double(m.eval(wo, wi).average()) * wi.z;
    });
    cells[size_t(k)].evaluated = b.mean;
    cells[size_t(k)].evaluated_var = b.stderr_ * b.stderr_;
  }
  std::sort(cells.begin(), cells.end(), [](const CellTally& a, const CellTally& b) { return a.evaluated < b.evaluated; });
  std::vector<CellTally> pools;
  CellTally open;
  for (const CellTally& t : cells) {
    open.add(t);
    if (open.count >= kMinSamplesPerPool) {
      pools.push_back(open);
      open = CellTally{};
    }
  }
  if (pools.empty()) pools.push_back(open);
  else pools.back().add(open);

  AgreementResult r;
  double worst_term = -1;
  for (const CellTally& t : pools) {
    const double a = t.sum / kSamples;
    const double var_a = std::max(0.0, t.sum2 / kSamples - a * a) / kSamples;
    const double var = var_a + t.evaluated_var;
    if (!(var > 0)) continue;
    const double term = (a - t.evaluated) * (a - t.evaluated) / var;
    r.statistic += term;
    ++r.dof;
    if (term > worst_term) {
      worst_term = term;
      r.worst = "pool of " + std::to_string(int(t.count)) + " samples: sampled " + std::to_string(a) +
                ", evaluated " + std::to_string(t.evaluated) + ", term " + std::to_string(term);
    }
  }
  r.p_value = below > 0 ? 0.0 : detail::chi2_survival(r.statistic, r.dof);
  if (below > 0) r.worst = std::to_string(below) + " samples below the surface";
  return r;
}

// E[f(a, b)] = E[f(b, a)] for a few random pairs (4.5 sigma per comparison).
template <class Bxdf>
void expect_reciprocal(const Bxdf& bxdf, const std::string& name, int estimates = 400) {
  Rng rng(41, 42);
  for (int pair = 0; pair < 4; ++pair) {
    const Vec3f a = direction_at(0.1 + 0.85 * rng.next_float(), 6.28 * rng.next_float());
    const Vec3f b = direction_at(0.1 + 0.85 * rng.next_float(), 6.28 * rng.next_float());
    const MeanEstimate ab = mean_of(estimates, [&](int k) { return double(bxdf.eval(jitter(a, k), b).average()); });
    const MeanEstimate ba = mean_of(estimates, [&](int k) { return double(bxdf.eval(jitter(b, k), a).average()); });
    const double se = std::sqrt(ab.stderr_ * ab.stderr_ + ba.stderr_ * ba.stderr_);
    EXPECT_NEAR(ab.mean, ba.mean, 4.5 * se + 1e-6 * ab.mean) << name << " pair " << pair;
  }
}

// Non-specular samples report pdf(wo, wi); the pdf is positive over wo's hemisphere and 0 across the surface.
// Counts the non-specular samples seen in *non_specular.
inline void expect_samples_report_pdf(const Material& m, const std::string& name, int* non_specular) {
  Rng rng(61, 62);
  *non_specular = 0;
  for (float c : {0.8f, 0.2f, -0.5f}) {
    const Vec3f wo = direction_at(c, 0.9);
    for (int i = 0; i < 3000; ++i) {
      const float uc = rng.next_float();
      const auto s = m.sample(wo, uc, rng.next_2d());
      if (!s) continue;
      ASSERT_GT(s->wi.z * wo.z, 0.0f) << name;  // reflection only, on wo's side (mirrored below)
      ASSERT_FALSE(s->is_transmission()) << name;
      if (s->is_specular()) continue;
      ++*non_specular;
      ASSERT_EQ(s->pdf, m.pdf(wo, s->wi)) << name;
      ASSERT_TRUE(s->f.is_finite() && !s->f.has_negative()) << name;
    }
    for (int i = 0; i < 200; ++i) {
      Vec3f wi = sample_uniform_hemisphere(rng.next_2d());
      if (wo.z < 0) wi.z = -wi.z;
      if (wi.z == 0) continue;
      ASSERT_GT(m.pdf(wo, wi), 0.0f) << name;
      ASSERT_EQ(m.pdf(wo, -wi), 0.0f) << name;
      ASSERT_TRUE(m.eval(wo, -wi).is_black()) << name;
    }
  }
}

}  // namespace kiln::test
