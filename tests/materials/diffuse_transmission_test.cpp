// DiffuseTransmission (pbrt-v4 "diffusetransmission"): Lambertian reflection R / pi on the side of wo, Lambertian
// transmission T / pi on the other side.
//  * chi-square of sample() against pdf() over the whole sphere, at incidences down to grazing and from either
//    side (Material mirrors wo.z < 0), for several (R, T) including one lobe alone;
//  * white furnace: the directional albedo is R + T at every angle, by quadrature of eval() over the sphere and by
//    the sampler's path weights (so energy is conserved exactly when R + T = 1, and lost otherwise);
//  * reciprocity f(wo, wi) = f(wi, wo) for pairs on the same and on opposite sides.
#include <gtest/gtest.h>

#include "brdf_test_util.h"
#include "core/sampling.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

struct Case {
  const char* name;
  Rgb reflectance, transmittance;
};
constexpr Case kCases[] = {
    {"balanced", Rgb(0.3f, 0.5f, 0.3f), Rgb(0.5f, 0.3f, 0.2f)},  // the feature scene's killeroo
    {"mostly_transmitting", Rgb(0.05f), Rgb(0.9f)},
    {"reflection_only", Rgb(0.7f), Rgb(0.0f)},
    {"transmission_only", Rgb(0.0f), Rgb(0.6f, 0.2f, 0.9f)},
};
constexpr float kIncidences[] = {0.95f, 0.5f, 0.1f, 0.01f, -0.4f};

Material material(const Case& c) { return surface_material(DiffuseTransmission{c.reflectance, c.transmittance}); }

TEST(DiffuseTransmission, SamplingMatchesPdf) {
  const int num_tests = int(std::size(kCases) * std::size(kIncidences));
  uint64_t seed = 70;
  for (const Case& c : kCases) {
    const Material m = material(c);
    for (float cos_o : kIncidences) {
      const Vec3f wo = direction_at(cos_o, 1.1);
      auto sample = [&](Rng& rng) -> std::optional<Vec3f> {
        const float uc = rng.next_float();
        const auto s = m.sample(wo, uc, rng.next_2d());
        return s ? std::optional<Vec3f>(s->wi) : std::nullopt;
      };
      auto pdf = [&](Vec3f wi) -> double { return m.pdf(wo, wi); };
      const Chi2Result r = chi2_sphere(sample, pdf, 400000, 20, 40, 0.01, num_tests, ++seed);
      EXPECT_TRUE(r.passed) << c.name << " cos " << cos_o << "\n" << r.message;
    }
  }
}

TEST(DiffuseTransmission, AlbedoIsReflectancePlusTransmittance) {
  for (const Case& c : kCases) {
    const Material m = material(c);
    const double expected = (c.reflectance + c.transmittance).average();
    for (float cos_o : kIncidences) {
      const Vec3f wo = direction_at(cos_o, 0.2);
      // Quadrature of f |cos| over both hemispheres.
      const auto integrand = [&](Vec3f wi) { return double(m.eval(wo, wi).average()) * std::abs(wi.z); };
      const double quadrature = integrate_upper_hemisphere(integrand, 400, 64) +
                                integrate_upper_hemisphere([&](Vec3f w) { return integrand({w.x, w.y, -w.z}); }, 400, 64);
      EXPECT_NEAR(quadrature, expected, 1e-4) << c.name << " cos " << cos_o;
      // Each sample's path weight is R / pr or T / (1 - pr) exactly; their mean is R + T.
      const AlbedoEstimate e = estimate_albedo(m, wo, 100000, 9);
      EXPECT_NEAR(e.mean, expected, 4.0 * e.stderr_ + 1e-6) << c.name << " cos " << cos_o;
    }
  }
}

TEST(DiffuseTransmission, IsReciprocal) {
  const Material m = material(kCases[0]);
  Rng rng(5, 6);
  for (int i = 0; i < 2000; ++i) {
    const Vec3f a = sample_uniform_sphere(rng.next_2d()), b = sample_uniform_sphere(rng.next_2d());
    ASSERT_EQ(m.eval(a, b), m.eval(b, a)) << i;
    // The other side's lobe: R / pi on the same side, T / pi across.
    const Rgb expected = (a.z * b.z > 0 ? kCases[0].reflectance : kCases[0].transmittance) * kInvPi;
    ASSERT_EQ(m.eval(a, b), expected) << i;
  }
}

TEST(DiffuseTransmission, TransmitsAcrossAThinSurface) {
  const Material m = material(kCases[0]);
  EXPECT_TRUE(m.has_surface_transmission());
  EXPECT_FALSE(m.oriented());  // two-sided: no inside, no medium change
  Rng rng(7, 8);
  for (int i = 0; i < 1000; ++i) {
    const float uc = rng.next_float();
    const auto s = m.sample(direction_at(0.6), uc, rng.next_2d());
    ASSERT_TRUE(s);
    ASSERT_EQ(s->is_transmission(), s->wi.z < 0.0f);
    ASSERT_EQ(s->eta, 1.0f);
  }
}

}  // namespace
}  // namespace kiln::test
