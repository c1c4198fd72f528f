#include "core/ray.h"

#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"

namespace kiln {
namespace {

// A coordinate with magnitude log-uniform in [1e-8, 1e8] and a random sign; exactly zero now and then.
float log_uniform_coordinate(Rng& rng) {
  const float u = rng.next_float();
  if (u < 0.02f) return 0.0f;
  const float mag = std::pow(10.0f, -8.0f + 16.0f * rng.next_float());
  return rng.next_float() < 0.5f ? -mag : mag;
}

// Normals: mostly random, but also axis-aligned and nearly tangent to a coordinate plane.
Vec3f test_normal(Rng& rng, int k) {
  switch (k % 4) {
    case 0: {
      const int axis = int(rng.next_float() * 3.0f);
      Vec3f n(0.0f);
      n[axis] = rng.next_float() < 0.5f ? -1.0f : 1.0f;
      return n;
    }
    case 1:
      return normalize(Vec3f(1.0f, 1e-4f * (rng.next_float() - 0.5f), 1e-4f * (rng.next_float() - 0.5f)));
    default:
      return sample_uniform_sphere(rng.next_2d());
  }
}

// (o - p) . n in double: how far o lies on n's side of the tangent plane through p.
double signed_offset(Vec3f o, Vec3f p, Vec3f n) {
  return (double(o.x) - p.x) * n.x + (double(o.y) - p.y) * n.y + (double(o.z) - p.z) * n.z;
}

TEST(OffsetRayOrigin, StrictlyOnTheOutgoingSideAtAllScales) {
  Rng rng(31, 0);
  int wrong_side = 0, too_far = 0, not_finite = 0;
  for (int k = 0; k < 400'000; ++k) {
    const Vec3f p(log_uniform_coordinate(rng), log_uniform_coordinate(rng), log_uniform_coordinate(rng));
    const Vec3f n = test_normal(rng, k);
    const Vec3f w = sample_uniform_sphere(rng.next_2d());
    if (dot(n, w) == 0.0f) continue;  // grazing: either side is acceptable
    const Vec3f o = offset_ray_origin(p, n, w);
    if (!is_finite(o)) {
      ++not_finite;
      continue;
    }
    const Vec3f side = dot(n, w) < 0.0f ? -n : n;
    if (!(signed_offset(o, p, side) > 0.0)) {
      if (wrong_side++ < 5)
        ADD_FAILURE() << "p = (" << p.x << ", " << p.y << ", " << p.z << "), n = (" << n.x << ", " << n.y << ", "
                      << n.z << "), offset " << signed_offset(o, p, side);
    }
    // Re-intersection safety must not cost accuracy: each coordinate moves by at most 256 ulps of the point's
    // largest coordinate (<= 2^-15 relative to it) plus the half ulp of rounding the sum.
    const double largest = std::max({std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))});
    for (int a = 0; a < 3; ++a) {
      const double moved = std::abs(double(o[a]) - double(p[a]));
      const double bound = std::max(largest, double(kOffsetMinMagnitude)) * 0x1p-15 + std::abs(double(o[a])) * 0x1p-24;
      if (moved > bound && too_far++ < 5)
        ADD_FAILURE() << "coordinate " << p[a] << " with normal component " << n[a] << " moved by " << moved;
    }
  }
  EXPECT_EQ(wrong_side, 0);
  EXPECT_EQ(too_far, 0);
  EXPECT_EQ(not_finite, 0);
}

TEST(OffsetRayOrigin, FollowsTheLeavingDirection) {
  const Vec3f p(10.0f, -3.0f, 0.5f), n(0.0f, 0.0f, 1.0f);
  EXPECT_GT(offset_ray_origin(p, n, Vec3f(0, 0, 1)).z, p.z);   // reflection: above
  EXPECT_LT(offset_ray_origin(p, n, Vec3f(0, 0, -1)).z, p.z);  // transmission: below
  EXPECT_LT(offset_ray_origin(p, -n, Vec3f(0.3f, 0, -1)).z, p.z);
  // Tiny, zero and negative-zero coordinates, both signs.
  for (float c : {1.0f / 32.0f, 1e-30f, -1e-20f, 0.0f, -0.0f}) {
    const Vec3f q(c, c, c);
    const Vec3f nn = normalize(Vec3f(1, -2, 3));
    EXPECT_GT(signed_offset(offset_ray_origin(q, nn, nn), q, nn), 0.0) << c;
    EXPECT_GT(signed_offset(offset_ray_origin(q, nn, -nn), q, -nn), 0.0) << c;
  }
}

TEST(SpawnRay, DirectionAndShadowEnd) {
  const Vec3f p(1, 2, 3), n(0, 1, 0), w = normalize(Vec3f(1, 1, 0));
  const Ray r = spawn_ray(p, n, w);
  EXPECT_EQ(r.d, w);
  EXPECT_EQ(r.tmin, 0.0f);
  EXPECT_EQ(r.tmax, kInfinity);
  EXPECT_GT(r.o.y, p.y);
  EXPECT_EQ(r.at(2.0f), r.o + w * 2.0f);

  const Vec3f target(4, 6, 3);
  const Ray s = spawn_ray_to(p, n, target);
  EXPECT_GT(s.o.y, p.y);
  // The segment stops a fixed fraction short of the target, so a light or surface there is not self-occluding.
  const Vec3f end = s.at(s.tmax);
  EXPECT_NEAR(length(target - end), (1.0f - kShadowRayEndFraction) * length(target - s.o), 1e-5f);
  EXPECT_LT(length(target - end), length(target - s.o));
  // A target below the surface offsets the origin below it.
  EXPECT_LT(spawn_ray_to(p, n, Vec3f(1, -5, 3)).o.y, p.y);
}

}  // namespace
}  // namespace kiln
