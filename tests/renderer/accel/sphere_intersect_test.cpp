#include "renderer/accel/sphere_intersect.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"

namespace kiln {
namespace {

TEST(SphereIntersect, AnalyticRootsAndRange) {
  const Vec3f o(0, 0, -5), d(0, 0, 1), c(0, 0, 0);
  const auto roots = sphere_roots(o, d, c, 1.0f);
  ASSERT_TRUE(roots);
  EXPECT_FLOAT_EQ(roots->t0, 4.0f);
  EXPECT_FLOAT_EQ(roots->t1, 6.0f);
  EXPECT_EQ(intersect_sphere(o, d, c, 1.0f, 0.0f, kInfinity), 4.0f);
  EXPECT_EQ(intersect_sphere(o, d, c, 1.0f, 4.0f, kInfinity), 4.0f) << "tmin is inclusive";
  EXPECT_EQ(intersect_sphere(o, d, c, 1.0f, 4.5f, kInfinity), 6.0f) << "near root before tmin: far root";
  EXPECT_EQ(intersect_sphere(o, d, c, 1.0f, 0.0f, 6.0f), 4.0f);
  EXPECT_FALSE(intersect_sphere(o, d, c, 1.0f, 0.0f, 3.99f)) << "both roots beyond tmax";
  EXPECT_FALSE(intersect_sphere(o, d, c, 1.0f, 6.01f, kInfinity)) << "both roots before tmin";
  // An unnormalised direction scales t.
  EXPECT_FLOAT_EQ(*intersect_sphere(o, Vec3f(0, 0, 2), c, 1.0f, 0.0f, kInfinity), 2.0f);
  // From inside only the far root is ahead.
  EXPECT_FLOAT_EQ(*intersect_sphere(Vec3f(0.5f, 0, 0), Vec3f(1, 0, 0), c, 1.0f, 0.0f, kInfinity), 0.5f);
  EXPECT_FALSE(intersect_sphere(Vec3f(0, 2, -5), d, c, 1.0f, 0.0f, kInfinity));
  EXPECT_FALSE(intersect_sphere(o, Vec3f(0, 0, 0), c, 1.0f, 0.0f, kInfinity)) << "zero direction";
}

// Hit point error measured in ulps of the largest coordinate involved: the only error a float renderer can't avoid.
double hit_error(Vec3f o, Vec3f d, Vec3f c, float r, float t) {
  const double px = double(o.x) + double(d.x) * t - c.x, py = double(o.y) + double(d.y) * t - c.y,
               pz = double(o.z) + double(d.z) * t - c.z;
  return std::abs(std::sqrt(px * px + py * py + pz * pz) - double(r));
}

TEST(SphereIntersect, FarFromOriginCentreIsAccurate) {
  const Vec3f c(148376.0f, 1234.0f, -223423.0f);
  const float ulp = std::nextafter(223423.0f, kInfinity) - 223423.0f;  // 1/64
  Rng rng(7, 0);
  for (float r : {0.5f, 1.0f, 10.0f, 1000.0f}) {
    for (float dist : {2.0f, 100.0f, 1e4f, 1e5f}) {
      for (int i = 0; i < 200; ++i) {
        // Origin dist radii away, aimed at a random point of the sphere facing it.
        const Vec3f dir = sample_uniform_sphere(rng.next_2d());
        const Vec3f o = c + dir * (r * dist);
        Vec3f aim = sample_uniform_sphere(rng.next_2d());
        if (dot(aim, dir) < 0.2f) aim = -aim;
        const Vec3f target = c + aim * (0.9f * r);
        const auto t = intersect_sphere(o, target - o, c, r, 0.0f, kInfinity);
        ASSERT_TRUE(t) << "r=" << r << " dist=" << dist;
        EXPECT_LE(hit_error(o, target - o, c, r, *t), 4.0 * ulp * std::max(1.0f, r * dist / 223423.0f))
            << "r=" << r << " dist=" << dist;
      }
    }
  }
}

TEST(SphereIntersect, DiscriminantSignSurvivesDistance) {
  // The classic b^2 - ac form cancels catastrophically here; the closest-point form keeps the sign right.
  const Vec3f c(148376.0f, 1234.0f, -223423.0f);
  for (float dist : {1e3f, 1e4f, 1e5f}) {
    const Vec3f o = c + Vec3f(0, 0, -dist);
    EXPECT_TRUE(intersect_sphere(o, Vec3f(0.98f, 0, dist), c, 1.0f, 0.0f, kInfinity)) << dist;
    EXPECT_FALSE(intersect_sphere(o, Vec3f(1.02f, 0, dist), c, 1.0f, 0.0f, kInfinity)) << dist;
  }
}

TEST(SphereIntersect, TinyRadii) {
  for (float r = 1e-2f; r >= 1e-12f; r *= 0.1f) {
    for (Vec3f c : {Vec3f(0, 0, 0), Vec3f(1e-3f, -2e-3f, 5e-4f)}) {
      const Vec3f o = c + Vec3f(0, 0, -1);
      const auto hit = intersect_sphere(o, Vec3f(0.5f * r, 0, 1), c, r, 0.0f, kInfinity);
      ASSERT_TRUE(hit) << "r=" << r;
      // t ~ 1 resolves the hit point only to an ulp of 1 along the ray; beyond that it must be exact.
      const double ulp_t = double(std::nextafter(*hit, kInfinity) - *hit);
      EXPECT_LE(hit_error(o, Vec3f(0.5f * r, 0, 1), c, r, *hit), 2.0 * ulp_t + 1e-3 * r) << "r=" << r;
      EXPECT_FALSE(intersect_sphere(o, Vec3f(1.5f * r, 0, 1), c, r, 0.0f, kInfinity)) << "r=" << r;
      // Ray starting at the centre: exit at t = r for a unit direction.
      EXPECT_NEAR(*intersect_sphere(c, Vec3f(0, 1, 0), c, r, 0.0f, kInfinity), r, 1e-6 * r);
    }
  }
}

}  // namespace
}  // namespace kiln
