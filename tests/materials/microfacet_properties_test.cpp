// Analytic properties of the pbrt-v4 microfacet BSDFs: values against the formulas evaluated independently in
// double precision, reciprocity (the adjoint form for transmission), energy (albedo <= 1, and exactly 1 for the
// smooth limit of the dielectric), the smooth limit of the conductor, consistency of sample() with eval()/pdf(),
// and the Material plumbing (no mirroring for BSDFs that handle both sides; RGB conductor Fresnel).
#include <gtest/gtest.h>

#include <complex>
#include <vector>

#include "brdf_test_util.h"
#include "core/sampling.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kSigmas = 4.0;

// ---- Independent double-precision references (textbook forms, not the code under test) ----

struct Vec3d {
  double x, y, z;
};
Vec3d to_d(Vec3f v) { return {v.x, v.y, v.z}; }
double dotd(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d normalized(Vec3d v) {
  const double l = std::sqrt(dotd(v, v));
  return {v.x / l, v.y / l, v.z / l};
}

double d_ref(double ax, double ay, Vec3d m) {
  const double cos2 = m.z * m.z, tan2 = (m.x * m.x + m.y * m.y) / cos2, phi = std::atan2(m.y, m.x);
  const double e = tan2 * (std::pow(std::cos(phi) / ax, 2) + std::pow(std::sin(phi) / ay, 2));
  return 1.0 / (kPiD * ax * ay * cos2 * cos2 * (1 + e) * (1 + e));
}
double lambda_ref(double ax, double ay, Vec3d w) {
  const double tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z), phi = std::atan2(w.y, w.x);
  const double a2 = std::pow(std::cos(phi) * ax, 2) + std::pow(std::sin(phi) * ay, 2);
  return (std::sqrt(1 + a2 * tan2) - 1) / 2;
}
double g_ref(double ax, double ay, Vec3d wo, Vec3d wi) {
  return 1 / (1 + lambda_ref(ax, ay, wo) + lambda_ref(ax, ay, wi));
}
const RgbComplexIor kGold{Rgb(0.143f, 0.374f, 1.442f), Rgb(3.983f, 2.385f, 1.603f)};

TEST(RoughConductor, MatchesMicrofacetFormula) {
  const float ax = 0.3f, ay = 0.12f;
  const RoughConductor c{TrowbridgeReitz(ax, ay), kGold};
  Rng rng(1, 2);
  for (int i = 0; i < 200; ++i) {
    const Vec3f wo = sample_uniform_hemisphere(rng.next_2d()), wi = sample_uniform_hemisphere(rng.next_2d());
    if (wo.z < 1e-2f || wi.z < 1e-2f) continue;
    const Vec3d o = to_d(wo), in = to_d(wi), m = normalized({o.x + in.x, o.y + in.y, o.z + in.z});
    const double common = d_ref(ax, ay, m) * g_ref(ax, ay, o, in) / (4 * o.z * in.z);
    const Rgb f = c.eval(wo, wi);
    for (int ch = 0; ch < 3; ++ch) {
      const double expected = common * fresnel_conductor_ref(dotd(o, m), {kGold.eta[ch], kGold.k[ch]});
      ASSERT_NEAR(f[ch], expected, 2e-4 * expected + 1e-7) << i << " channel " << ch;
    }
  }
}

