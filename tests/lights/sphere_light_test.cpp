// SphereLight: visible-cone sampling against the analytic irradiance pi L (r/d)^2, the area-sampling fallback,
// tiny cones, and the ellipsoid's exact world solid-angle density (chi-square against pdf_li).
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/frame.h"
#include "light_test_util.h"
#include "lights/sphere_light.h"
#include "support/chi2.h"

namespace kiln {
namespace {

using test::estimate;
using test::irradiance_sample;
using test::within_error;

constexpr float kL = 2.5f;
const Rgb kRadiance{kL};
constexpr int kIrradianceSamples = 200000;

SphereLight plain_sphere(Vec3f c, float r) { return SphereLight(c, r, Transform(), kRadiance); }

// Irradiance at the origin, normal +z, from a sphere of radius r centred at distance d on +z.
struct SphereCase {
  float r, d;
};

TEST(SphereLight, ConeSamplingMatchesAnalyticIrradiance) {
  for (SphereCase c : {SphereCase{0.5f, 1.0f}, {0.1f, 1.0f}, {0.99f, 1.0f}, {1.0f, 3.0f}, {2.0f, 100.0f}}) {
    const SphereLight light = plain_sphere({0, 0, c.d}, c.r);
    const LightQuery q{{0, 0, 0}, {0, 0, 1}};
    const auto e = estimate([&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
                            kIrradianceSamples, 7);
    const double expected = test::kPiD * kL * double(c.r) * c.r / (double(c.d) * c.d);
    EXPECT_EQ(e.invalid, 0);
    EXPECT_TRUE(within_error(e, expected)) << "r=" << c.r << " d=" << c.d << ": " << e.mean << " +- " << e.std_error
                                           << " vs " << expected;
  }
}

TEST(SphereLight, AreaSamplingMatchesAnalyticIrradiance) {
  for (SphereCase c : {SphereCase{0.5f, 1.0f}, {0.3f, 1.0f}, {1.0f, 3.0f}}) {
    const SphereLight light = plain_sphere({0, 0, c.d}, c.r);
    const LightQuery q{{0, 0, 0}, {0, 0, 1}};
    const auto e = estimate([&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_area(qq, u); }, q, rng); },
                            kIrradianceSamples, 11);
    const double expected = test::kPiD * kL * double(c.r) * c.r / (double(c.d) * c.d);
    EXPECT_EQ(e.invalid, 0);
    EXPECT_TRUE(within_error(e, expected)) << "r=" << c.r << " d=" << c.d << ": " << e.mean << " +- " << e.std_error
                                           << " vs " << expected;
  }
}

// r/d = 1e-4, both as a tiny sphere nearby and a unit sphere far away (where re-intersecting in float would fail).
TEST(SphereLight, TinyConeStaysAccurateAndFinite) {
  for (SphereCase c : {SphereCase{1e-4f, 1.0f}, {1.0f, 1e4f}}) {
    const Vec3f center{0.3f * c.d, 0.0f, 0.9539392f * c.d};  // unit direction, off-axis
    const SphereLight light = plain_sphere(center, c.r);
    const LightQuery q{{0, 0, 0}, {0, 0, 1}};
    Rng rng(3, 5);
    double max_radius_err = 0, min_facing = 1;
    for (int i = 0; i < 20000; ++i) {
      const auto s = light.sample_li(q, rng.next_2d());
      ASSERT_TRUE(s.has_value());
      ASSERT_TRUE(is_finite(s->wi) && is_finite(s->p_light) && is_finite(s->n_light) && std::isfinite(s->pdf));
      max_radius_err = std::max(max_radius_err, std::abs(double(length(s->p_light - center)) - c.r) / c.r);
      min_facing = std::min(min_facing, double(dot(s->n_light, -s->wi)));
    }
    // The point is rounded to float once: its error is a few ulps of |center|, i.e. relative to r it is about
    // 1e-7 * d / r.
    EXPECT_LT(max_radius_err, 4e-7 * c.d / c.r + 1e-6) << "r=" << c.r << " d=" << c.d;
    EXPECT_GE(min_facing, -1e-3) << "sampled points must face the query point";
    const auto e = estimate([&](Rng& r) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, r); },
                            kIrradianceSamples, 13);
    const double expected = test::kPiD * kL * 1e-8 * 0.9539392;  // pi L (r/d)^2 cos(angle to the normal)
    EXPECT_EQ(e.invalid, 0);
    EXPECT_NEAR(e.mean, expected, 4 * e.std_error + 1e-4 * expected) << "r=" << c.r << " d=" << c.d;
  }
}

