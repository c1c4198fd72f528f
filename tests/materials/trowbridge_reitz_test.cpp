// The Trowbridge-Reitz (GGX) distribution on its own: D against the textbook tan-form in double precision,
// projected-area normalisation, the weak white furnace (visible normals integrate to 1 from every direction) and
// chi-square of the visible-normal sampler, isotropic and anisotropic, down to grazing and from below.
#include <gtest/gtest.h>

#include "brdf_test_util.h"
#include "core/sampling.h"
#include "materials/trowbridge_reitz.h"
#include "support/chi2.h"

namespace kiln::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// pbrt-v4's D(wm) written with tan(theta) and phi, in double: an independent form of TrowbridgeReitz::d.
double d_reference(double ax, double ay, Vec3f m) {
  const double x = m.x, y = m.y, z = m.z;
  const double sin2 = x * x + y * y, cos2 = z * z;
  const double tan2 = sin2 / cos2;
  const double phi = std::atan2(y, x);
  const double e = tan2 * (std::pow(std::cos(phi) / ax, 2) + std::pow(std::sin(phi) / ay, 2));
  return 1.0 / (kPiD * ax * ay * cos2 * cos2 * (1 + e) * (1 + e));
}

double lambda_reference(double ax, double ay, Vec3f w) {
  const double x = w.x, y = w.y, z = w.z;
  const double tan2 = (x * x + y * y) / (z * z);
  const double phi = std::atan2(y, x);
  const double alpha2 = std::pow(std::cos(phi) * ax, 2) + std::pow(std::sin(phi) * ay, 2);
  return (std::sqrt(1 + alpha2 * tan2) - 1) / 2;
}

struct Alphas {
  float ax, ay;
};
constexpr Alphas kAlphas[] = {{0.5f, 0.5f}, {0.15f, 0.15f}, {0.3f, 0.08f}, {1.0f, 1.0f}};

TEST(TrowbridgeReitz, DMatchesTheTangentForm) {
  Rng rng(5, 6);
  for (const Alphas a : kAlphas) {
    const TrowbridgeReitz tr(a.ax, a.ay);
    for (int i = 0; i < 200; ++i) {
      const Vec3f m = sample_uniform_hemisphere(rng.next_2d());
      if (m.z < 1e-3f) continue;
      const double ref = d_reference(a.ax, a.ay, m);
      ASSERT_NEAR(tr.d(m), ref, 1e-4 * ref) << a.ax << " " << a.ay;
      const Vec3f w = sample_uniform_sphere(rng.next_2d());
      const double lr = lambda_reference(a.ax, a.ay, w);
      ASSERT_NEAR(tr.lambda(w), lr, 1e-4 * lr + 1e-7) << a.ax << " " << a.ay;
    }
  }
}

TEST(TrowbridgeReitz, ProjectedAreaIsOne) {
  for (const Alphas a : kAlphas) {
    const TrowbridgeReitz tr(a.ax, a.ay);
    const double total = integrate_upper_hemisphere([&](Vec3f m) { return double(tr.d(m)) * m.z; });
    EXPECT_NEAR(total, 1.0, 1e-3) << a.ax << " " << a.ay;
  }
}

TEST(TrowbridgeReitz, VisibleNormalsIntegrateToOne) {
  // The weak white furnace: G1 is exactly the normalisation of the visible normals, from above and below.
  for (const Alphas a : kAlphas) {
    const TrowbridgeReitz tr(a.ax, a.ay);
    for (float c : {1.0f, 0.7f, 0.2f, 0.02f, -0.5f}) {
      const Vec3f w = direction_at(c, 0.9);
      const double total = integrate_upper_hemisphere([&](Vec3f m) { return double(tr.visible_d(w, m)); });
      EXPECT_NEAR(total, 1.0, 2e-3) << a.ax << " " << a.ay << " cos " << c;
    }
  }
}

TEST(TrowbridgeReitz, SmoothThresholdAndRemap) {
  EXPECT_TRUE(TrowbridgeReitz(0.0f, 0.0f).effectively_smooth());
  EXPECT_TRUE(TrowbridgeReitz(9e-4f, 5e-4f).effectively_smooth());
  EXPECT_FALSE(TrowbridgeReitz(9e-4f, 2e-3f).effectively_smooth());
  // A rough axis raises a zero alpha on the other to the floor that keeps D finite.
  const TrowbridgeReitz aniso(0.0f, 0.2f);
  EXPECT_EQ(aniso.alpha_x, TrowbridgeReitz::kMinAlpha);
  EXPECT_TRUE(std::isfinite(aniso.d(Vec3f(0, 0, 1))));
  EXPECT_FLOAT_EQ(TrowbridgeReitz::roughness_to_alpha(0.25f), 0.5f);
  EXPECT_FLOAT_EQ(TrowbridgeReitz::roughness_to_alpha(0.0f), 0.0f);
}

struct VisibleCase {
  Alphas a;
  float cos_w;
  int theta_bins, phi_bins;
};

std::vector<VisibleCase> make_visible_cases() {
  std::vector<VisibleCase> c;
  for (float cw : {1.0f, 0.6f, 0.15f, 1e-3f, -0.4f}) {
    c.push_back({{0.5f, 0.5f}, cw, 20, 40});
    c.push_back({{0.3f, 0.08f}, cw, 40, 80});
  }
  return c;
}

const std::vector<VisibleCase>& visible_cases() {
  static const std::vector<VisibleCase> cases = make_visible_cases();
  return cases;
}

class VisibleNormalsChi2 : public ::testing::TestWithParam<size_t> {};

TEST_P(VisibleNormalsChi2, SamplesFollowVisibleD) {
  const VisibleCase& c = visible_cases()[GetParam()];
  const TrowbridgeReitz tr(c.a.ax, c.a.ay);
  const Vec3f w = direction_at(c.cos_w, 0.8);
  const Chi2Result r = chi2_sphere([&](Rng& rng) { return tr.sample_visible(w, rng.next_2d()); },
                                   [&](Vec3f m) -> double { return m.z > 0 ? tr.visible_d(w, m) : 0.0; }, 500'000,
                                   c.theta_bins, c.phi_bins, 0.01, int(visible_cases().size()), 0x7a00 + GetParam());
  EXPECT_TRUE(r.passed) << c.a.ax << " " << c.a.ay << " cos " << c.cos_w << "\n" << r.message;
}

INSTANTIATE_TEST_SUITE_P(TrowbridgeReitz, VisibleNormalsChi2, ::testing::Range(size_t(0), visible_cases().size()));

}  // namespace
}  // namespace kiln::test