TEST(RoughDielectric, MatchesWalterFormulas) {
  const float eta = 1.5f, ax = 0.25f, ay = 0.4f;
  const RoughDielectric d{eta, TrowbridgeReitz(ax, ay)};
  Rng rng(3, 4);
  int reflections = 0, transmissions = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3f wo = sample_uniform_sphere(rng.next_2d()), wi = sample_uniform_sphere(rng.next_2d());
    if (std::abs(wo.z) < 1e-2f || std::abs(wi.z) < 1e-2f) continue;
    const Vec3d o = to_d(wo), in = to_d(wi);
    const bool outside = o.z > 0;
    const double n_o = outside ? 1.0 : eta, n_i = (in.z > 0) ? 1.0 : eta;
    double expected = 0;
    if (o.z * in.z > 0) {
      Vec3d m = normalized({o.x + in.x, o.y + in.y, o.z + in.z});
      if (m.z < 0) m = {-m.x, -m.y, -m.z};
      const double cos_om = dotd(o, m);
      const double F = fresnel_dielectric_ref(std::abs(cos_om), n_o, outside ? eta : 1.0);
      expected = d_ref(ax, ay, m) * g_ref(ax, ay, o, in) * F / std::abs(4 * o.z * in.z);
      ++reflections;
    } else {
      // Walter et al.: h = -(n_o wo + n_i wi), radiance scaled by (n_o / n_i)^2.
      Vec3d m = normalized({n_o * o.x + n_i * in.x, n_o * o.y + n_i * in.y, n_o * o.z + n_i * in.z});
      if (m.z < 0) m = {-m.x, -m.y, -m.z};
      const double om = dotd(o, m), im = dotd(in, m);
      if (om * o.z <= 0 || im * in.z <= 0) {
        EXPECT_EQ(d.f(wo, wi), 0.0f);
        continue;
      }
      const double F = fresnel_dielectric_ref(std::abs(om), n_o, n_i);
      const double denom = std::pow(n_o * om + n_i * im, 2);
      expected = std::abs(om * im / (o.z * in.z)) * n_i * n_i * (1 - F) * d_ref(ax, ay, m) *
                 g_ref(ax, ay, o, in) / denom * (n_o * n_o) / (n_i * n_i);
      ++transmissions;
    }
    ASSERT_NEAR(d.f(wo, wi), expected, 5e-4 * expected + 1e-7) << "wo.z " << wo.z << " wi.z " << wi.z;
  }
  EXPECT_GT(reflections, 50);
  EXPECT_GT(transmissions, 50);
}

// ---- Reciprocity ----

TEST(RoughConductor, IsReciprocal) {
  const Material m = surface_material(RoughConductor{TrowbridgeReitz(0.35f, 0.1f), kGold});
  Rng rng(5, 6);
  for (int i = 0; i < 2000; ++i) {
    const Vec3f a = sample_uniform_hemisphere(rng.next_2d()), b = sample_uniform_hemisphere(rng.next_2d());
    const Rgb fab = m.eval(a, b), fba = m.eval(b, a);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(fab[c], fba[c], 1e-4f * std::max(1.0f, fab[c]));
  }
}

TEST(RoughDielectric, RadianceAndImportanceAreAdjoint) {
  // f_radiance(wo, wi) = f_importance(wi, wo), i.e. f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2 in radiance mode
  // (Veach's generalised reciprocity, eta of the side each direction lies on).
  for (float eta : {1.5f, 1.0f / 1.33f}) {
    const RoughDielectric d{eta, TrowbridgeReitz(0.3f, 0.15f)};
    Rng rng(7, 8);
    int nonzero = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3f a = sample_uniform_sphere(rng.next_2d()), b = sample_uniform_sphere(rng.next_2d());
      const float rad = d.f(a, b, Transport::Radiance), imp = d.f(b, a, Transport::Importance);
      ASSERT_NEAR(rad, imp, 2e-4f * std::max(1.0f, rad)) << eta << " " << a.z << " " << b.z;
      const float eta_a = a.z > 0 ? 1.0f : eta, eta_b = b.z > 0 ? 1.0f : eta;
      ASSERT_NEAR(rad / (eta_a * eta_a), d.f(b, a) / (eta_b * eta_b), 2e-4f * std::max(1.0f, rad));
      if (rad > 0 && a.z * b.z < 0) ++nonzero;
    }
    EXPECT_GT(nonzero, 200) << eta;
  }
}

// ---- Energy ----