TEST(SphereLight, InsideOrOnTheSurfaceFallsBackAndSeesNoLight) {
  const SphereLight light = plain_sphere({1, 2, 3}, 2.0f);
  EXPECT_TRUE(light.contains({1, 2, 3}));
  EXPECT_TRUE(light.contains({1, 2, 5}));  // on the surface
  EXPECT_FALSE(light.contains({1, 2, 5.01f}));
  Rng rng(1, 1);
  for (Vec3f p : {Vec3f{1, 2, 3}, Vec3f{1.5f, 2, 3}, Vec3f{1, 2, 5}}) {
    const LightQuery q{p, {0, 0, 1}};
    for (int i = 0; i < 1000; ++i) EXPECT_FALSE(light.sample_li(q, rng.next_2d()).has_value());
  }
}

TEST(SphereLight, EmitsOutwardOnly) {
  const SphereLight light = plain_sphere({0, 0, 0}, 1.0f);
  EXPECT_EQ(light.emitted({0, 0, 1}, {0, 0.6f, 0.8f}), kRadiance);
  EXPECT_TRUE(light.emitted({0, 0, 1}, {0, 0.6f, -0.8f}).is_black());
}

// ---- Ellipsoids ---------------------------------------------------------------------------------------------

// Rotated, non-uniformly scaled, translated unit sphere.
Transform ellipsoid_transform() {
  return Transform::translate({2.0f, 0.5f, 0.3f}) * Transform::rotate(35.0f, {1, 2, 0.5f}) *
         Transform::scale({1.4f, 0.5f, 0.9f});
}

// First intersection of q + t w with the light's surface (object-space ray/sphere in double).
std::optional<Vec3f> intersect(const Transform& to_world, Vec3f center, float radius, Vec3f q, Vec3f w) {
  const Transform inv = to_world.inverse();
  const Vec3f o = inv.point(q) - center, d = inv.vector(w);
  const double a = double(dot(d, d)), b = double(dot(o, d)), c = double(dot(o, o)) - double(radius) * radius;
  const double disc = b * b - a * c;
  if (disc < 0) return std::nullopt;
  const double t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
  const double t = t0 > 0 ? t0 : t1;
  if (!(t > 0)) return std::nullopt;
  return q + w * float(t);
}

TEST(SphereLight, EllipsoidConeSamplingMatchesPdfChi2) {
  const Transform xf = ellipsoid_transform();
  const Vec3f center{0.2f, -0.1f, 0.1f};
  const SphereLight light(center, 1.0f, xf, kRadiance);
  const LightQuery q{{0, 0, 0}, {0, 0, 0}};
  ASSERT_FALSE(light.contains(q.p));
  const auto r = test::chi2_sphere(
      [&](Rng& rng) -> std::optional<Vec3f> {
        const auto s = light.sample_li(q, rng.next_2d());
        if (!s) return std::nullopt;
        return s->wi;
      },
      [&](Vec3f w) -> double {
        const auto p = intersect(xf, center, 1.0f, q.p, w);
        return p ? light.pdf_li(q, *p, {}, 0) : 0.0;
      },
      1000000, 30, 60, 0.01, 2, 21);
  EXPECT_TRUE(r.passed) << r.message;
}

// Quadrature-free check of the same density: for any region R inside the light's silhouette,
// E[1_R(wi) / pdf(wi)] = |R|. Caps of directions around points inside the ellipsoid have |R| = 2 pi (1 - cos a).
TEST(SphereLight, EllipsoidConeDensityRecoversCapSolidAngles) {
  const Transform xf = ellipsoid_transform();
  const Vec3f center{0.2f, -0.1f, 0.1f};
  const SphereLight light(center, 1.0f, xf, kRadiance);
  const LightQuery q{{0, 0, 0}, {0, 0, 0}};
  const float cap_half_angle = radians(4.0f);
  const float cos_cap = std::cos(cap_half_angle);
  for (Vec3f inner : {Vec3f{0, 0, 0}, Vec3f{0.5f, 0, 0}, Vec3f{0, -0.4f, 0}, Vec3f{0, 0, 0.5f}}) {
    const Vec3f axis = normalize(xf.point(center + inner) - q.p);
    // The cap must lie inside the silhouette (whose cross-section is convex): check its rim.
    const Frame f(axis);
    for (int k = 0; k < 64; ++k) {
      const float phi = 2 * kPi * float(k) / 64;
      const Vec3f w = f.to_world({std::sin(cap_half_angle) * std::cos(phi), std::sin(cap_half_angle) * std::sin(phi), cos_cap});
      ASSERT_TRUE(intersect(xf, center, 1.0f, q.p, w).has_value()) << "test setup: cap leaves the silhouette";
    }
    const auto e = estimate(
        [&](Rng& rng) -> double {
          const auto s = light.sample_li(q, rng.next_2d());
          return (s && dot(s->wi, axis) >= cos_cap) ? 1.0 / double(s->pdf) : 0.0;
        },
        400000, 41);
    const double expected = 2 * test::kPiD * (1 - double(cos_cap));
    EXPECT_TRUE(within_error(e, expected)) << "cap around object point (" << inner.x << ", " << inner.y << ", "
                                           << inner.z << "): " << e.mean << " +- " << e.std_error << " vs " << expected;
  }
}

