// CoatedConductor (pbrt-v4's layered BxDF over a conductor). Like CoatedDiffuse its sampler's density has no closed
// form; the tests use what can be proved:
//  * A closed form when both layers are smooth and the layer holds no medium: every walk leaves in the mirror
//    direction. With the coat's Fresnel reflectance R = F(theta_o) (the same from inside at the refracted angle),
//    the conductor's Fc at the refracted angle (its index relative to the coat) and the round-trip attenuation
//    a = exp(-2 t / mu_t), the walk's exits (after 1, 3, ... < max_depth events: K = floor(max_depth / 2) of them)
//    sum to the albedo
//      R + (1 - R)^2 Fc a (1 - (R Fc a)^K) / (1 - R Fc a),
//    returned as specular samples only (eval() is 0).
//  * A base that reflects nothing leaves the coat's own reflection, exactly.
//  * sample() and eval() estimate the same BSDF (layered_test_util.h's two-sample chi-square) with rough and smooth
//    coats and bases, a medium, and incidences down to grazing; energy (albedo <= 1 over a near-perfect conductor by
//    both routes), reciprocity of E[f], and that samples report pdf(wo, wi).
#include <gtest/gtest.h>

#include <complex>
#include <vector>

#include "layered_test_util.h"

namespace kiln::test {
namespace {

constexpr double kSigmas = 4.0;

// Gold-like per-channel index, relative to air.
const RgbComplexIor kGold{Rgb(0.16f, 0.40f, 1.59f), Rgb(6.6f, 2.37f, 1.70f)};

CoatedConductor coated(float eta, float coat_alpha, RgbComplexIor ior_in_air, float base_alpha, float thickness,
                       Rgb albedo = Rgb(0), float g = 0, int max_depth = 10, int n_samples = 1) {
  const RgbComplexIor under_coat{ior_in_air.eta / eta, ior_in_air.k / eta};
  const LayerStack layers{RoughDielectric{eta, TrowbridgeReitz(coat_alpha, coat_alpha)}, thickness, albedo, g,
                          max_depth, n_samples};
  return CoatedConductor{{layers, RoughConductor{TrowbridgeReitz(base_alpha, base_alpha), under_coat}}};
}

TEST(CoatedConductor, SmoothLayersMatchTheSeriesOfInternalReflections) {
  struct Config {
    float thickness;
    int max_depth;
  };
  constexpr float kEta = 1.5f;
  for (const Config cfg : {Config{0.0f, 10}, Config{0.05f, 10}, Config{0.0f, 3}, Config{0.3f, 100}}) {
    const CoatedConductor bxdf = coated(kEta, 0.0f, kGold, 0.0f, cfg.thickness, Rgb(0), 0, cfg.max_depth);
    const Material m = surface_material(bxdf);
    EXPECT_EQ(bxdf.flags(), kLobeReflection | kLobeSpecular);
    const int K = cfg.max_depth / 2;
    for (float c : {1.0f, 0.6f, 0.2f, 0.03f}) {
      const Vec3f wo = direction_at(c, 0.7);
      const double R = fresnel_dielectric_ref(c, 1, kEta);
      const double mu_t = std::sqrt(1 - (1 - double(c) * c) / (kEta * kEta));
      const double a = std::exp(-2 * cfg.thickness / mu_t);
      Rng rng(3, uint64_t(cfg.max_depth * 100 + c * 100));
      for (int ch = 0; ch < 3; ++ch) {
        const double fc = fresnel_conductor_ref(mu_t, {kGold.eta[ch] / kEta, kGold.k[ch] / kEta});
        const double q = R * fc * a;
        const double expected = R + (1 - R) * (1 - R) * fc * a * (1 - std::pow(q, K)) / (1 - q);
        int not_mirror = 0;
        const MeanEstimate e = mean_of(40000, [&](int) {
          const float uc = rng.next_float();
          const auto s = m.sample(wo, uc, rng.next_2d());
          if (!s) return 0.0;
          if (!s->is_specular() || length(s->wi - reflect_z(wo)) > 1e-5f) ++not_mirror;
          return double(s->f[ch]) * std::abs(s->wi.z) / s->pdf;
        });
        EXPECT_EQ(not_mirror, 0);
        EXPECT_NEAR(e.mean, expected, kSigmas * e.stderr_ + 2e-5)
            << "thickness " << cfg.thickness << " max_depth " << cfg.max_depth << " cos " << c << " channel " << ch;
      }
      EXPECT_TRUE(m.eval(wo, direction_at(0.5, 2.0)).is_black());
    }
  }
}

TEST(CoatedConductor, BaseThatReflectsNothingLeavesTheCoat) {
  // eta = 1, k = 0 relative to the coat: the conductor's Fresnel reflectance is 0 at every angle.
  const CoatedConductor bxdf = coated(1.5f, 0.3f, {Rgb(1.5f), Rgb(0.0f)}, 0.2f, 0.01f);
  Rng rng(21, 22);
  for (int i = 0; i < 500; ++i) {
    const Vec3f wo = sample_uniform_hemisphere(rng.next_2d()), wi = sample_uniform_hemisphere(rng.next_2d());
    ASSERT_EQ(bxdf.eval(wo, wi), Rgb(bxdf.layers.coat.f(wo, wi)));
  }
}

struct Case {
  std::string name;
  CoatedConductor bxdf;
  int evals_per_cell = 120;  // sample_eval_agreement's
};

std::vector<Case> cases() {
  const auto alpha = TrowbridgeReitz::roughness_to_alpha;
  return {
      // The feature scene's coated gold: interface roughness 0.02, conductor roughness 0.1.
      {"scene_gold", coated(1.5f, alpha(0.02f), kGold, alpha(0.1f), 0.01f)},
      {"rough_both", coated(1.5f, 0.3f, kGold, 0.4f, 0.01f)},
      {"smooth_coat_rough_base", coated(1.5f, 0.0f, kGold, 0.3f, 0.01f)},
      {"medium", coated(1.33f, 0.2f, kGold, 0.3f, 0.5f, Rgb(0.9f, 0.6f, 0.3f), 0.5f)},
      {"two_samples", coated(1.5f, 0.5f, kGold, 0.2f, 0.1f, Rgb(0.5f), 0.0f, 10, 2)},
      {"rough_coat_smooth_base", coated(1.5f, 0.25f, kGold, 0.0f, 0.01f)},  // agreement: its own test below
  };
}
constexpr float kIncidences[] = {0.9f, 0.5f, 0.15f, 0.02f};

void expect_sample_and_eval_agree(const std::vector<Case>& tested, uint64_t seed) {
  const int num_tests = int(tested.size() * std::size(kIncidences));
  for (const Case& cc : tested) {
    for (float c : kIncidences) {
      const AgreementResult r =
          sample_eval_agreement(surface_material(cc.bxdf), direction_at(c, 0.4), ++seed, cc.evals_per_cell);
      ASSERT_GT(r.dof, 10) << cc.name << " cos " << c;
      EXPECT_GE(r.p_value, detail::sidak_threshold(0.01, num_tests)) << cc.name << " cos " << c << ": chi2 "
                                                                      << r.statistic << " dof " << r.dof << " p "
                                                                      << r.p_value << "; worst " << r.worst;
    }
  }
}

TEST(CoatedConductor, SampleAndEvalEstimateTheSameBsdf) {
  std::vector<Case> tested = cases();
  tested.pop_back();  // the smooth base, below
  expect_sample_and_eval_agree(tested, 3000);
}

// A rough coat over a mirror: each eval() is a narrow spike (the coat's transmission lobe around the mirrored entry
// direction), so the per-cell means take 2000 calls to have a trustworthy sample variance (with 120, cells at
// grazing incidence fail although 20000 calls agree with 2 M samples: chi2 107 on 96 cells).
TEST(CoatedConductor, SampleAndEvalEstimateTheSameBsdfOverASmoothBase) {
  expect_sample_and_eval_agree({{"rough_coat_smooth_base", coated(1.5f, 0.25f, kGold, 0.0f, 0.01f), 2000}}, 3100);
}

TEST(CoatedConductor, AlbedoAtMostOne) {
  // A near-perfect conductor (eta = 1, k = 200 relative to air: Fc > 0.9999) under coats that lose nothing.
  const RgbComplexIor mirror{Rgb(1.0f), Rgb(200.0f)};
  const std::vector<std::pair<std::string, CoatedConductor>> white = {
      {"rough_both", coated(1.5f, 0.3f, mirror, 0.3f, 0.0f, Rgb(0), 0, 100)},
      {"smooth_coat", coated(1.5f, 0.0f, mirror, 0.5f, 0.0f, Rgb(0), 0, 100)},
      {"smooth_base", coated(1.5f, 0.4f, mirror, 0.0f, 0.0f, Rgb(0), 0, 100)},
      {"medium", coated(1.5f, 0.2f, mirror, 0.2f, 1.0f, Rgb(1), 0.6f, 100)},
      {"dense_coat", coated(2.5f, 0.2f, mirror, 0.1f, 0.0f, Rgb(0), 0, 100)},
  };
  uint64_t seed = 400;
  for (const auto& [name, bxdf] : white) expect_albedo_at_most_one(surface_material(bxdf), name, kSigmas, seed);
}

TEST(CoatedConductor, ExpectedValueIsReciprocal) {
  for (const Case& cc : cases()) expect_reciprocal(cc.bxdf, cc.name);
}

TEST(CoatedConductor, SamplesReportThePdfFunction) {
  for (const Case& cc : cases()) {
    int glossy = 0;
    expect_samples_report_pdf(surface_material(cc.bxdf), cc.name, &glossy);
    EXPECT_GT(glossy, 1000) << cc.name;
  }
}

TEST(CoatedConductor, FlagsFollowTheLayers) {
  EXPECT_EQ(coated(1.5f, 0.0f, kGold, 0.0f, 0.01f).flags(), kLobeReflection | kLobeSpecular);
  EXPECT_EQ(coated(1.5f, 0.0f, kGold, 0.2f, 0.01f).flags(), kLobeReflection | kLobeSpecular | kLobeGlossy);
  EXPECT_EQ(coated(1.5f, 0.2f, kGold, 0.0f, 0.01f).flags(), kLobeReflection | kLobeGlossy);
  EXPECT_TRUE(coated(1.5f, 0.2f, kGold, 0.2f, 0.5f, Rgb(0.5f)).flags() & kLobeDiffuse);
  EXPECT_FALSE(surface_material(coated(1.5f, 0.2f, kGold, 0.2f, 0.01f)).oriented());
}

}  // namespace
}  // namespace kiln::test
