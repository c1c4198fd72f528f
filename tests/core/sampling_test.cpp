// Chi-square and normalisation tests for every warp in core/sampling.h.
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "support/chi2.h"

namespace kiln {
namespace {

using test::chi2_discrete;
using test::chi2_sphere;
using test::integrate_sphere;

constexpr uint64_t kSamples = 1'000'000;
constexpr double kPiD = 3.14159265358979323846;
// Unit vectors produced in float are unit to within a few ulps.
constexpr float kUnitTol = 1e-5f;

double hemisphere_pdf(Vec3f w) { return w.z > 0.0f ? double(uniform_hemisphere_pdf()) : 0.0; }
double cone_pdf(Vec3f w, float one_minus_cos_max) {
  return 1.0 - double(w.z) <= double(one_minus_cos_max) ? double(uniform_cone_pdf(one_minus_cos_max)) : 0.0;
}

TEST(UniformHemisphere, Chi2) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_uniform_hemisphere(rng.next_2d()); }, hemisphere_pdf,
                             kSamples, 20, 40);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(UniformSphere, Chi2) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_uniform_sphere(rng.next_2d()); },
                             [](Vec3f) { return double(uniform_sphere_pdf()); }, kSamples, 20, 40);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(CosineHemisphere, Chi2) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_cosine_hemisphere(rng.next_2d()); },
                             [](Vec3f w) { return double(cosine_hemisphere_pdf(w.z)); }, kSamples, 20, 40);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(UniformCone, Chi2ForSeveralApertures) {
  for (float half_angle_deg : {10.0f, 30.0f, 60.0f, 90.0f, 120.0f, 175.0f}) {
    // 1 - cos computed as 2 sin^2(theta/2) keeps its precision for small cones.
    const float omc = 2.0f * sqr(std::sin(radians(half_angle_deg) * 0.5f));
    // About six theta bins across the cone.
    const int theta_bins = int(std::ceil(180.0f * 6.0f / half_angle_deg));
    const auto r = chi2_sphere([&](Rng& rng) { return sample_uniform_cone(rng.next_2d(), omc); },
                               [&](Vec3f w) { return cone_pdf(w, omc); }, kSamples, theta_bins, 32);
    EXPECT_TRUE(r.passed) << "half angle " << half_angle_deg << ": " << r.message;
  }
}

TEST(UniformCone, TinyConesAreUniformAroundTheAxis) {
  // The cone is far smaller than any sphere cell, so histogram it locally: with s = (1 - cos theta) / (1 - cos_max)
  // computed as sin^2 / ((1 + cos) (1 - cos_max)) (no cancellation), a uniform cone has s and phi independent and
  // uniform on [0,1) x [0, 2 pi).
  constexpr int kSBins = 16, kPhiBins = 16;
  for (float omc : {1e-2f, 1e-4f, 1e-6f}) {
    std::vector<uint64_t> obs(kSBins * kPhiBins, 0);
    Rng rng(11, 0);
    int outside = 0, not_unit = 0;
    for (uint64_t k = 0; k < kSamples; ++k) {
      const Vec3f w = sample_uniform_cone(rng.next_2d(), omc);
      const double sin2 = double(w.x) * w.x + double(w.y) * w.y;
      const double s = sin2 / ((1.0 + w.z) * omc);
      if (s > 1.0 + 1e-5) ++outside;
      if (std::abs(length(w) - 1.0f) > kUnitTol) ++not_unit;
      double phi = std::atan2(double(w.y), double(w.x));
      if (phi < 0.0) phi += 2.0 * kPiD;
      const int si = std::clamp(int(s * kSBins), 0, kSBins - 1);
      const int pj = std::clamp(int(phi / (2.0 * kPiD) * kPhiBins), 0, kPhiBins - 1);
      ++obs[size_t(si) * kPhiBins + pj];
    }
    EXPECT_EQ(outside, 0) << "omc " << omc;
    EXPECT_EQ(not_unit, 0) << "omc " << omc;
    const std::vector<double> p(obs.size(), 1.0 / double(obs.size()));
    const auto r = chi2_discrete(obs, p);
    EXPECT_TRUE(r.passed) << "omc " << omc << ": " << r.message;
    // The pdf is the reciprocal of the cone's solid angle 2 pi (1 - cos_max).
    EXPECT_NEAR(double(uniform_cone_pdf(omc)) * 2.0 * kPiD * omc, 1.0, 1e-6);
  }
}