// Directional albedo through the BSDF's own sampler in the given transport mode (importance mode measures
// energy: no 1/eta^2 radiance compression).
AlbedoEstimate dielectric_albedo(const RoughDielectric& d, Vec3f wo, Transport mode, int n, uint64_t seed) {
  Rng rng(seed, 99);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const float uc = rng.next_float();
    double v = 0;
    if (const auto s = d.sample(wo, uc, rng.next_2d(), mode)) v = double(s->f.r) * std::abs(s->wi.z) / s->pdf;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(RoughDielectric, SmoothLimitConservesEnergyExactly) {
  // Effectively smooth: R + T = 1 (every sample weighs exactly 1 in importance mode), from either side.
  for (float eta : {1.5f, 1.0f / 1.5f})
    for (float c : {1.0f, 0.5f, 0.1f, -0.3f, -0.9f}) {
      const RoughDielectric d{eta, TrowbridgeReitz(5e-4f, 5e-4f)};
      ASSERT_TRUE(d.is_specular());
      const AlbedoEstimate a = dielectric_albedo(d, direction_at(c), Transport::Importance, 2000, 3);
      EXPECT_NEAR(a.mean, 1.0, 1e-6) << eta << " cos " << c;
      // Radiance mode: the transmitted part is compressed by 1/etap^2.
      const AlbedoEstimate r = dielectric_albedo(d, direction_at(c), Transport::Radiance, 200000, 4);
      const float R = fresnel_dielectric(c, eta);
      const std::optional<Refraction> t = refract(direction_at(c), eta);
      const double expected = R + (t ? (1 - R) / sqr(t->etap) : 0.0);
      EXPECT_NEAR(r.mean, expected, kSigmas * r.stderr_ + 1e-6) << eta << " cos " << c;
    }
}

TEST(RoughDielectric, RoughAlbedoAtMostOne) {
  uint64_t seed = 40;
  for (float eta : {1.5f, 1.0f / 1.5f, 2.4f})
    for (float alpha : {0.05f, 0.3f, 1.0f})
      for (float c : {1.0f, 0.6f, 0.2f, 0.02f, -0.2f, -0.7f}) {
        const RoughDielectric d{eta, TrowbridgeReitz(alpha, alpha)};
        const AlbedoEstimate a = dielectric_albedo(d, direction_at(c), Transport::Importance, 40000, ++seed);
        EXPECT_LE(a.mean, 1.0 + kSigmas * a.stderr_) << eta << " alpha " << alpha << " cos " << c;
      }
}

TEST(RoughConductor, AlbedoAtMostOneAndMatchesQuadrature) {
  // A perfect reflector (k = 1e4: F = 1) is the worst case; the sampled albedo must equal the integral of
  // f cos computed by quadrature (two independent routes to the same number). The quadrature runs over half
  // vectors (dwi = 4 |wo . wm| dwm), where the lobe sits at the pole whatever the incidence, so a theta-phi grid
  // resolves it even when the reflected lobe is a thin sliver at the horizon.
  uint64_t seed = 70;
  for (float alpha : {0.05f, 0.3f, 1.0f})
    for (float c : {1.0f, 0.7f, 0.3f, 0.05f}) {
      const Material m = surface_material(RoughConductor{TrowbridgeReitz(alpha, alpha), {Rgb(1.0f), Rgb(1e4f)}});
      const Vec3f wo = direction_at(c, 0.2);
      const AlbedoEstimate a = estimate_albedo(m, wo, 100000, ++seed);
      const double quad = integrate_upper_hemisphere(
          [&](Vec3f wm) {
            const float cos_om = dot(wo, wm);
            if (!(cos_om > 0.0f)) return 0.0;
            const Vec3f wi = reflect(wo, wm);
            return wi.z > 0.0f ? double(m.eval(wo, wi).r) * wi.z * 4.0 * cos_om : 0.0;
          },
          2000, 256);
      EXPECT_LE(a.mean, 1.0 + kSigmas * a.stderr_) << alpha << " cos " << c;
      EXPECT_NEAR(a.mean, quad, kSigmas * a.stderr_ + 1e-3 * quad) << alpha << " cos " << c;
    }
}

TEST(RoughConductor, NearlySmoothApproachesFresnel) {
  // alpha just above the smooth threshold: the lobe is a mirror with reflectance F(theta_o) up to shadowing.
  for (float c : {1.0f, 0.7f, 0.4f}) {
    const Material m = surface_material(RoughConductor{TrowbridgeReitz(2e-3f, 2e-3f), kGold});
    const AlbedoEstimate a = estimate_albedo(m, direction_at(c), 4000, 11);
    const Rgb F = fresnel_conductor(c, kGold);
    EXPECT_NEAR(a.mean, F.average(), 2e-3) << "cos " << c;
  }
}

// ---- sample() agrees with eval() and pdf() ----

TEST(MicrofacetSample, ValuesAgreeWithEvalAndPdf) {
  struct Case {
    std::string name;
    Material m;
  };
  const std::vector<Case> cases = {
      {"Conductor", surface_material(RoughConductor{TrowbridgeReitz(0.3f, 0.1f), kGold})},
      {"Dielectric", surface_material(RoughDielectric{1.5f, TrowbridgeReitz(0.2f, 0.35f)})},
      {"DielectricInv", surface_material(RoughDielectric{0.7f, TrowbridgeReitz(0.4f, 0.4f)})},
  };
  for (const Case& c : cases) {
    Rng rng(9, 10);
    int transmitted = 0;
    for (float ct : {0.9f, 0.3f, 0.01f, -0.6f, -0.05f}) {
      const Vec3f wo = direction_at(ct, 1.0);
      for (int i = 0; i < 5000; ++i) {
        const float uc = rng.next_float();
        const auto s = c.m.sample(wo, uc, rng.next_2d());
        if (!s) continue;
        ASSERT_FALSE(s->is_specular()) << c.name;
        const Rgb f = c.m.eval(wo, s->wi);
        ASSERT_EQ(s->pdf, c.m.pdf(wo, s->wi)) << c.name;
        ASSERT_EQ(s->f, f) << c.name;
        if (s->is_transmission()) {
          ++transmitted;
          ASSERT_LT(s->wi.z * wo.z, 0.0f) << c.name;
          const auto* d = std::get_if<RoughDielectric>(&c.m.surface);
          ASSERT_TRUE(d);
          ASSERT_EQ(s->eta, wo.z > 0 ? d->eta : 1.0f / d->eta) << c.name;
        } else {
          ASSERT_GT(s->wi.z * wo.z, 0.0f) << c.name;
        }
      }
    }
    if (std::holds_alternative<RoughDielectric>(c.m.surface)) {
      EXPECT_GT(transmitted, 1000) << c.name;
    }
  }
}

// ---- Material plumbing ----

TEST(MaterialSides, BothSidedBsdfsAreNotMirrored) {
  const RoughDielectric d{1.5f, TrowbridgeReitz(0.3f, 0.3f)};
  const Material m = surface_material(d);
  EXPECT_TRUE(m.oriented());
  EXPECT_TRUE(m.has_surface_transmission());
  // From inside, glass reflects totally beyond the critical angle: mirroring into +z would lose that.
  const Vec3f wo = direction_at(-0.3, 0.0), wi = direction_at(-0.3, kPiD);
  EXPECT_EQ(m.eval(wo, wi), d.eval(wo, wi));
  EXPECT_EQ(m.pdf(wo, wi), d.pdf(wo, wi));
  const Vec3f mo(wo.x, wo.y, -wo.z), mi(wi.x, wi.y, -wi.z);
  EXPECT_GT(std::abs(d.f(wo, wi) - d.f(mo, mi)), 0.1f * d.f(mo, mi));
  // One-sided BSDFs are still mirrored, and a conductor is not oriented.
  const Material c = surface_material(RoughConductor{TrowbridgeReitz(0.3f, 0.3f), kGold});
  EXPECT_FALSE(c.oriented());
  EXPECT_FALSE(c.has_surface_transmission());
  EXPECT_EQ(c.eval(wo, wi), c.eval(mo, mi));
  Material glass;
  glass.delta = Dielectric{1.5f};
  EXPECT_TRUE(glass.oriented());
  EXPECT_FALSE(glass.has_surface_transmission());
}

TEST(Conductor, RgbIorGivesPerChannelFresnel) {
  Material m;
  m.delta = Conductor{Rgb(1.0f), 1.0f, 0.0f, kGold};
  for (float c : {1.0f, 0.5f, 0.1f}) {
    const auto s = m.sample(direction_at(c), 0.5f, Vec2f(0.5f, 0.5f));
    ASSERT_TRUE(s);
    const Rgb w = s->f * (std::abs(s->wi.z) / s->pdf);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(w[ch], fresnel_conductor_ref(c, {kGold.eta[ch], kGold.k[ch]}), 1e-5) << c << " " << ch;
  }
}

}  // namespace
}  // namespace kiln::test
