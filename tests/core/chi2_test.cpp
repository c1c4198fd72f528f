// Tests of the chi-square test support itself: the p-value, the pooling, and that wrong samplers fail.
#include "support/chi2.h"

#include <gtest/gtest.h>

#include <array>

#include "core/sampling.h"

namespace kiln {
namespace {

using test::chi2_discrete;
using test::chi2_sphere;
using test::integrate_sphere;

constexpr uint64_t kSamples = 1'000'000;

TEST(Chi2Survival, MatchesTabulatedQuantiles) {
  // Upper-tail quantiles of the chi-square distribution (standard tables).
  EXPECT_NEAR(test::detail::chi2_survival(3.841458820694124, 1), 0.05, 1e-9);
  EXPECT_NEAR(test::detail::chi2_survival(6.634896601021214, 1), 0.01, 1e-9);
  EXPECT_NEAR(test::detail::chi2_survival(18.307038053275146, 10), 0.05, 1e-9);
  EXPECT_NEAR(test::detail::chi2_survival(124.34211340400407, 100), 0.05, 1e-9);
  EXPECT_NEAR(test::detail::chi2_survival(1074.6794394, 1000), 0.05, 1e-7);
  // Two degrees of freedom: Q = exp(-x/2) exactly.
  for (double x : {0.1, 1.0, 5.0, 30.0, 200.0}) EXPECT_NEAR(test::detail::chi2_survival(x, 2), std::exp(-0.5 * x), 1e-12);
  EXPECT_EQ(test::detail::chi2_survival(0.0, 5), 1.0);
}

TEST(Chi2Survival, SidakThreshold) {
  EXPECT_NEAR(test::detail::sidak_threshold(0.01, 1), 0.01, 1e-12);
  EXPECT_NEAR(test::detail::sidak_threshold(0.01, 10), 0.0010045, 1e-6);
}

TEST(Chi2Discrete, FairDiePasses) {
  Rng rng(7, 0);
  std::array<uint64_t, 6> obs{};
  for (uint64_t i = 0; i < kSamples; ++i) ++obs[std::min<size_t>(5, size_t(rng.next_float() * 6))];
  const std::array<double, 6> p{1 / 6.0, 1 / 6.0, 1 / 6.0, 1 / 6.0, 1 / 6.0, 1 / 6.0};
  const auto r = chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_EQ(r.dof, 5);
}

TEST(Chi2Discrete, SlightlyLoadedDieFails) {
  Rng rng(7, 0);
  std::array<uint64_t, 6> obs{};
  // Face 5 is 1% more likely than the others: a 1M-sample test must see it.
  const std::array<double, 6> loaded_cdf{0.1663, 0.3326, 0.4989, 0.6652, 0.8315, 1.0};
  for (uint64_t i = 0; i < kSamples; ++i) {
    const float u = rng.next_float();
    size_t k = 0;
    while (u >= loaded_cdf[k]) ++k;
    ++obs[k];
  }
  const std::array<double, 6> p{1 / 6.0, 1 / 6.0, 1 / 6.0, 1 / 6.0, 1 / 6.0, 1 / 6.0};
  const auto r = chi2_discrete(obs, p);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2Discrete, CountInZeroProbabilityEntryFails) {
  const std::array<uint64_t, 3> obs{500000, 1, 499999};
  const std::array<double, 3> p{0.5, 0.0, 0.5};
  const auto r = chi2_discrete(obs, p);
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.message.find("entry 1"), std::string::npos) << r.message;
}

TEST(Chi2Discrete, UnderNormalisedModelFails) {
  const std::array<uint64_t, 2> obs{500000, 500000};
  const std::array<double, 2> p{0.49, 0.49};  // 2% of the probability is missing
  EXPECT_FALSE(chi2_discrete(obs, p).passed);
}

TEST(Chi2Discrete, SizeMismatchFails) {
  const std::array<uint64_t, 2> obs{1, 1};
  const std::array<double, 3> p{0.3, 0.3, 0.4};
  const auto r = chi2_discrete(obs, p);
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.message.find("observed"), std::string::npos);
}

