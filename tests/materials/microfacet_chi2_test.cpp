// Chi-square goodness of fit of the pbrt-v4 microfacet BSDFs (RoughConductor, RoughDielectric) through
// Material::sample / Material::pdf, isotropic and anisotropic, smooth-ish to very rough, at normal, oblique,
// shallow and grazing incidence; the dielectric from outside and from inside (no mirroring: it handles both sides)
// and with eta < 1. Also the Henyey-Greenstein phase function of CoatedDiffuse's medium.
#include <gtest/gtest.h>

#include <vector>

#include "brdf_test_util.h"
#include "materials/henyey_greenstein.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

constexpr double kSignificance = 0.01;
constexpr uint64_t kSamples = 1'000'000;
constexpr float kIncidences[] = {1.0f, 0.6f, 0.15f, 1e-3f};

struct Chi2Case {
  std::string name;
  Material material;
  float cos_theta_o;
  int theta_bins, phi_bins;
};

Material rough_conductor(float ax, float ay) {
  return surface_material(RoughConductor{TrowbridgeReitz(ax, ay), {Rgb(0.2f, 0.9f, 1.1f), Rgb(3.9f, 2.4f, 2.1f)}});
}

Material rough_dielectric(float eta, float ax, float ay) {
  return surface_material(RoughDielectric{eta, TrowbridgeReitz(ax, ay)});
}

std::vector<Chi2Case> make_cases() {
  std::vector<Chi2Case> cases;
  auto add = [&](const std::string& name, const Material& m, int tb, int pb, bool both_sides) {
    for (float c : kIncidences) {
      cases.push_back({name + "_cos" + std::to_string(c), m, c, tb, pb});
      if (both_sides) cases.push_back({name + "_inside_cos" + std::to_string(c), m, -c, tb, pb});
    }
  };
  add("Conductor_a0.5", rough_conductor(0.5f, 0.5f), 20, 40, false);
  add("Conductor_a0.1", rough_conductor(0.1f, 0.1f), 60, 120, false);
  add("Conductor_aniso", rough_conductor(0.4f, 0.05f), 60, 120, false);
  add("Conductor_a1", rough_conductor(1.0f, 1.0f), 20, 40, false);
  add("Dielectric_a0.5", rough_dielectric(1.5f, 0.5f, 0.5f), 30, 60, true);
  add("Dielectric_a0.1", rough_dielectric(1.5f, 0.1f, 0.1f), 60, 120, true);
  add("Dielectric_aniso", rough_dielectric(1.5f, 0.3f, 0.08f), 60, 120, true);
  add("DielectricInv_a0.3", rough_dielectric(1.0f / 1.5f, 0.3f, 0.3f), 30, 60, true);
  return cases;
}

const std::vector<Chi2Case>& all_cases() {
  static const std::vector<Chi2Case> cases = make_cases();
  return cases;
}

class MicrofacetChi2 : public ::testing::TestWithParam<size_t> {};

TEST_P(MicrofacetChi2, SamplesFollowPdf) {
  const Chi2Case& c = all_cases()[GetParam()];
  const Vec3f wo = direction_at(c.cos_theta_o, 0.7);
  const Material& m = c.material;
  auto sample = [&](Rng& rng) -> std::optional<Vec3f> {
    const float uc = rng.next_float();
    const auto s = m.sample(wo, uc, rng.next_2d());
    if (!s || s->is_specular()) return std::nullopt;
    return s->wi;
  };
  auto pdf = [&](Vec3f wi) -> double { return m.pdf(wo, wi); };
  const Chi2Result r = chi2_sphere(sample, pdf, kSamples, c.theta_bins, c.phi_bins, kSignificance,
                                   int(all_cases().size()), 0x3f00000u + GetParam());
  EXPECT_TRUE(r.passed) << c.name << "\n" << r.message;
}

INSTANTIATE_TEST_SUITE_P(PbrtBxdfs, MicrofacetChi2, ::testing::Range(size_t(0), all_cases().size()),
                         [](const ::testing::TestParamInfo<size_t>& p) {
                           std::string n = all_cases()[p.param].name;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

TEST(HenyeyGreenstein, SamplesFollowPhaseFunction) {
  const float gs[] = {0.0f, 0.5f, -0.7f, 0.9f};
  for (float g : gs) {
    const HenyeyGreenstein hg{g};
    const Vec3f wo = direction_at(0.3, 1.1);
    const Chi2Result r = chi2_sphere([&](Rng& rng) { return std::optional<Vec3f>(hg.sample(wo, rng.next_2d())->wi); },
                                     [&](Vec3f wi) -> double { return hg.pdf(wo, wi); }, 500'000, 40, 80, kSignificance,
                                     4, 0x4700 + uint64_t(g * 100 + 100));
    EXPECT_TRUE(r.passed) << "g " << g << "\n" << r.message;
    // The sample reports the phase function value as its pdf.
    Rng rng(3, 9);
    for (int i = 0; i < 100; ++i) {
      const auto s = hg.sample(wo, rng.next_2d());
      ASSERT_TRUE(s);
      EXPECT_NEAR(s->p, hg.p(wo, s->wi), 1e-5f * s->p);
      EXPECT_EQ(s->p, s->pdf);
    }
  }
}

TEST(HenyeyGreenstein, ForwardMeansAwayFromWo) {
  // pbrt's convention: light arriving along -wo; g > 0 favours continuing along -wo.
  const HenyeyGreenstein hg{0.6f};
  const Vec3f wo(0, 0, 1);
  EXPECT_GT(hg.p(wo, Vec3f(0, 0, -1)), 10.0f * hg.p(wo, Vec3f(0, 0, 1)));
  // Isotropic for g = 0.
  EXPECT_NEAR(HenyeyGreenstein{0.0f}.p(wo, Vec3f(1, 0, 0)), 1.0 / (4 * 3.14159265358979), 1e-7);
}

}  // namespace
}  // namespace kiln::test
