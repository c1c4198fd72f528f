// QuadricLight (emitting pbrt disks, cylinders and partial spheres): the irradiance its samples estimate at a point
// matches the closed forms (a disk, an annulus sector and a half disk on their axis; the inside of a half cylinder
// and of a quarter sphere from the centre of their axis), under a non-uniform scale matches a quadrature of the
// emitter; samples agree with pdf_li; one-sided emitters send nothing behind them; the world area is exact.
#include <gtest/gtest.h>

#include "core/error.h"
#include "light_test_util.h"
#include "lights/quadric_light.h"

namespace kiln {
namespace {

using test::estimate;
using test::irradiance_sample;
using test::kPiD;
using test::within_error;

constexpr float kL = 2.0f;
constexpr int kSamples = 400000;

Quadric disk(float r, float inner = 0.0f, float phi_max_deg = 360.0f) {
  return *make_quadric(QuadricType::Disk, r, inner, 0.0f, 0.0f, 0.0f, phi_max_deg).quadric;
}

// The irradiance one-sample estimator of a light at q.
test::Estimate irradiance(const QuadricLight& light, const LightQuery& q, uint64_t seed = 3) {
  return estimate(
      [&](Rng& rng) { return irradiance_sample([&](auto& qq, Vec2f u) { return light.sample_li(qq, u); }, q, rng); },
      kSamples, seed);
}

// Irradiance on the axis of a Lambertian disk of radius r at distance h, facing it: pi L r^2 / (h^2 + r^2).
double disk_irradiance(double r, double h) { return kPiD * kL * r * r / (h * h + r * r); }

TEST(QuadricLight, DiskAnnulusAndSectorMatchTheirClosedFormsOnTheAxis) {
  constexpr float kH = 1.3f;
  // The disk at z = 0 faces +z; the query looks down at it from z = kH.
  const LightQuery q{{0.0f, 0.0f, kH}, {0.0f, 0.0f, -1.0f}};
  struct Case {
    const char* name;
    Quadric shape;
    double expected;
  } cases[] = {
      {"disk", disk(1.5f), disk_irradiance(1.5, kH)},
      {"annulus", disk(1.5f, 0.6f), disk_irradiance(1.5, kH) - disk_irradiance(0.6, kH)},
      {"half annulus", disk(1.5f, 0.6f, 180.0f), 0.5 * (disk_irradiance(1.5, kH) - disk_irradiance(0.6, kH))},
  };
  for (const Case& c : cases) {
    const QuadricLight light(c.shape, Transform(), false, Rgb(kL), false);
    const auto e = irradiance(light, q);
    EXPECT_EQ(e.invalid, 0) << c.name;
    EXPECT_TRUE(within_error(e, c.expected))
        << c.name << ": " << e.mean << " +- " << e.std_error << " vs " << c.expected;
  }
}

TEST(QuadricLight, InsideAHalfCylinderAndAQuarterSphereFromTheAxis) {
  // Half a cylinder (phi in [0, pi]) of radius R from z = 0 to H, emitting inwards (flip): from the origin, looking
  // up the axis, the wall fills the directions with tan(theta) > R / H over half the azimuths:
  // E = 1/2 pi L cos^2(theta_0) = 1/2 pi L H^2 / (H^2 + R^2).
  constexpr float kR = 0.8f, kH = 2.0f;
  const LightQuery q{{0, 0, 0}, {0, 0, 1}};
  const Quadric cylinder = *make_quadric(QuadricType::Cylinder, kR, 0.0f, 0.0f, 0.0f, kH, 180.0f).quadric;
  const auto ec = irradiance(QuadricLight(cylinder, Transform(), true, Rgb(kL), false), q);
  const double want_c = 0.5 * kPiD * kL * kH * kH / (kH * kH + kR * kR);
  EXPECT_TRUE(within_error(ec, want_c)) << ec.mean << " +- " << ec.std_error << " vs " << want_c;
  // A quarter sphere (z >= 0, phi in [0, pi]) around the origin covers half the upper hemisphere: E = 1/2 pi L.
  const Quadric dome = *make_quadric(QuadricType::Sphere, 1.7f, 0.0f, 0.0f, 0.0f, 1.7f, 180.0f).quadric;
  const auto es = irradiance(QuadricLight(dome, Transform(), true, Rgb(kL), false), q);
  EXPECT_TRUE(within_error(es, 0.5 * kPiD * kL)) << es.mean << " +- " << es.std_error;
  // Emitting outwards only, neither sends the centre any light.
  EXPECT_EQ(irradiance(QuadricLight(dome, Transform(), false, Rgb(kL), false), q).mean, 0.0);
}

TEST(QuadricLight, AnEllipticalDiskMatchesAQuadratureOfItsSurface) {
  // A disk stretched 2.5x along x and tilted: the area element grows by J = |det M| |M^-T n| = 2.5 (constant on a
  // plane), which the world area and the density must both carry.
  const Transform xf = Transform::translate({0.3f, -0.2f, 0.0f}) * Transform::rotate(20.0f, {1, 0, 0}) *
                       Transform::scale({2.5f, 1.0f, 1.0f});
  const Quadric shape = disk(1.0f);
  const QuadricLight light(shape, xf, false, Rgb(kL), false);
  EXPECT_NEAR(light.area(), kPiD * 2.5, 1e-4 * kPiD * 2.5);
  const LightQuery q{{0.5f, 0.4f, 1.5f}, normalize(Vec3f{0.1f, -0.2f, -1.0f})};
  // E = L * integral over the ellipse of cos_i cos_l / d^2 dA, by a fine midpoint rule in polar coordinates.
  double want = 0.0;
  constexpr int kN = 1000;
  const Vec3f n_world = normalize(xf.normal({0, 0, 1}));
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const double r = (i + 0.5) / kN, phi = 2.0 * kPiD * (j + 0.5) / kN;
      const Vec3f p = xf.point({float(r * std::cos(phi)), float(r * std::sin(phi)), 0.0f});
      const Vec3f d = p - q.p;
      const double d2 = dot(d, d), len = std::sqrt(d2);
      const double cos_i = std::max(0.0, double(dot(q.n, d)) / len);
      const double cos_l = std::max(0.0, -double(dot(n_world, d)) / len);
      want += kL * cos_i * cos_l / d2 * (2.5 * r * (1.0 / kN) * (2.0 * kPiD / kN));
    }
  const auto e = irradiance(light, q);
  EXPECT_TRUE(within_error(e, want)) << e.mean << " +- " << e.std_error << " vs " << want;
}

TEST(QuadricLight, SamplesAgreeWithPdfLiAndFaceTheirEmittingSide) {
  const Transform xf = Transform::translate({0, 0, 2}) * Transform::rotate(30.0f, {0, 1, 0}) *
                       Transform::scale({1.0f, 1.5f, 0.7f});
  const Quadric shapes[] = {disk(1.0f, 0.3f, 270.0f),
                            *make_quadric(QuadricType::Cylinder, 0.6f, 0, 0, -0.5f, 0.8f, 300.0f).quadric,
                            *make_quadric(QuadricType::Sphere, 0.9f, 0, 0, -0.4f, 0.7f, 200.0f).quadric};
  for (const Quadric& shape : shapes)
    for (bool two_sided : {false, true}) {
      const QuadricLight light(shape, xf, false, Rgb(kL), two_sided);
      const LightQuery q{{0.2f, -0.3f, 4.0f}, {0, 0, -1}};  // above: on the disk's emitting side
      Rng rng(5, 6);
      int samples = 0;
      for (int i = 0; i < 5000; ++i) {
        const auto s = light.sample_li(q, rng.next_2d());
        if (!s) continue;
        ++samples;
        EXPECT_NEAR(light.pdf_li(q, s->p_light, s->n_light, 0), s->pdf, 2e-3f * s->pdf);
        EXPECT_NEAR(length(s->p_light - q.p), s->distance, 1e-4f);
        // One-sided: the sample's point faces q.
        if (!two_sided) {
          EXPECT_LT(dot(s->n_light, s->wi), 0.0f);
        }
        EXPECT_EQ(light.emitted(s->n_light, -s->wi), Rgb(kL));
      }
      EXPECT_GT(samples, 500);
    }
}

TEST(QuadricLight, RejectsASingularTransformAndQuadricsRejectBadParameters) {
  EXPECT_THROW(QuadricLight(disk(1.0f), Transform::scale({1, 0, 1}), false, Rgb(1), false), Error);
  EXPECT_FALSE(make_quadric(QuadricType::Disk, -1.0f, 0, 0, 0, 0, 360).quadric);
  EXPECT_FALSE(make_quadric(QuadricType::Disk, 1.0f, 1.5f, 0, 0, 0, 360).quadric);
  EXPECT_FALSE(make_quadric(QuadricType::Cylinder, 1.0f, 0, 0, 1, 1, 360).quadric);
  EXPECT_FALSE(make_quadric(QuadricType::Sphere, 1.0f, 0, 0, 2, 3, 360).quadric);  // above the sphere
  EXPECT_FALSE(make_quadric(QuadricType::Sphere, 1.0f, 0, 0, -1, 1, 0).quadric);
}

}  // namespace
}  // namespace kiln