TEST(Chi2Discrete, PoolsSmallExpectations) {
  // Ten entries expecting 1 sample each (of 100000) must be pooled, leaving 2 cells: the big one and the pool.
  std::array<uint64_t, 11> obs{};
  std::array<double, 11> p{};
  obs[0] = 99990;
  p[0] = 0.9999;
  for (size_t i = 1; i < 11; ++i) {
    obs[i] = 1;
    p[i] = 1e-5;
  }
  const auto r = chi2_discrete(obs, p);
  EXPECT_TRUE(r.passed) << r.message;
  EXPECT_EQ(r.dof, 1) << r.message;
}

TEST(Chi2Discrete, PValuesAreCalibrated) {
  // Under the null hypothesis p-values are uniform: about 10% of 400 fair experiments fall below 0.1.
  constexpr int kTrials = 400;
  int below = 0;
  for (int t = 0; t < kTrials; ++t) {
    Rng rng(1000 + t, 3);
    std::array<uint64_t, 10> obs{};
    const std::array<double, 10> p{0.05, 0.05, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.2};
    for (int i = 0; i < 2000; ++i) {
      const float u = rng.next_float();
      double c = 0;
      size_t k = 0;
      while (k < 9 && u >= (c += p[k])) ++k;
      ++obs[k];
    }
    if (chi2_discrete(obs, p).p_value < 0.1) ++below;
  }
  // Binomial(400, 0.1): mean 40, sd 6; +-4 sd.
  EXPECT_GT(below, 16);
  EXPECT_LT(below, 64);
}

TEST(Chi2Sphere, UniformSpherePasses) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_uniform_sphere(rng.next_2d()); },
                             [](Vec3f) { return double(kInv4Pi); }, kSamples, 20, 40);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Chi2Sphere, CosineSamplerAgainstUniformPdfFails) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_cosine_hemisphere(rng.next_2d()); },
                             [](Vec3f w) { return w.z > 0.0f ? double(kInv2Pi) : 0.0; }, kSamples, 20, 40);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2Sphere, SlightlyWrongPdfFails) {
  // Uniform sphere samples against a pdf that puts 3% more mass on the upper hemisphere.
  const auto r = chi2_sphere([](Rng& rng) { return sample_uniform_sphere(rng.next_2d()); },
                             [](Vec3f w) { return kInv4Pi * (w.z > 0.0f ? 1.03 : 0.97); }, kSamples, 20, 40);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2Sphere, FailedSamplesFailWhenPdfIntegratesToOne) {
  // Every 100th sample fails although the pdf claims all mass is on the sphere.
  uint64_t k = 0;
  const auto r = chi2_sphere(
      [&](Rng& rng) -> std::optional<Vec3f> {
        const Vec3f w = sample_uniform_sphere(rng.next_2d());
        if (++k % 100 == 0) return std::nullopt;
        return w;
      },
      [](Vec3f) { return double(kInv4Pi); }, kSamples, 20, 40);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2Sphere, FailedSamplesPassWhenPdfAccountsForThem) {
  // Samples below the horizon are discarded; the pdf (uniform sphere restricted to z > 0) integrates to 1/2.
  const auto r = chi2_sphere(
      [](Rng& rng) -> std::optional<Vec3f> {
        const Vec3f w = sample_uniform_sphere(rng.next_2d());
        if (w.z <= 0.0f) return std::nullopt;
        return w;
      },
      [](Vec3f w) { return w.z > 0.0f ? double(kInv4Pi) : 0.0; }, kSamples, 20, 40);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Chi2Sphere, SamplesWherePdfIsZeroFail) {
  // A hemisphere sampler that leaks 0.1% of its samples below the horizon.
  uint64_t k = 0;
  const auto r = chi2_sphere(
      [&](Rng& rng) {
        Vec3f w = sample_uniform_hemisphere(rng.next_2d());
        if (++k % 1000 == 0) w.z = -w.z;
        return w;
      },
      [](Vec3f w) { return w.z > 0.0f ? double(kInv2Pi) : 0.0; }, kSamples, 20, 40);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2Sphere, PdfTooLargeFails) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_uniform_sphere(rng.next_2d()); },
                             [](Vec3f) { return 2.0 * kInv4Pi; }, kSamples, 20, 40);
  EXPECT_FALSE(r.passed) << r.message;
}

