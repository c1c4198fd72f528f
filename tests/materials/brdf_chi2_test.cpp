// Chi-square goodness of fit of every non-delta sampler against its own pdf, through Material::sample /
// Material::pdf, at several incident angles down to grazing. A Material mixing a surface with a delta part is
// tested too: its delta samples count as failed samples, whose expected share is delta_probability().
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "brdf_test_util.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

struct Chi2Case {
  std::string name;
  Material material;
  float cos_theta_o;
  int theta_bins, phi_bins;
  uint64_t samples;
};

constexpr double kSignificance = 0.01;
constexpr uint64_t kSamples = 1'000'000;
// Incidences: normal, oblique, shallow and grazing (the lobes clip against the horizon).
constexpr float kIncidences[] = {1.0f, 0.6f, 0.15f, 1e-3f};

std::vector<Chi2Case> make_cases() {
  std::vector<Chi2Case> cases;
  auto add = [&](const std::string& name, const Material& m, int tb, int pb) {
    for (float c : kIncidences) cases.push_back({name + "_cos" + std::to_string(c), m, c, tb, pb, kSamples});
  };
  add("Lambert", surface_material(Lambert{Rgb(0.7f)}), 20, 40);
  // Pure lobes (kd = 0) at a broad, a medium and a sharp exponent, bins matched to the lobe width. With kd = 0
  // the sampler does not depend on the variant, so one variant covers the lobe samplers...
  constexpr PhongVariant kNorm = PhongVariant::ModifiedNormalized;
  add("Phong_p1", surface_material(Phong{Rgb(0), Rgb(0.8f), 1.0f, kNorm}), 20, 40);
  add("Phong_p40", surface_material(Phong{Rgb(0), Rgb(0.8f), 40.0f, kNorm}), 40, 80);
  add("Blinn_p1", surface_material(BlinnPhong{Rgb(0), Rgb(0.8f), 1.0f, kNorm}), 20, 40);
  add("Blinn_p40", surface_material(BlinnPhong{Rgb(0), Rgb(0.8f), 40.0f, kNorm}), 40, 80);
  // ... while the kd + ks mixture probability differs per variant.
  for (PhongVariant v : {PhongVariant::Original, PhongVariant::Modified, PhongVariant::ModifiedNormalized}) {
    const std::string vn = variant_name(v);
    add("PhongMix" + vn, surface_material(Phong{Rgb(0.3f), Rgb(0.6f), 10.0f, v}), 30, 60);
    add("BlinnMix" + vn, surface_material(BlinnPhong{Rgb(0.3f), Rgb(0.6f), 10.0f, v}), 30, 60);
  }
  add("PhongSharp_p800", surface_material(Phong{Rgb(0), Rgb(1), 800.0f, PhongVariant::ModifiedNormalized}), 90, 180);
  add("BlinnSharp_p800", surface_material(BlinnPhong{Rgb(0), Rgb(1), 800.0f, PhongVariant::ModifiedNormalized}), 90,
      180);
  add("TS_p1", surface_material(TorranceSparrow{Rgb(0), Rgb(1), 1.0f, 1.5f, 0.0f, false}), 20, 40);
  add("TS_p50_mix_kdfresnel", surface_material(TorranceSparrow{Rgb(0.5f), Rgb(0.5f), 50.0f, 0.37f, 2.82f, true}), 40,
      80);
  // Surface + delta mixtures: delta samples are "failed" for the sphere test and must occur at the rate
  // delta_probability; the dielectric one is seen from inside (wo.z < 0) through the two-sided flip.
  Material mirror_mix = surface_material(BlinnPhong{Rgb(0.4f), Rgb(0.3f), 20.0f, PhongVariant::ModifiedNormalized});
  mirror_mix.delta = Mirror{Rgb(0.5f)};
  mirror_mix.roughness = 0.2f;
  add("BlinnPlusMirror", mirror_mix, 30, 60);
  Material glass = surface_material(Phong{Rgb(0), Rgb(0.3f), 20.0f, PhongVariant::ModifiedNormalized});
  glass.delta = Dielectric{1.5f};
  for (float c : kIncidences)
    cases.push_back({"PhongPlusGlassInside_cos" + std::to_string(c), glass, -c, 30, 60, kSamples});
  return cases;
}

const std::vector<Chi2Case>& all_cases() {
  static const std::vector<Chi2Case> cases = make_cases();
  return cases;
}

class BrdfChi2 : public ::testing::TestWithParam<size_t> {};

TEST_P(BrdfChi2, SamplesFollowPdf) {
  const Chi2Case& c = all_cases()[GetParam()];
  const Vec3f wo = direction_at(c.cos_theta_o, 0.7);
  const Material& m = c.material;
  auto sample = [&](Rng& rng) -> std::optional<Vec3f> {
    const float uc = rng.next_float();
    const Vec2f u = rng.next_2d();
    const auto s = m.sample(wo, uc, u);
    if (!s || s->is_specular()) return std::nullopt;
    return s->wi;
  };
  auto pdf = [&](Vec3f wi) -> double { return m.pdf(wo, wi); };
  const Chi2Result r = chi2_sphere(sample, pdf, c.samples, c.theta_bins, c.phi_bins, kSignificance,
                                   int(all_cases().size()), 0x5eed0000u + GetParam());
  EXPECT_TRUE(r.passed) << c.name << "\n" << r.message;
}

INSTANTIATE_TEST_SUITE_P(AllBrdfs, BrdfChi2, ::testing::Range(size_t(0), all_cases().size()),
                         [](const ::testing::TestParamInfo<size_t>& p) {
                           std::string n = all_cases()[p.param].name;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace kiln::test