// E[1 / pdf(wi)] over all samples is the solid angle of the silhouette. That cone is convex, so with polar angle
// theta_b(phi) of its rim around an inner axis, Omega = integral of (1 - cos theta_b) dphi (trapezoid rule on a
// smooth periodic integrand, rim found by bisection against an independent ray/ellipsoid intersection).
TEST(SphereLight, EllipsoidConeDensityIntegratesToTheSilhouetteSolidAngle) {
  const Transform xf = ellipsoid_transform();
  const Vec3f center{0.2f, -0.1f, 0.1f};
  const SphereLight light(center, 1.0f, xf, kRadiance);
  const LightQuery q{{0, 0, 0}, {0, 0, 0}};
  const Frame f(normalize(xf.point(center) - q.p));
  constexpr int kAzimuths = 256;
  double omega = 0;
  for (int k = 0; k < kAzimuths; ++k) {
    const double phi = 2 * test::kPiD * (k + 0.5) / kAzimuths;
    double lo = 0, hi = test::kPiD / 2;  // hit at lo, miss at hi
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      const Vec3f w = f.to_world({float(std::sin(mid) * std::cos(phi)), float(std::sin(mid) * std::sin(phi)),
                                  float(std::cos(mid))});
      (intersect(xf, center, 1.0f, q.p, w) ? lo : hi) = mid;
    }
    omega += (1 - std::cos(lo)) * 2 * test::kPiD / kAzimuths;
  }
  const auto e = estimate(
      [&](Rng& rng) -> double {
        const auto s = light.sample_li(q, rng.next_2d());
        return s ? 1.0 / double(s->pdf) : 0.0;
      },
      1600000, 43);
  EXPECT_TRUE(within_error(e, omega)) << e.mean << " +- " << e.std_error << " vs " << omega;
}

TEST(SphereLight, EllipsoidAreaSamplingMatchesPdfChi2) {
  const Transform xf = ellipsoid_transform();
  const Vec3f center{0.2f, -0.1f, 0.1f};
  const SphereLight light(center, 1.0f, xf, kRadiance);
  const LightQuery q{{-0.5f, 1.0f, -0.8f}, {0, 0, 0}};
  ASSERT_FALSE(light.contains(q.p));
  // Back-facing points give no sample: the chi-square test's failed-sample cell checks that probability too.
  const auto r = test::chi2_sphere(
      [&](Rng& rng) -> std::optional<Vec3f> {
        const auto s = light.sample_area(q, rng.next_2d());
        if (!s) return std::nullopt;
        return s->wi;
      },
      [&](Vec3f w) -> double {
        const auto p = intersect(xf, center, 1.0f, q.p, w);
        return p ? light.pdf_area(q, *p) : 0.0;
      },
      300000, 18, 36, 0.01, 2, 22);
  EXPECT_TRUE(r.passed) << r.message;
}

// Cone and area sampling use different density formulas (object cone pdf with the direction Jacobian vs area pdf
// with the surface Jacobian); both must give the same irradiance from an ellipsoid.
TEST(SphereLight, EllipsoidConeAndAreaEstimatesAgree) {
  const SphereLight light({0, 0, 0}, 1.0f, Transform::translate({0.3f, -0.2f, 2.5f}) *
                                                Transform::rotate(-20.0f, {0, 1, 1}) * Transform::scale({0.4f, 1.3f, 0.7f}),
                          kRadiance);
  const LightQuery q{{0, 0, 0}, normalize(Vec3f{0.1f, 0.2f, 1.0f})};
  const auto cone = estimate([&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
                             kIrradianceSamples, 31);
  const auto area = estimate([&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_area(qq, u); }, q, rng); },
                             kIrradianceSamples, 32);
  const double sigma = std::hypot(cone.std_error, area.std_error);
  EXPECT_NEAR(cone.mean, area.mean, 4 * sigma + 1e-5 * cone.mean);
  EXPECT_GT(cone.mean, 0.0);
  EXPECT_LT(cone.std_error, area.std_error) << "cone sampling should have the lower variance";
}