TEST(Chi2Sphere, NonUnitSamplesFail) {
  const auto r = chi2_sphere([](Rng& rng) { return 1.01f * sample_uniform_sphere(rng.next_2d()); },
                             [](Vec3f) { return double(kInv4Pi); }, 1000, 4, 8);
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.message.find("unit"), std::string::npos) << r.message;
}

TEST(Chi2Sphere, InvalidPdfFails) {
  const auto r = chi2_sphere([](Rng& rng) { return sample_uniform_sphere(rng.next_2d()); },
                             [](Vec3f w) { return w.z > 0.5f ? std::nan("") : double(kInv4Pi); }, 1000, 4, 8);
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.message.find("pdf returned"), std::string::npos) << r.message;
}

TEST(Chi2Sphere, DiscontinuityInsideCellsIsIntegrated) {
  // A cone of half-angle 37 degrees: its edge crosses theta cells, so the expected counts depend on the adaptive
  // integration being accurate to well under the statistical noise.
  const float one_minus_cos = 1.0f - std::cos(radians(37.0f));
  const auto r = chi2_sphere([&](Rng& rng) { return sample_uniform_cone(rng.next_2d(), one_minus_cos); },
                             [&](Vec3f w) { return 1.0f - w.z <= one_minus_cos ? double(uniform_cone_pdf(one_minus_cos)) : 0.0; },
                             kSamples, 20, 40);
  EXPECT_TRUE(r.passed) << r.message;
}

TEST(Chi2Sphere, CellIntegrationResolvesEdges) {
  // Indicator of a cone of half-angle alpha integrated over the cell theta in [36, 45] deg, phi in [0, 9] deg,
  // for edges anywhere in the cell, including just inside its borders.
  constexpr double kDeg = 3.14159265358979323846 / 180.0, kN = 1e6;
  const double t0 = 36 * kDeg, t1 = 45 * kDeg, p1 = 9 * kDeg;
  for (double alpha_deg : {36.001, 36.05, 37.0, 39.5, 40.5, 42.0, 44.3, 44.95, 44.999}) {
    const double cos_alpha = std::cos(alpha_deg * kDeg);
    auto cone = [&](Vec3f w) { return double(w.z) >= cos_alpha ? 1.0 : 0.0; };
    const double exact = (std::cos(t0) - cos_alpha) * p1;
    const double got = test::detail::integrate_cell(cone, t0, t1, 0.0, p1, kN);
    // Within the promised fraction of the Poisson noise of a 1M-sample cell, or the documented edge resolution.
    const double area = (std::cos(t0) - std::cos(t1)) * p1;
    const double edge_limit = area / (4.0 * std::ldexp(1.0, test::detail::kMaxIntegrationDepth));
    EXPECT_NEAR(got, exact, std::max(test::detail::kIntegrationTolSigmas * std::sqrt(kN * exact) / kN, edge_limit))
        << "alpha = " << alpha_deg;
  }
}

TEST(Chi2Sphere, PValuesAreNotSystematicallySmall) {
  // Integration errors show up as p-values piling up near 0 over many seeds of a correct sampler.
  constexpr int kSeeds = 16;
  double mean_p = 0.0;
  for (int s = 0; s < kSeeds; ++s) {
    const auto r = chi2_sphere([](Rng& rng) { return sample_cosine_hemisphere(rng.next_2d()); },
                               [](Vec3f w) { return double(cosine_hemisphere_pdf(w.z)); }, 200'000, 10, 20, 0.01, 1,
                               uint64_t(100 + s));
    EXPECT_GT(r.p_value, 1e-4) << r.message;
    mean_p += r.p_value / kSeeds;
  }
  // Mean of 16 uniform variates: 0.5 +- 0.072 (1 sd).
  EXPECT_GT(mean_p, 0.2);
  EXPECT_LT(mean_p, 0.8);
}

TEST(IntegrateSphere, KnownIntegrals) {
  EXPECT_NEAR(integrate_sphere([](Vec3f) { return 1.0; }), 4.0 * 3.14159265358979, 1e-9);
  EXPECT_NEAR(integrate_sphere([](Vec3f w) { return w.z > 0.0f ? double(w.z) : 0.0; }), 3.14159265358979, 1e-5);
  EXPECT_NEAR(integrate_sphere([](Vec3f w) { return double(w.x) * w.x; }), 4.0 * 3.14159265358979 / 3.0, 1e-4);
}

}  // namespace
}  // namespace kiln