TEST(UniformCone, TinyConeLocalHistogramDetectsNonUniformity) {
  // Guard that the local histogram above can fail: squaring u.x concentrates samples towards the axis.
  constexpr int kSBins = 16;
  constexpr float omc = 1e-6f;
  std::vector<uint64_t> obs(kSBins, 0);
  Rng rng(11, 0);
  for (uint64_t k = 0; k < kSamples; ++k) {
    Vec2f u = rng.next_2d();
    u.x = u.x * (0.98f + 0.02f * u.x);  // a 1% distortion
    const Vec3f w = sample_uniform_cone(u, omc);
    const double s = (double(w.x) * w.x + double(w.y) * w.y) / ((1.0 + w.z) * omc);
    ++obs[size_t(std::clamp(int(s * kSBins), 0, kSBins - 1))];
  }
  const std::vector<double> p(kSBins, 1.0 / kSBins);
  EXPECT_FALSE(chi2_discrete(obs, p).passed);
}

TEST(ConcentricDisk, Chi2CartesianHistogram) {
  // 16x16 cells over [-1,1]^2; a cell's probability is its overlap with the unit disk over pi, the overlap
  // integrated in x from the exact y-extent of the disk at each x.
  constexpr int kBins = 16;
  constexpr int kXSteps = 8192;
  const double cell = 2.0 / kBins;
  std::vector<double> p(kBins * kBins);
  double total = 0.0;
  for (int i = 0; i < kBins; ++i)
    for (int j = 0; j < kBins; ++j) {
      const double x0 = -1.0 + i * cell, y0 = -1.0 + j * cell, y1 = y0 + cell;
      double area = 0.0;
      for (int k = 0; k < kXSteps; ++k) {
        const double x = x0 + (k + 0.5) * cell / kXSteps;
        const double h = std::sqrt(std::max(0.0, 1.0 - x * x));
        area += std::max(0.0, std::min(y1, h) - std::max(y0, -h));
      }
      p[size_t(i) * kBins + j] = area * (cell / kXSteps) / kPiD;
      total += p[size_t(i) * kBins + j];
    }
  ASSERT_NEAR(total, 1.0, 1e-5);
  std::vector<uint64_t> obs(p.size(), 0);
  Rng rng(3, 0);
  int outside = 0;
  for (uint64_t k = 0; k < kSamples; ++k) {
    const Vec2f d = sample_uniform_disk_concentric(rng.next_2d());
    if (d.x * d.x + d.y * d.y > 1.0f + 1e-6f) ++outside;
    const int i = std::clamp(int((d.x + 1.0f) / float(cell)), 0, kBins - 1);
    const int j = std::clamp(int((d.y + 1.0f) / float(cell)), 0, kBins - 1);
    ++obs[size_t(i) * kBins + j];
  }
  EXPECT_EQ(outside, 0);
  const auto r = chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(ConcentricDisk, Chi2PolarHistogram) {
  // Equal-area cells: r^2 and phi uniform.
  constexpr int kRBins = 16, kPhiBins = 32;
  std::vector<uint64_t> obs(kRBins * kPhiBins, 0);
  Rng rng(5, 0);
  for (uint64_t k = 0; k < kSamples; ++k) {
    const Vec2f d = sample_uniform_disk_concentric(rng.next_2d());
    const double r2 = double(d.x) * d.x + double(d.y) * d.y;
    double phi = std::atan2(double(d.y), double(d.x));
    if (phi < 0.0) phi += 2.0 * kPiD;
    const int i = std::clamp(int(r2 * kRBins), 0, kRBins - 1);
    const int j = std::clamp(int(phi / (2.0 * kPiD) * kPhiBins), 0, kPhiBins - 1);
    ++obs[size_t(i) * kPhiBins + j];
  }
  const std::vector<double> p(obs.size(), 1.0 / double(obs.size()));
  const auto r = chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
}

// The concentric map's own cosine and sine agree with libm's to float precision over the whole quarter turn they
// are used on (and so the disk's points to within a few ulps of the exact map).
TEST(ConcentricDisk, QuarterTurnCosineAndSineMatchLibm) {
  constexpr int kSteps = 100000;
  double worst = 0.0;
  for (int i = 0; i <= kSteps; ++i) {
    const float a = (kPi / 4.0f) * (2.0f * float(i) / float(kSteps) - 1.0f);
    const Vec2f cs = cos_sin_within_quarter_pi(a);
    worst = std::max({worst, std::abs(double(cs.x) - std::cos(double(a))),
                      std::abs(double(cs.y) - std::sin(double(a)))});
  }
  EXPECT_LT(worst, 1.2e-7) << "largest error against cos/sin in double";
  for (const Vec2f u : {Vec2f{0.9f, 0.6f}, Vec2f{0.55f, 0.95f}, Vec2f{0.1f, 0.3f}, Vec2f{0.35f, 0.02f}}) {
    const Vec2f d = sample_uniform_disk_concentric(u);
    const double ox = 2.0 * u.x - 1.0 + kHalfUnitGridStep, oy = 2.0 * u.y - 1.0 + kHalfUnitGridStep;
    const double r = std::abs(ox) > std::abs(oy) ? ox : oy;
    const double theta = std::abs(ox) > std::abs(oy) ? (kPiD / 4) * (oy / ox) : kPiD / 2 - (kPiD / 4) * (ox / oy);
    EXPECT_NEAR(d.x, r * std::cos(theta), 3e-7) << u.x << ", " << u.y;
    EXPECT_NEAR(d.y, r * std::sin(theta), 3e-7) << u.x << ", " << u.y;
  }
}

// u's grid is centred before mapping: its middle goes within a grid step of the disk's centre, and its first and
// last values (u = 0 included) stay inside the disk by about a grid step, so a cosine-weighted direction never
// lies on the horizon.
TEST(ConcentricDisk, CornersAndCentre) {
  const Vec2f c = sample_uniform_disk_concentric({0.5f, 0.5f});
  EXPECT_LE(std::abs(c.x) + std::abs(c.y), 2 * kHalfUnitGridStep);
  for (const Vec2f u : {Vec2f{0.0f, 0.0f}, Vec2f{0.0f, 0.5f}, Vec2f{0.0f, 0.73f}, Vec2f{kOneMinusEpsilon, 0.2f},
                        Vec2f{0.4f, 0.0f}, Vec2f{0.0f, kOneMinusEpsilon}}) {
    const Vec3f w = sample_cosine_hemisphere(u);
    EXPECT_GT(cosine_hemisphere_pdf(w.z), 0.0f) << u.x << ", " << u.y;
    EXPECT_NEAR(length(w), 1.0f, 1e-6f);
  }
  for (Vec2f u : {Vec2f{0.0f, 0.0f}, Vec2f{kOneMinusEpsilon, 0.0f}, Vec2f{0.0f, kOneMinusEpsilon},
                  Vec2f{kOneMinusEpsilon, kOneMinusEpsilon}}) {
    const Vec2f d = sample_uniform_disk_concentric(u);
    EXPECT_NEAR(d.x * d.x + d.y * d.y, 1.0f, 1e-5f);
  }
}

TEST(UniformTriangle, Chi2BarycentricHistogram) {
  // (b1, b2) binned on an n x n grid of the unit square: cells below the diagonal b1 + b2 = 1 hold 2/n^2 of the
  // probability, cells the diagonal cuts corner to corner hold half of that, cells above it none.
  constexpr int kBins = 20;
  std::vector<double> p(kBins * kBins, 0.0);
  for (int i = 0; i < kBins; ++i)
    for (int j = 0; j < kBins; ++j) {
      const double full = 2.0 / (kBins * kBins);
      p[size_t(i) * kBins + j] = (i + j < kBins - 1) ? full : (i + j == kBins - 1 ? 0.5 * full : 0.0);
    }
  std::vector<uint64_t> obs(p.size(), 0);
  Rng rng(9, 0);
  int invalid = 0;
  for (uint64_t k = 0; k < kSamples; ++k) {
    const Vec2f b = sample_uniform_triangle(rng.next_2d());
    if (b.x < 0.0f || b.y < 0.0f || b.x + b.y > 1.0f + 1e-6f) ++invalid;
    const int i = std::clamp(int(b.x * kBins), 0, kBins - 1);
    const int j = std::clamp(int(b.y * kBins), 0, kBins - 1);
    ++obs[size_t(i) * kBins + j];
  }
  EXPECT_EQ(invalid, 0);
  const auto r = chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Distribution1D, Chi2WithZeroWeights) {
  const std::vector<float> w{0.0f, 3.0f, 0.0f, 0.0f, 1.0f, 5.0f, 0.0f, 0.5f, 2.0f, 0.0f, 0.01f, 0.0f};
  const Distribution1D dist(w);
  ASSERT_EQ(dist.size(), w.size());
  double total = 0.0;
  for (float x : w) total += x;
  EXPECT_NEAR(dist.total(), total, 1e-9);
  std::vector<double> p(w.size());
  for (size_t i = 0; i < w.size(); ++i) {
    p[i] = double(w[i]) / total;
    EXPECT_NEAR(dist.pmf(i), p[i], 1e-7) << i;
  }
  std::vector<uint64_t> obs(w.size(), 0);
  constexpr int kRemapBins = 32;
  std::vector<uint64_t> remap_obs(kRemapBins, 0);
  Rng rng(13, 0);
  int pmf_mismatch = 0, remap_out_of_range = 0;
  for (uint64_t k = 0; k < kSamples; ++k) {
    float pmf = -1.0f, u2 = -1.0f;
    const size_t i = dist.sample(rng.next_float(), &pmf, &u2);
    ASSERT_LT(i, w.size());
    ++obs[i];
    if (pmf != dist.pmf(i)) ++pmf_mismatch;
    if (!(u2 >= 0.0f && u2 < 1.0f)) ++remap_out_of_range;
    ++remap_obs[size_t(std::clamp(int(u2 * kRemapBins), 0, kRemapBins - 1))];
  }
  EXPECT_EQ(pmf_mismatch, 0);
  EXPECT_EQ(remap_out_of_range, 0);
  for (size_t i = 0; i < w.size(); ++i)
    if (w[i] == 0.0f) {
      EXPECT_EQ(obs[i], 0u) << "zero-weight entry " << i << " was chosen";
    }
  const auto r = chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
  // The remapped u is uniform on [0,1) again (so it can drive another sampling decision).
  const std::vector<double> pu(kRemapBins, 1.0 / kRemapBins);
  const auto ru = chi2_discrete(remap_obs, pu);
  EXPECT_TRUE(ru.passed) << ru.message;
}

TEST(Distribution1D, ZeroWeightEntriesNeverChosenAtBoundaries) {
  const std::vector<float> w{0.0f, 1.0f, 0.0f, 1.0f, 0.0f};
  const Distribution1D dist(w);
  // u at 0, at the end, exactly on the CDF step between the two live entries, and just around it.
  for (float u : {0.0f, kOneMinusEpsilon, 0.5f, std::nextafter(0.5f, 0.0f), std::nextafter(0.5f, 1.0f), 1.0f}) {
    float pmf = 0.0f;
    const size_t i = dist.sample(u, &pmf);
    EXPECT_TRUE(i == 1 || i == 3) << "u = " << u << " chose " << i;
    EXPECT_EQ(pmf, 0.5f) << "u = " << u;
  }
  EXPECT_EQ(dist.sample(0.5f), 3u);  // [0.5, 1) belongs to the second live entry
  EXPECT_EQ(dist.sample(std::nextafter(0.5f, 0.0f)), 1u);
}

TEST(Distribution1D, NegligibleWeightIsNeverChosenWithZeroPmf) {
  // A weight so small relative to the total that its float pmf underflows to 0 must not be returned (a chosen
  // entry with pmf 0 would divide by zero in the estimator), and neither may the zero-weight entry before it.
  const std::vector<float> w{0.0f, 1e-30f, 1e20f};
  const Distribution1D dist(w);
  for (float u : {0.0f, 1e-30f, 0.5f, kOneMinusEpsilon}) {
    float pmf = 0.0f;
    const size_t i = dist.sample(u, &pmf);
    EXPECT_GT(pmf, 0.0f) << "u = " << u << " chose " << i;
    EXPECT_NE(i, 0u) << "u = " << u;
  }
}

TEST(Distribution1D, InvalidAndEmptyWeights) {
  const std::vector<float> bad{-1.0f, std::nanf(""), kInfinity, 2.0f};
  const Distribution1D dist(bad);
  EXPECT_EQ(dist.pmf(3), 1.0f);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(dist.pmf(i), 0.0f);
  for (float u : {0.0f, 0.3f, kOneMinusEpsilon}) EXPECT_EQ(dist.sample(u), 3u);

  const std::vector<float> zeros{0.0f, 0.0f};
  const Distribution1D none(zeros);
  float pmf = 1.0f;
  EXPECT_EQ(none.sample(0.5f, &pmf), 0u);
  EXPECT_EQ(pmf, 0.0f);
  EXPECT_EQ(none.total(), 0.0);

  const Distribution1D empty;
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_EQ(empty.pmf(0), 0.0f);
}

TEST(PowerHeuristic, Sanity) {
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3.0f, 1.0f), 0.9f);
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(power_heuristic(0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(kInfinity, 5.0f), 1.0f);  // delta distributions always win
  EXPECT_FLOAT_EQ(power_heuristic(5.0f, kInfinity), 0.0f);
  Rng rng(17, 0);
  for (int k = 0; k < 10000; ++k) {
    // Weights of the two strategies partition unity over the whole dynamic range of float pdfs (grazing
    // area-light pdfs reach 1e20 and more, where squaring overflows).
    const float f = std::pow(10.0f, 60.0f * (rng.next_float() - 0.5f));
    const float g = std::pow(10.0f, 60.0f * (rng.next_float() - 0.5f));
    const float wf = power_heuristic(f, g), wg = power_heuristic(g, f);
    ASSERT_TRUE(std::isfinite(wf)) << f << " " << g;
    EXPECT_NEAR(wf + wg, 1.0f, 1e-6f) << f << " " << g;
    EXPECT_GE(wf, 0.0f);
    EXPECT_LE(wf, 1.0f);
    if (f > 1.001f * g) {
      EXPECT_GT(wf, 0.5f) << f << " " << g;
    }
    // Only the ratio of the pdfs matters.
    EXPECT_NEAR(power_heuristic(f, g), power_heuristic(f * 1e-3f, g * 1e-3f), 1e-5f) << f << " " << g;
  }
  EXPECT_FLOAT_EQ(power_heuristic(1e25f, 1e25f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(1e-25f, 1e-25f), 0.5f);
}

TEST(SamplingPdfs, IntegrateToOne) {
  // The pdfs are float constants (1/(2 pi) and 1/(4 pi) carry a relative rounding error of ~4e-8).
  EXPECT_NEAR(integrate_sphere(hemisphere_pdf), 1.0, 1e-7);
  EXPECT_NEAR(integrate_sphere([](Vec3f) { return double(uniform_sphere_pdf()); }), 1.0, 1e-7);
  // cos(theta)/pi is linear in cos(theta): the midpoint rule is exact up to rounding.
  EXPECT_NEAR(integrate_sphere([](Vec3f w) { return double(cosine_hemisphere_pdf(w.z)); }), 1.0, 1e-6);
  // Cone edges at 1 - cos = k/256 fall on grid lines of the default 512-row cos(theta) grid.
  for (float omc : {0.25f, 1.0f, 1.5f, 2.0f})
    EXPECT_NEAR(integrate_sphere([&](Vec3f w) { return cone_pdf(w, omc); }), 1.0, 1e-5) << "omc " << omc;
}

TEST(SamplingWarps, ExtremeInputsGiveFiniteUnitVectors) {
  const std::array<Vec2f, 5> us{Vec2f{0.0f, 0.0f}, Vec2f{kOneMinusEpsilon, 0.0f}, Vec2f{0.0f, kOneMinusEpsilon},
                                Vec2f{kOneMinusEpsilon, kOneMinusEpsilon}, Vec2f{0.5f, 0.5f}};
  for (Vec2f u : us) {
    for (Vec3f w : {sample_uniform_hemisphere(u), sample_uniform_sphere(u), sample_cosine_hemisphere(u),
                    sample_uniform_cone(u, 1e-6f), sample_uniform_cone(u, 2.0f)}) {
      EXPECT_TRUE(is_finite(w)) << u.x << " " << u.y;
      EXPECT_NEAR(length(w), 1.0f, kUnitTol) << u.x << " " << u.y;
    }
    EXPECT_GE(sample_uniform_hemisphere(u).z, 0.0f);
    EXPECT_GE(sample_cosine_hemisphere(u).z, 0.0f);
  }
}

}  // namespace
}  // namespace kiln