TEST(SphereLight, UniformlyScaledSphereKeepsTheConePdf) {
  // scale(2) of a radius-0.5 sphere at (0,0,1) is a radius-1 sphere at (0,0,2).
  const SphereLight scaled({0, 0, 1}, 0.5f, Transform::scale({2, 2, 2}), kRadiance);
  const SphereLight plain = plain_sphere({0, 0, 2}, 1.0f);
  const LightQuery q{{0.1f, 0, -0.2f}, {0, 0, 1}};
  Rng rng(9, 9);
  for (int i = 0; i < 100; ++i) {
    const auto a = scaled.sample_li(q, rng.next_2d());
    ASSERT_TRUE(a.has_value());
    EXPECT_NEAR(a->pdf, plain.pdf_li(q, a->p_light, a->n_light, 0), 1e-4f * a->pdf);
  }
  EXPECT_NEAR(scaled.surface_area(), 4 * kPi, 1e-4f);
}

TEST(SphereLight, PdfLiAgreesWithSampleLi) {
  const std::vector<SphereLight> lights{plain_sphere({0, 0, 3}, 1.0f), plain_sphere({0, 0, 1e3f}, 0.01f),
                                        SphereLight({0.2f, -0.1f, 0.1f}, 1.0f, ellipsoid_transform(), kRadiance)};
  Rng rng(4, 2);
  for (const SphereLight& light : lights) {
    for (int i = 0; i < 2000; ++i) {
      const LightQuery q{{rng.next_float() - 0.5f, rng.next_float() - 0.5f, -1.5f + rng.next_float()}, {}};
      const Vec2f u = rng.next_2d();
      if (const auto s = light.sample_li(q, u)) {
        EXPECT_NEAR(light.pdf_li(q, s->p_light, s->n_light, 0), s->pdf, 1e-3f * s->pdf);
      }
      if (const auto s = light.sample_area(q, u)) {
        EXPECT_NEAR(light.pdf_area(q, s->p_light), s->pdf, 1e-3f * s->pdf);
      }
    }
  }
}

TEST(SphereLight, PdfLiIsZeroForMissedDirections) {
  const SphereLight light = plain_sphere({0, 0, 5}, 1.0f);
  const LightQuery q{{0, 0, 0}, {0, 0, 1}};
  EXPECT_GT(light.pdf_li(q, {0, 0, 4}, {0, 0, -1}, 0), 0.0f);
  EXPECT_EQ(light.pdf_li(q, {0, 3, 5}, {0, 1, 0}, 0), 0.0f);   // beside the sphere
  EXPECT_EQ(light.pdf_li(q, {0, 0, -4}, {0, 0, 1}, 0), 0.0f);  // behind q
}

TEST(SphereLight, EllipsoidSurfaceAreaAndPower) {
  // Semi-axes 3, 2, 1 (rotation must not matter). Reference by numerically integrating the exact area.
  const auto area_of = [](const Transform& xf) { return SphereLight({0, 0, 0}, 1.0f, xf, kRadiance).surface_area(); };
  double exact = 0;  // integral over the unit sphere parametrisation of |dP/dtheta x dP/dphi|
  const int n = 2000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = (i + 0.5) * test::kPiD / n, ph = (j + 0.5) * test::kPiD / n;
      const double st = std::sin(th), ct = std::cos(th), sp = std::sin(ph), cp = std::cos(ph);
      // P = (3 st cp, 2 st sp, ct); |P_th x P_ph| = st * sqrt((2*1 st cp)^2 + (3*1 st sp)^2 + (3*2 ct)^2)
      exact += st * std::sqrt(4 * st * st * cp * cp + 9 * st * st * sp * sp + 36 * ct * ct) * (test::kPiD / n) *
               (test::kPiD / n);
    }
  const Transform s = Transform::scale({3, 2, 1});
  EXPECT_NEAR(area_of(s), exact, 0.012 * exact);  // Thomsen's formula is within about 1.1%
  EXPECT_NEAR(area_of(Transform::rotate(40, {1, 1, 0}) * s * Transform::rotate(-70, {0, 1, 2})), area_of(s),
              1e-4 * exact);
  const SphereLight sphere = plain_sphere({0, 0, 0}, 2.0f);
  EXPECT_NEAR(sphere.surface_area(), 16 * kPi, 1e-4f);
  EXPECT_NEAR(sphere.power(), kPi * 16 * kPi * kRadiance.luminance(), 1e-3f);
}

TEST(SphereLight, RejectsBadInput) {
  const auto make = [](float r) { return SphereLight(Vec3f{0, 0, 0}, r, Transform(), kRadiance); };
  EXPECT_THROW(make(0.0f), Error);
  EXPECT_THROW(make(-1.0f), Error);
}

}  // namespace
}  // namespace kiln
